// Hops components: descriptions in Hops' schema, a solve body in the Hops client's wire format
// (tests/service/fixtures/hops_planarize_noisy_grid.json: the shipped noisy grid as a point list
// and a flat face list, branch keys "{0}" and "0", data as strings) run and answered.
#include "gproj/service/hops.h"

#include <gtest/gtest.h>

#include "service/service_test_util.h"

namespace gproj::service {
namespace {

nlohmann::json Fixture() {
  return nlohmann::json::parse(ReadFile(std::string(GPROJ_SOURCE_DIR) +
                                        "/tests/service/fixtures/hops_planarize_noisy_grid.json"));
}

const nlohmann::json* Named(const nlohmann::json& params, const std::string& name) {
  for (const nlohmann::json& p : params)
    if (p.at("Name") == name) return &p;
  return nullptr;
}

TEST(HopsTest, DescriptionHasMeshListsOptionsWithDefaultsAndMeasures) {
  const ProblemSpec& spec = *Registry::Builtin().Find("planarize");
  const nlohmann::json d = HopsDescription(spec);
  EXPECT_EQ(d.at("Uri"), "/hops/planarize");
  const nlohmann::json& inputs = d.at("Inputs");
  const nlohmann::json* points = Named(inputs, "mesh_points");
  ASSERT_TRUE(points);
  EXPECT_EQ(points->at("ParamType"), "Point");
  EXPECT_EQ(points->at("AtLeast"), 1);
  EXPECT_EQ(points->at("AtMost"), 2147483647);
  const nlohmann::json* faces = Named(inputs, "mesh_faces");
  ASSERT_TRUE(faces);
  EXPECT_EQ(faces->at("ParamType"), "Integer");
  const nlohmann::json* reference = Named(inputs, "reference_points");
  ASSERT_TRUE(reference);
  EXPECT_EQ(reference->at("AtLeast"), 0);           // optional
  ASSERT_TRUE(Named(inputs, "reference_corners"));  // a polygon-mesh input
  EXPECT_EQ(Named(inputs, "reference_corners")->at("Default"), 3);
  // planarize takes polygon meshes, but a flat face list means quads unless it says otherwise
  // (Grasshopper definitions that send quads keep working).
  ASSERT_TRUE(Named(inputs, "mesh_corners"));
  EXPECT_EQ(Named(inputs, "mesh_corners")->at("Default"), 4);
  const nlohmann::json* tolerance = Named(inputs, "tolerance");
  ASSERT_TRUE(tolerance);
  EXPECT_EQ(tolerance->at("ParamType"), "Number");
  EXPECT_EQ(tolerance->at("Default").get<double>(), 1e-9);
  EXPECT_FALSE(tolerance->contains("Minimum"));  // > 0 is not an inclusive bound
  const nlohmann::json* angle = Named(inputs, "min_angle");
  ASSERT_TRUE(angle);
  EXPECT_EQ(angle->at("Minimum").get<double>(), 0.0);
  EXPECT_EQ(angle->at("Maximum").get<double>(), 59.9);
  EXPECT_EQ(Named(inputs, "fix_boundary")->at("ParamType"), "Boolean");
  EXPECT_EQ(Named(inputs, "edge_length")->at("ParamType"), "Text");
  const nlohmann::json& outputs = d.at("Outputs");
  ASSERT_TRUE(Named(outputs, "output_points"));
  EXPECT_FALSE(Named(outputs, "output_faces"));  // same connectivity as the input
  ASSERT_TRUE(Named(outputs, "converged"));
  ASSERT_TRUE(Named(outputs, "max_planarity"));
  ASSERT_TRUE(Named(outputs, "report"));
  // Every problem has a component.
  const nlohmann::json list = HopsComponents(Registry::Builtin());
  EXPECT_EQ(list.size(), Registry::Builtin().problems().size());
}

TEST(HopsTest, RecordedShapeSolvesToAPlanarMeshInTheSameOrder) {
  const nlohmann::json body = Fixture();
  const ProblemSpec* spec = HopsProblem(body, Registry::Builtin());
  ASSERT_TRUE(spec);
  EXPECT_EQ(spec->name, "planarize");
  const nlohmann::json request = HopsRunRequest(body, *spec);
  EXPECT_EQ(request.at("inputs").at("fixed"), nlohmann::json({0, 20}));
  EXPECT_EQ(request.at("options").at("tolerance").get<double>(), 1e-9);
  EXPECT_EQ(request.at("options").at("solver"), "gp");
  EXPECT_FALSE(request.at("options").contains("edge_length"));  // an empty tree: the default
  RunRequest run = ParseRunRequest(request, Registry::Builtin(), {});
  RunContext context;
  context.outputs = run.outputs;
  const RunResult result = RunProblem(*run.spec, run.inputs, run.options, context);
  ASSERT_TRUE(result.report.converged) << result.report.termination;
  const nlohmann::json report = RunResultJson(*run.spec, result, run.options, run.inputs, nullptr);
  const nlohmann::json answer = HopsAnswer(*spec, &result, report, "converged", {}, {});
  // One value per output of the description, in its order.
  const nlohmann::json outputs = HopsDescription(*spec).at("Outputs");
  ASSERT_EQ(answer.at("values").size(), outputs.size());
  for (std::size_t i = 0; i < outputs.size(); ++i)
    EXPECT_EQ(answer["values"][i]["ParamName"], outputs[i]["Name"]);
  const nlohmann::json& points = answer["values"][0]["InnerTree"]["0"];
  ASSERT_EQ(points.size(), 441u);
  nlohmann::json mesh = {{"vertices", nlohmann::json::array()},
                         {"faces", request["inputs"]["mesh"]["faces"]}};
  for (const nlohmann::json& item : points) {
    EXPECT_EQ(item.at("type"), "Rhino.Geometry.Point3d");
    const nlohmann::json p = nlohmann::json::parse(item.at("data").get<std::string>());
    mesh["vertices"].push_back({p.at("X"), p.at("Y"), p.at("Z")});
  }
  EXPECT_LT(MaxDiagonalGap(mesh), 1e-7);
  // The fixed corners stay where they were sent.
  for (int v : {0, 20}) EXPECT_EQ(mesh["vertices"][v], request["inputs"]["mesh"]["vertices"][v]);
  const nlohmann::json* converged = nullptr;
  for (const nlohmann::json& value : answer["values"])
    if (value["ParamName"] == "converged") converged = &value;
  ASSERT_TRUE(converged);
  EXPECT_EQ((*converged)["InnerTree"]["0"][0]["data"], "true");
}

TEST(HopsTest, BadTreesNameTheParameter) {
  const ProblemSpec& spec = *Registry::Builtin().Find("planarize");
  auto error = [&](const nlohmann::json& body) {
    try {
      HopsRunRequest(body, spec);
    } catch (const InputError& e) {
      return std::string(e.what());
    }
    return std::string("(accepted)");
  };
  nlohmann::json body = Fixture();
  body["values"][1]["InnerTree"]["{0}"].erase(0);  // 1,599 ids
  EXPECT_NE(error(body).find("mesh_faces: 1599 ids are not a whole number of faces of 4"),
            std::string::npos)
      << error(body);
  body = Fixture();
  body["values"][8]["InnerTree"]["{0}"][0]["data"] = "maybe";
  EXPECT_NE(error(body).find("fix_boundary: expected true or false"), std::string::npos);
  body = Fixture();
  body["values"][5]["InnerTree"]["{1}"] = body["values"][5]["InnerTree"]["{0}"];
  EXPECT_NE(error(body).find("tolerance: has 2 branches"), std::string::npos) << error(body);
  body = Fixture();
  body["values"][0]["InnerTree"]["{0}"][3]["data"] = "{\"X\":1,\"Y\":2}";
  EXPECT_NE(error(body).find("mesh_points[3]: expected a point with finite Z"), std::string::npos)
      << error(body);
  body = Fixture();
  body["values"][10]["InnerTree"]["{0}"] = {{{"type", "System.String"}, {"data", "\"1,x\""}}};
  EXPECT_NE(error(body).find("edge_length"), std::string::npos) << error(body);
  body = Fixture();
  body["values"][6]["ParamName"] = "closenes";  // a definition made for another version
  EXPECT_NE(error(body).find("closenes: gproj planarize has no such input"), std::string::npos)
      << error(body);
  body = Fixture();
  body["values"][6]["ParamName"] = "tolerance";
  EXPECT_NE(error(body).find("tolerance: is given twice"), std::string::npos) << error(body);
  body = Fixture();
  body["values"][0]["InnerTree"]["{0}"][3]["data"] = std::string(200, '[') + std::string(200, ']');
  EXPECT_NE(error(body).find("mesh_points[3]: the data nests deeper than 64 levels"),
            std::string::npos)
      << error(body);
  body = Fixture();
  body["pointer"] = "hops/nothing";
  EXPECT_EQ(HopsProblem(body, Registry::Builtin()), nullptr);
}

}  // namespace
}  // namespace gproj::service
