#include "gproj/problems/marionette/marionette_mesh_problem.h"

#include <gtest/gtest.h>

#include <cmath>

#include "gproj/geometry/mesh/quad_grid.h"
#include "gproj/problems/marionette/marionette_run.h"

namespace gproj::marionette {
namespace {

// The shipped tower plan (12 × 18 faces around the z axis) on cylindrical lines, with radii
// 7.5 on row 0 and column 0: the lift is the cylinder of radius 7.5.
struct Tower {
  Tower() {
    const std::string path =
        std::string(GPROJ_SOURCE_DIR) + "/examples/data/marionette_tower_12x18.obj";
    const PolyMesh mesh = ReadMesh(path, MeshRequirements{true});
    MarionetteProjectionOptions projection;
    projection.type = MarionetteProjection::kCylindrical;
    lines = MakeMarionetteLines(mesh, projection, path);
    std::vector<MarionetteTarget> single;
    for (int j = 0; j <= 18; ++j) single.push_back({j, 7.5});
    for (int i = 1; i <= 12; ++i) single.push_back({i * 19, 7.5});
    prescribed = ResolveMarionetteGuides(mesh, {}, single);
  }
  MarionetteLines lines;
  std::vector<MarionetteTarget> prescribed;
};

TEST(MarionetteMeshProblemTest, GuidedProjectionSolvesTheRowsToRoundOff) {
  const Tower tower;
  MarionetteMeshProblem problem(tower.lines, tower.prescribed, {});
  EXPECT_FALSE(problem.StopsAtTolerance());
  EXPECT_GT(ValueOf(problem.Measure(), "max_relative_det"), 1e-3);  // the plan is not a lift
  int records = 0;
  const RunReport report = problem.Run([&](const RunRecord& r) {
    EXPECT_FALSE(std::isnan(ValueOf(r.measures, "max_relative_det")));
    return ++records > 0;
  });
  EXPECT_TRUE(report.converged) << report.termination;
  EXPECT_EQ(records, report.iterations + 1);
  EXPECT_LE(ValueOf(report.final, "max_relative_det"), 1e-12);
  for (int v = 0; v < tower.lines.num_vertices(); ++v)
    EXPECT_NEAR(problem.Parameters()[v], 7.5, 1e-9) << v;
}

TEST(MarionetteMeshProblemTest, CeresCrossCheckFindsTheSameCylinder) {
  const Tower tower;
  MarionetteMeshProblem problem(tower.lines, tower.prescribed, {});
  const RunReport report = problem.RunCeres(200);
  EXPECT_EQ(report.solver, SolverKind::kCeres);
  EXPECT_FALSE(report.failed) << report.termination;
  EXPECT_LE(ValueOf(report.final, "max_guide_error"), 1e-8);
  EXPECT_LE((problem.Parameters().array() - 7.5).abs().maxCoeff(), 1e-6);
}

TEST(MarionetteMeshProblemTest, OneIterationMissesTheTolerance) {
  const Tower tower;
  MarionetteMeshOptions options;
  options.solver.max_iterations = 1;
  MarionetteMeshProblem problem(tower.lines, tower.prescribed, options);
  const RunReport report = problem.Run();
  EXPECT_FALSE(report.failed);
  EXPECT_FALSE(report.converged);
  EXPECT_GT(ValueOf(report.final, "max_relative_det"), options.tolerance);
}

TEST(MarionetteMeshProblemTest, DirectPropagationIsReportedAsARun) {
  const Tower tower;
  MarionetteMeshProblem problem(tower.lines, tower.prescribed, {});
  const MarionetteMeshLift lift =
      LiftMarionetteMesh(tower.lines, DecomposeIntoPatches(tower.lines.mesh), tower.prescribed);
  const RunReport report =
      problem.RunDirect("propagation", "propagation", [&] { problem.SetParameters(lift.t); });
  EXPECT_TRUE(report.converged);
  EXPECT_EQ(report.iterations, 0);
  EXPECT_GT(ValueOf(report.initial, "max_relative_det"), 1e-3);
  EXPECT_LE(ValueOf(report.final, "max_relative_det"), 1e-12);
  EXPECT_EQ(problem.Parameters(), lift.t);
}

}  // namespace
}  // namespace gproj::marionette
