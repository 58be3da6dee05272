#include "gproj/problems/marionette/marionette_grid_problem.h"

#include <gtest/gtest.h>

#include <cmath>
#include <limits>

#include "gproj/geometry/mesh/quad_grid.h"
#include "gproj/problems/marionette/marionette_run.h"

namespace gproj::marionette {
namespace {

// A jittered 6 × 5-face grid plan.
PolyMesh PlanMesh() {
  QuadGridOptions o;
  o.nu = 7;
  o.nv = 6;
  o.noise = 0.15;
  o.seed = 5;
  return MakeQuadGrid(o);
}

Eigen::VectorXd Curve(int size, double phase) {
  Eigen::VectorXd v(size);
  for (int k = 0; k < size; ++k) v[k] = 0.4 * std::sin(0.8 * k + phase) + 0.05 * k;
  return v;
}

// The lift from curves of the right sizes sharing vertex 0's height.
MarionetteGridProblem Lift(const MarionetteOptions& options = {}) {
  Eigen::VectorXd row = Curve(6, 0.0), column = Curve(7, 1.0);
  column[0] = row[0];
  return MarionetteGridProblem(PlanMesh(), "plan.obj", row, column, Eigen::VectorXd(), options);
}

TEST(MarionetteGridProblemTest, GuidedProjectionReachesTheDirectLiftInOneIteration) {
  MarionetteGridProblem gp = Lift(), direct = Lift();
  const RunReport report = gp.Run();
  EXPECT_TRUE(report.converged);
  EXPECT_FALSE(report.failed);
  EXPECT_EQ(report.iterations, 1);
  EXPECT_GT(ValueOf(report.initial, "max_guide_error"), 0.1);  // x starts at 0
  EXPECT_LE(ValueOf(report.final, "max_guide_error"), 1e-12);
  EXPECT_LE(ValueOf(report.final, "max_planarity"), 1e-12);
  const RunReport d =
      direct.RunDirect("propagation", "direct", [&] { direct.SetHeights(direct.DirectHeights()); });
  EXPECT_EQ(d.solver, SolverKind::kDirect);
  EXPECT_EQ(d.method, "propagation");
  EXPECT_EQ(d.iterations, 0);
  EXPECT_TRUE(d.converged);
  EXPECT_LE((gp.problem().x() - direct.problem().x()).lpNorm<Eigen::Infinity>(), 1e-10);
}

TEST(MarionetteGridProblemTest, CeresCrossCheckSolvesTheSameRows) {
  MarionetteGridProblem ceres = Lift(), direct = Lift();
  const RunReport report = ceres.RunCeres(50);
  EXPECT_EQ(report.solver, SolverKind::kCeres);
  EXPECT_TRUE(report.converged) << report.termination;
  EXPECT_LE((ceres.problem().x() - direct.DirectHeights()).lpNorm<Eigen::Infinity>(), 1e-8);
}

TEST(MarionetteGridProblemTest, MissedToleranceAndNonFiniteHeightsAreReported) {
  MarionetteOptions strict;
  strict.tolerance = 1e-300;  // below the round-off of any lift
  MarionetteGridProblem lift = Lift(strict);
  const RunReport missed =
      lift.RunDirect("propagation", "direct", [&] { lift.SetHeights(lift.DirectHeights()); });
  EXPECT_FALSE(missed.converged);
  EXPECT_FALSE(missed.failed);
  EXPECT_GT(ValueOf(missed.final, "max_planarity"), 0.0);

  MarionetteGridProblem broken = Lift();
  const RunReport failed = broken.RunDirect("propagation", "direct", [&] {
    broken.SetHeights(Eigen::VectorXd::Constant(42, std::numeric_limits<double>::quiet_NaN()));
  });
  EXPECT_TRUE(failed.failed);
  EXPECT_FALSE(failed.converged);
  EXPECT_TRUE(failed.final.empty());
}

TEST(MarionetteGridProblemTest, FitIsTheConstrainedLeastSquaresSolutionAndPlanarToRounding) {
  const PolyMesh mesh = PlanMesh();
  Eigen::VectorXd target(mesh.n_vertices());
  for (auto v : mesh.vertices()) target[v.idx()] = std::sin(3 * mesh.point(v)[0]);
  // One solve is planar only up to the weight ratio of its rows (about 1e-7); the shifted
  // constraint targets of the following solves make the planarity rows hold exactly.
  MarionetteOptions options;
  options.tolerance = 1e-12;
  MarionetteGridProblem fit(mesh, "", Eigen::VectorXd(), Eigen::VectorXd(), target, options);
  EXPECT_FALSE(fit.StopsAtTolerance());
  const RunReport report = fit.Run();
  EXPECT_EQ(report.iterations, 3);
  EXPECT_TRUE(report.converged) << ValueOf(report.final, "max_planarity");
  EXPECT_LE(ValueOf(report.final, "max_planarity"), 1e-12);
  EXPECT_GT(ValueOf(report.final, "rms_distance_to_target"), 0.01);
  const Eigen::VectorXd direct = fit.DirectHeights();
  const double range = direct.maxCoeff() - direct.minCoeff();
  EXPECT_LE((fit.problem().x() - direct).lpNorm<Eigen::Infinity>(), 1e-9 * range);
  // Its first solve alone is off by the weight ratio.
  EXPECT_GT(ValueOf(report.history[1].measures, "max_planarity"), 1e-10);
}

TEST(MarionetteGridProblemTest, RefusesGuideCurvesThatDoNotFit) {
  EXPECT_THROW(
      MarionetteGridProblem(PlanMesh(), "", Curve(6, 0), Curve(7, 1), Eigen::VectorXd(), {}),
      InputError);  // vertex 0 gets two heights
}

}  // namespace
}  // namespace gproj::marionette
