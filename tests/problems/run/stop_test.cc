// Every registered run that iterates stops at the record its callback returns false for (the
// Python callback's False, Ctrl-C): no record after it, no later stage, status USER_ABORT and
// converged false — at its first record, midway, and at its very last, where a tolerance met
// must not turn the stop into CONVERGENCE.
#include <gtest/gtest.h>

#include <cmath>

#include "gproj/geometry/io/text_input.h"
#include "gproj/geometry/mesh/parametric_grid.h"
#include "gproj/geometry/mesh/quad_grid.h"
#include "gproj/geometry/surface/bspline_surface.h"
#include "stop_test_util.h"

namespace gproj {
namespace {

const std::string kData = std::string(GPROJ_SOURCE_DIR) + "/examples/data/";

RunInputs MeshInput(const PolyMesh& mesh, const std::string& name = "mesh") {
  RunInputs inputs;
  inputs.meshes[name] = mesh;
  inputs.sources[name] = name;
  return inputs;
}

RunInputs CurveInput(const std::string& file) {
  RunInputs inputs;
  inputs.curves["curve"] = ReadPoints(kData + file);
  inputs.sources["curve"] = file;
  return inputs;
}

RunInputs SurfaceInput(const BSplineSurface& surface) {
  RunInputs inputs;
  inputs.surfaces["surface"] = surface;
  inputs.sources["surface"] = "surface";
  return inputs;
}

PolyMesh NoisyGrid(int n) {
  QuadGridOptions grid;
  grid.nu = grid.nv = n;
  grid.noise = 0.05;
  return MakeQuadGrid(grid);
}

PolyMesh AsymptoticGrid(const std::string& surface, int n, double jitter) {
  ParametricGridOptions o;
  o.nu = o.nv = n;
  o.jitter = jitter;
  o.seed = 4;
  return MakeParametricGrid(AsymptoticSurface(surface), o);
}

std::vector<double> Values(int n, double (*f)(int)) {
  std::vector<double> v;
  for (int i = 0; i < n; ++i) v.push_back(f(i));
  return v;
}

struct StopCase {
  std::string name;  // the test's name
  std::string problem;
  RunInputs inputs;
  nlohmann::json options;
};

std::vector<StopCase> Cases() {
  const PolyMesh revolution = ReadMesh(kData + "revolution_13x17.obj");
  const std::vector<double> row_lengths =
      Values(16, [](int j) { return 0.09 + 0.05 * std::sin(j / 5.0); });
  const nlohmann::json canal = {{"first_point", {-0.5, 0.5, 2}}, {"length", 2}, {"smooth", true}};
  const nlohmann::json marionette = {
      {"row", Values(21, [](int j) { return 0.4 * std::sin(j / 4.0); })},
      {"column", Values(21, [](int i) { return 0.3 * (1 - std::cos(i / 5.0)); })},
      {"solver", "gp"}};
  return {
      {"planarize", "planarize", MeshInput(NoisyGrid(9)), {}},
      {"planarize_ceres", "planarize", MeshInput(NoisyGrid(9)), {{"solver", "ceres"}}},
      {"anet", "anet", MeshInput(AsymptoticGrid("enneper", 11, 0.03)), {}},
      {"hnet", "hnet", MeshInput(AsymptoticGrid("hypar", 15, 0.1)), {}},
      {"hnet_ceres", "hnet", MeshInput(AsymptoticGrid("hypar", 7, 0.03)), {{"solver", "ceres"}}},
      {"cyclidic", "cyclidic", MeshInput(revolution), {{"segments", 2}}},
      {"combescure",
       "combescure",
       MeshInput(revolution),
       {{"row_lengths", row_lengths}, {"solver", "gp"}}},
      {"combescure_ceres",
       "combescure",
       MeshInput(revolution),
       {{"row_lengths", row_lengths}, {"solver", "ceres"}}},
      {"canal", "canal", CurveInput("canal_curve.txt"), canal},
      {"weingarten", "weingarten", SurfaceInput(MakeWavyBSpline(8, 8, 3)), {}},
      {"weingarten_levels",
       "weingarten",
       SurfaceInput(MakeWavyBSpline(6, 6, 3)),
       {{"refine", 1}, {"max_iterations", 3}}},
      {"marionette", "marionette", MeshInput(ReadMesh(kData + "marionette_plan_21x21.obj"), "plan"),
       marionette},
  };
}

// A failure names the case, not its bytes.
void PrintTo(const StopCase& c, std::ostream* out) { *out << c.name; }

class StopTest : public ::testing::TestWithParam<StopCase> {};

TEST_P(StopTest, StopsAtTheRecordItsCallbackRefuses) {
  const StopCase& c = GetParam();
  StopCount count;
  const RunResult unstopped = RunStoppedAt(c.problem, c.inputs, c.options, 0, &count);
  ASSERT_FALSE(unstopped.report.failed) << unstopped.report.termination;
  const int n = count.records;
  ASSERT_GE(n, 2) << "a run that iterates records its iterates";
  for (int stop_at : {1, (n + 1) / 2, n}) {
    const RunResult r = RunStoppedAt(c.problem, c.inputs, c.options, stop_at, &count);
    EXPECT_EQ(StatusOf(r.report), RunStatus::kUserAbort)
        << "stopped at record " << stop_at << " of " << n << ": " << r.report.termination;
    EXPECT_FALSE(r.report.converged) << stop_at;
    EXPECT_FALSE(r.report.failed) << stop_at << ": " << r.report.termination;
    EXPECT_EQ(count.records, stop_at) << "the run went on past the stop";
    EXPECT_EQ(count.after_stop, 0) << stop_at;
    // The result is the last iterate, written as an unstopped run writes it (an H-net stopped in
    // its A-net step has none yet).
    if (c.problem != "hnet" || !r.facts["rounds"].empty()) {
      EXPECT_EQ(r.meshes.count("output") + r.texts.count("output"), 1u) << stop_at;
    }
  }
}

INSTANTIATE_TEST_SUITE_P(Problems, StopTest, ::testing::ValuesIn(Cases()),
                         [](const ::testing::TestParamInfo<StopCase>& info) {
                           return info.param.name;
                         });

// Paneling is a stage of its own after the optimisation (seconds on the shipped 10 x 10
// paneling): a run stopped before it skips it rather than panel on.
TEST(WeingartenStopTest, AStoppedRunSkipsThePaneling) {
  const RunInputs inputs = SurfaceInput(MakeWavyBSpline(8, 8, 3));
  const nlohmann::json options = {{"panels", {3, 3}}};
  const std::set<std::string> outputs = {"output", "panel_picture", "seam_histograms"};
  StopCount count;
  const RunResult unstopped = RunStoppedAt("weingarten", inputs, options, 0, &count, outputs);
  ASSERT_TRUE(unstopped.facts.contains("panels"));
  EXPECT_EQ(unstopped.texts.count("panel_picture"), 1u);
  const RunResult r = RunStoppedAt("weingarten", inputs, options, 2, &count, outputs);
  EXPECT_EQ(StatusOf(r.report), RunStatus::kUserAbort) << r.report.termination;
  EXPECT_EQ(count.after_stop, 0);
  EXPECT_FALSE(r.facts.contains("panels"));
  EXPECT_EQ(r.texts.count("panel_picture"), 0u);
  EXPECT_EQ(r.texts.count("output"), 1u);  // the B-spline of the last iterate
}

// Runs without iterations (constructions) have no record to refuse: they call no callback.
TEST(StopTest, ConstructionsCallNoCallback) {
  const PolyMesh revolution = ReadMesh(kData + "revolution_13x17.obj");
  StopCount count;
  const RunResult r = RunStoppedAt(
      "invert", MeshInput(revolution),
      {{"m_revolution", {{2, 0, 1}, {0, 2, 1}, {-2, 0, 1}, {0, -2, 1}}}, {"t", 0.6}}, 1, &count);
  EXPECT_EQ(count.records, 0);
  EXPECT_EQ(StatusOf(r.report), RunStatus::kDirect) << r.report.termination;
}

}  // namespace
}  // namespace gproj
