// The MeshProblem base, and what adding a mesh problem costs: one class on the base and one
// registration, no front-end code. The problem (every vertex onto the plane through the input's
// centre, with the base's bounds, held vertices and result) is registered in a registry of its
// own and run through the one run protocol, as the command line and Python run the built-in
// ones; its schema, report options and option errors come from the registration.
#include "gproj/problems/mesh/mesh_problem.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>

#include "gproj/geometry/mesh/quad_grid.h"
#include "gproj/problems/run/registry.h"
#include "gproj/solver/term.h"

namespace gproj {
namespace {

// ---- the problem (what a library file holds) ----
struct FlattenOptions {
  double tolerance = 1e-9;
  VertexControlOptions vertices;
};

struct OnMeanPlane {
  template <typename T>
  void operator()(const T* p, T* r) const {
    r[0] = p[2];
  }
};

class Flatten : public MeshProblem {
 public:
  Flatten(const PolyMesh& mesh, const FlattenOptions& options)
      : MeshProblem(mesh), tolerance_(options.tolerance) {
    LoadInputVertices();
    auto* plane = problem_.AddTerm<1, 3>("on_plane", OnMeanPlane{});
    for (auto v : mesh.vertices()) plane->Add({vertices()[v]});
    AddBoundsAndControl(PanelBoundsOptions{}, options.vertices);
  }
  SolverOptions solver_options() const override {
    SolverOptions s;
    s.fairness_weight = 0.0;
    return s;
  }
  CeresOptions ceres_options(int max_iterations) const override {
    return CeresOptionsFor(solver_options(), max_iterations, 1.0);
  }
  NamedValues MeasureAt(const Eigen::VectorXd& x) const override {
    const PolyMesh& mesh = MeshAt(x);
    double worst = 0.0;
    for (auto v : mesh.vertices())
      if (!std::binary_search(control_.held.begin(), control_.held.end(), v.idx()))
        worst = std::max(worst, std::abs(mesh.point(v)[2] - norm_.center.z()));
    return {{"max_height", worst}};
  }
  bool MeetsTolerance(const NamedValues& m) const override {
    return ValueOf(m, "max_height") <= tolerance_;
  }
  BlockItems items() const { return vertices(); }
  double height() const { return norm_.center.z(); }

 private:
  double tolerance_;
};

// ---- its registration (what the problem's *_problem.cc holds) ----
const OptionSchema<FlattenOptions>& Schema() {
  static const OptionSchema<FlattenOptions> schema = [] {
    OptionSchema<FlattenOptions> s;
    s.Field<double>("tolerance", OptionType::kNumber,
                    "Converged when every free vertex is this "
                    "close to the plane",
                    [](FlattenOptions& o) -> double& { return o.tolerance; })
        .Positive();
    return s;
  }();
  return schema;
}

ProblemSpec FlattenSpec() {
  ProblemSpec spec;
  spec.name = "flatten";
  spec.summary = "Every vertex onto the plane through the input's centre.";
  spec.inputs = {{"mesh", InputKind::kMesh, "The mesh to flatten", true},
                 {"fixed", InputKind::kVertexIds, "Vertices that do not move"}};
  spec.outputs = {{"output", OutputKind::kMesh, "the flat mesh", true, true}};
  spec.options = Schema().specs();
  spec.log_measures = {"max_height"};
  spec.run = [](const RunInputs& inputs, const nlohmann::json& values, const RunContext& context) {
    FlattenOptions options = Schema().Apply(values);
    options.vertices.fixed = inputs.VertexIds("fixed");
    Flatten flatten(inputs.Mesh("mesh"), options);
    RunResult result;
    result.report = flatten.Run([&](const RunRecord& r) { return context.Record(r); });
    result.tolerance_measure = "max_height";
    result.tolerance = options.tolerance;
    if (!result.report.failed) result.meshes["output"] = flatten.Result();
    return result;
  };
  return spec;
}
// ---- end of what the problem costs ----

PolyMesh Paraboloid() {
  QuadGridOptions g;
  g.nu = g.nv = 9;
  g.noise = 0.02;
  return MakeQuadGrid(g);
}

TEST(MeshProblemTest, ItemsByIndexAndHandleAreTheVertexBlocksFirstItems) {
  const PolyMesh mesh = Paraboloid();
  Flatten flatten(mesh, FlattenOptions{});
  const BlockItems items = flatten.items();
  EXPECT_EQ(items.size(), static_cast<int>(mesh.n_vertices()));
  EXPECT_EQ(flatten.problem().layout().block(0).name, "vertices");
  for (int v : {0, 7, 80}) {
    EXPECT_EQ(items[v], flatten.problem().layout().Item(0, v));
    EXPECT_EQ(items[mesh.vertex_handle(v)], items[v]);
  }
  EXPECT_EQ(items(3, 5), (std::array<int, 2>{items[3], items[5]}));
}

TEST(MeshProblemTest, ResultIsInInputUnitsWithHeldVerticesExact) {
  const PolyMesh mesh = Paraboloid();
  FlattenOptions options;
  options.vertices.fixed = {0, 40};
  Flatten flatten(mesh, options);
  const RunReport report = flatten.Run();
  ASSERT_TRUE(report.converged) << report.termination;
  const PolyMesh out = flatten.Result();
  ASSERT_EQ(out.n_vertices(), mesh.n_vertices());
  for (auto v : out.vertices()) {
    if (v.idx() == 0 || v.idx() == 40) {
      EXPECT_EQ(out.point(v), mesh.point(v)) << v.idx();  // bit for bit
    } else {
      EXPECT_NEAR(out.point(v)[2], flatten.height(), 1e-9) << v.idx();
    }
  }
  EXPECT_TRUE(flatten.FacesAtAngleBound().empty());
  EXPECT_EQ(flatten.input().point(mesh.vertex_handle(3)), mesh.point(mesh.vertex_handle(3)));
}

TEST(MeshProblemTest, OneClassAndOneRegistrationRunThroughTheRunProtocol) {
  Registry registry;
  registry.Add(FlattenSpec());
  const ProblemSpec& spec = *registry.Find("flatten");
  // The schema every front end is generated from: the option, its default and its range.
  const nlohmann::json schema = registry.SchemaJson();
  ASSERT_EQ(schema["problems"].size(), 1u);
  const nlohmann::json& option = schema["problems"][0]["options"][0];
  EXPECT_EQ(option["name"], "tolerance");
  EXPECT_EQ(option["default"].get<double>(), 1e-9);

  const PolyMesh mesh = Paraboloid();
  RunInputs inputs;
  inputs.meshes["mesh"] = mesh;
  inputs.vertex_ids["fixed"] = {0};
  inputs.sources["mesh"] = "paraboloid";
  int records = 0;
  RunContext context;
  context.on_record = [&records](const RunRecord&) { return ++records, true; };
  context.outputs = {"output"};
  const RunResult result = RunProblem(spec, inputs, {{"tolerance", 1e-8}}, context);
  ASSERT_TRUE(result.report.converged) << result.report.termination;
  EXPECT_EQ(records, static_cast<int>(result.report.history.size()));
  const PolyMesh& flat = result.meshes.at("output");
  double centre = 0.0;
  for (auto v : mesh.vertices()) centre += mesh.point(v)[2] / mesh.n_vertices();
  for (auto v : flat.vertices()) {
    if (v.idx() == 0) {
      EXPECT_EQ(flat.point(v), mesh.point(v));  // held bit for bit
      continue;
    }
    EXPECT_NEAR(flat.point(v)[2], centre, 1e-8) << v.idx();
  }
  // The report names the complete options as the schema does.
  const nlohmann::json report = RunResultJson(spec, result, {{"tolerance", 1e-8}}, inputs, nullptr);
  EXPECT_EQ(report["options"]["tolerance"].get<double>(), 1e-8);
  EXPECT_TRUE(report["converged"].get<bool>());
  // A bad option is refused by name before anything runs.
  EXPECT_THROW(RunProblem(spec, inputs, {{"tolerance", -1.0}}, context), InputError);
  EXPECT_THROW(RunProblem(spec, inputs, {{"tolerence", 1.0}}, context), InputError);
}

}  // namespace
}  // namespace gproj
