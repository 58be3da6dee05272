// The service's run requests: inputs read from JSON as the command line reads files (the same
// checks, messages naming the field), limits checked before allocating, results as JSON.
#include "gproj/service/run_request.h"

#include <gtest/gtest.h>

#include "service/service_test_util.h"

namespace gproj::service {
namespace {

nlohmann::json GridRequest() {
  const PolyMesh mesh = ReadMesh(ExamplePath("noisy_grid_21x21.obj"));
  return {{"problem", "planarize"}, {"inputs", {{"mesh", MeshToJson(mesh)}}}};
}

std::string ErrorOf(const nlohmann::json& body, const RequestLimits& limits = {}) {
  try {
    ParseRunRequest(body, Registry::Builtin(), limits);
  } catch (const InputError& e) {
    return e.what();
  }
  return "(accepted)";
}

TEST(RunRequestTest, MeshFromArraysAndFromFileContentsAreTheSame) {
  const RunRequest arrays = ParseRunRequest(GridRequest(), Registry::Builtin(), {});
  nlohmann::json body = GridRequest();
  body["inputs"]["mesh"] = {{"obj", ReadFile(ExamplePath("noisy_grid_21x21.obj"))}};
  const RunRequest text = ParseRunRequest(body, Registry::Builtin(), {});
  const PolyMesh& a = arrays.inputs.Mesh("mesh");
  const PolyMesh& b = text.inputs.Mesh("mesh");
  ASSERT_EQ(a.n_vertices(), 441u);
  ASSERT_EQ(a.n_vertices(), b.n_vertices());
  ASSERT_EQ(a.n_faces(), b.n_faces());
  for (const auto vh : a.vertices()) EXPECT_EQ(a.point(vh), b.point(vh));
  EXPECT_EQ(arrays.spec->name, "planarize");
  EXPECT_TRUE(arrays.outputs.count("output"));
  // Defaults are filled in by the schema.
  EXPECT_EQ(arrays.options.at("tolerance").get<double>(), 1e-9);
}

TEST(RunRequestTest, BadContentNamesTheField) {
  nlohmann::json body = GridRequest();
  body["inputs"]["mesh"]["faces"][7][2] = 100000;
  EXPECT_NE(ErrorOf(body).find("inputs.mesh.faces[7]: vertex 100000 is out of range"),
            std::string::npos)
      << ErrorOf(body);
  body = GridRequest();
  body["inputs"]["mesh"]["vertices"][3] = {1.0, "x", 2.0};
  EXPECT_NE(ErrorOf(body).find("inputs.mesh.vertices[3][1]: expected a number"), std::string::npos)
      << ErrorOf(body);
  body = GridRequest();
  body["problem"] = "anet";  // a quad-mesh input (planarize takes polygon meshes)
  body["inputs"]["mesh"]["faces"][0] = {0, 1, 22};
  EXPECT_NE(ErrorOf(body).find("inputs.mesh"), std::string::npos) << ErrorOf(body);
  EXPECT_NE(ErrorOf(body).find("quad"), std::string::npos) << ErrorOf(body);
  body = GridRequest();
  body["inputs"]["fixed"] = {0, 441};
  EXPECT_NE(ErrorOf(body).find("inputs.fixed[1]: vertex 441 is out of range"), std::string::npos)
      << ErrorOf(body);
  body = GridRequest();
  body["inputs"]["meshh"] = 1;
  EXPECT_NE(ErrorOf(body).find("inputs.meshh: planarize has no such input"), std::string::npos)
      << ErrorOf(body);
  body = GridRequest();
  body["options"] = {{"tolerance", -1}};
  EXPECT_NE(ErrorOf(body).find("tolerance"), std::string::npos) << ErrorOf(body);
  body = GridRequest();
  body["options"] = {{"tolerence", 1e-3}};
  EXPECT_NE(ErrorOf(body).find("tolerance"), std::string::npos) << ErrorOf(body);  // the closest
  body = GridRequest();
  body["problem"] = "planarise";
  EXPECT_NE(ErrorOf(body).find("problem: no problem named \"planarise\" (planarize, "),
            std::string::npos);
  body = GridRequest();
  body["inputs"]["mesh"]["faces"][2][1] = 18446744073709551615ull;
  EXPECT_NE(ErrorOf(body).find("inputs.mesh.faces[2][1]: the integer 18446744073709551615 is out "
                               "of range"),
            std::string::npos)
      << ErrorOf(body);
  body = GridRequest();
  body["outputs"] = {"picture", "nothing"};
  EXPECT_NE(ErrorOf(body).find("outputs[1]: planarize has no output \"nothing\""),
            std::string::npos);
  body = GridRequest();
  body["inputs"]["mesh"] = {{"obj", "v 0 0 0\nv 1 0 0\nv 1 1 0\nf 1 2 9\n"}};
  EXPECT_NE(ErrorOf(body).find("inputs.mesh:4:"), std::string::npos) << ErrorOf(body);
  body = GridRequest();
  body["inputs"]["mesh"] = "/etc/passwd";  // no value names a file on the server
  EXPECT_NE(ErrorOf(body).find("inputs.mesh: expected a mesh"), std::string::npos) << ErrorOf(body);
  EXPECT_NE(ErrorOf(nlohmann::json::array()).find("request: expected a JSON object"),
            std::string::npos);
}

TEST(RunRequestTest, DeepJsonAndInvalidUtf8AreRefusedNotFatal) {
  try {
    ParseRequestJson("{\"problem\": \"planarize\", \"inputs\": {\"mesh\": " +
                     std::string(100000, '[') + std::string(100000, ']') + "}}");
    ADD_FAILURE() << "accepted";
  } catch (const RequestError& e) {
    EXPECT_NE(std::string(e.what()).find("nests deeper than 64 levels"), std::string::npos);
  }
  // Invalid UTF-8 in a body is refused as not JSON; in a message (a path quoted) it is replaced.
  try {
    ParseRequestJson("{\"problem\": \"plan\xff\"}");
    ADD_FAILURE() << "accepted";
  } catch (const RequestError& e) {
    EXPECT_NE(std::string(e.what()).find("ill-formed UTF-8"), std::string::npos) << e.what();
  }
  // A NUL byte ends the JSON reader's input: refused, not read as the end of the body.
  try {
    ParseRequestJson(std::string("{\"problem\": \"planarize\"}\0{\"x\": 1}", 33));
    ADD_FAILURE() << "accepted";
  } catch (const RequestError& e) {
    EXPECT_NE(std::string(e.what()).find("a NUL byte at byte 24"), std::string::npos) << e.what();
  }
  // A number beyond double's range is JSON, but not a number any field can take.
  try {
    ParseRequestJson("{\"problem\": \"planarize\", \"options\": {\"tolerance\": 1e400}}");
    ADD_FAILURE() << "accepted";
  } catch (const RequestError& e) {
    EXPECT_NE(std::string(e.what()).find("number overflow"), std::string::npos) << e.what();
  }
  EXPECT_NE(DumpJson({{"error", "GET /nope\xff: no such endpoint"}}).find("\xef\xbf\xbd"),
            std::string::npos);
  // A generator is a run too: its mesh comes back.
  const RunRequest grid = ParseRunRequest(
      {{"problem", "grid"}, {"options", {{"nu", 5}, {"nv", 4}}}}, Registry::Builtin(), {});
  EXPECT_EQ(grid.spec->name, "grid");
}

TEST(RunRequestTest, SizesAreCheckedAgainstTheLimits) {
  RequestLimits limits;
  limits.max_vertices = 400;
  EXPECT_NE(ErrorOf(GridRequest(), limits)
                .find("inputs.mesh.vertices: has 441 vertices; the service takes at most 400"),
            std::string::npos)
      << ErrorOf(GridRequest(), limits);
  nlohmann::json body = GridRequest();
  body["inputs"]["mesh"] = {{"obj", ReadFile(ExamplePath("noisy_grid_21x21.obj"))}};
  EXPECT_NE(ErrorOf(body, limits).find("has 441 vertices"), std::string::npos);
}

TEST(RunRequestTest, ResultJsonKeepsTheVertexOrder) {
  RunRequest request = ParseRunRequest(GridRequest(), Registry::Builtin(), {});
  RunContext context;
  context.outputs = request.outputs;
  const RunResult result = RunProblem(*request.spec, request.inputs, request.options, context);
  ASSERT_TRUE(result.report.converged) << result.report.termination;
  const nlohmann::json json = ResultJson(*request.spec, result);
  const PolyMesh& out = result.meshes.at("output");
  ASSERT_EQ(json.at("output").at("vertices").size(), out.n_vertices());
  for (const auto vh : out.vertices())
    for (int c = 0; c < 3; ++c)
      EXPECT_EQ(json["output"]["vertices"][vh.idx()][c].get<double>(), out.point(vh)[c]);
  EXPECT_LT(MaxDiagonalGap(json.at("output")), 1e-7);
  EXPECT_EQ(json["output"]["faces"], GridRequest()["inputs"]["mesh"]["faces"]);
}

// A JSON input (darboux's H-net) as an object or as its text: the same skin; anything else is
// refused naming the field, and a broken H-net names the field and key.
TEST(RunRequestTest, JsonInputAsObjectOrText) {
  RunContext context;
  context.outputs = {"output"};
  const RunResult grid =
      RunProblem(*Registry::Builtin().Find("grid"), {},
                 {{"surface", "hyperboloid"}, {"nu", 7}, {"nv", 7}, {"noise", 0.02}}, context);
  const nlohmann::json hnet_body = {{"problem", "hnet"},
                                    {"inputs", {{"mesh", MeshToJson(grid.meshes.at("output"))}}}};
  RunRequest hnet_request = ParseRunRequest(hnet_body, Registry::Builtin(), {});
  context.outputs = hnet_request.outputs;
  const RunResult hnet =
      RunProblem(*hnet_request.spec, hnet_request.inputs, hnet_request.options, context);
  ASSERT_TRUE(hnet.report.converged) << hnet.report.termination;
  const nlohmann::json object = nlohmann::json::parse(hnet.texts.at("output"));
  std::string skins[2];
  for (int k = 0; k < 2; ++k) {
    const nlohmann::json body = {
        {"problem", "darboux"},
        {"inputs", {{"hnet", k == 0 ? object : nlohmann::json(object.dump())}}},
        {"options", {{"centre", {0.0, 0.0, 0.0}}, {"radius", 1.0}}}};
    RunRequest request = ParseRunRequest(body, Registry::Builtin(), {});
    context.outputs = request.outputs;
    const RunResult result = RunProblem(*request.spec, request.inputs, request.options, context);
    ASSERT_TRUE(result.report.converged) << result.report.termination;
    EXPECT_GT(result.facts["measures"]["k_positive_samples"].get<int>(), 0);
    skins[k] = result.texts.at("output");
    const nlohmann::json json = ResultJson(*request.spec, result);
    EXPECT_EQ(json.at("output").at("patches").size(), object["faces"].size());
  }
  EXPECT_EQ(skins[0], skins[1]);
  nlohmann::json body = {{"problem", "darboux"}, {"inputs", {{"hnet", 3}}}};
  EXPECT_NE(ErrorOf(body).find("inputs.hnet: expected a JSON object (or its text), not a number"),
            std::string::npos)
      << ErrorOf(body);
  nlohmann::json broken = object;
  broken["faces"][2] = {0, 1};
  body["inputs"]["hnet"] = broken;
  RunRequest request = ParseRunRequest(body, Registry::Builtin(), {});
  try {
    RunProblem(*request.spec, request.inputs, request.options, context);
    ADD_FAILURE() << "a broken H-net ran";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("inputs.hnet: faces[2]: expected four vertex ids"),
              std::string::npos)
        << e.what();
  }
}

}  // namespace
}  // namespace gproj::service
