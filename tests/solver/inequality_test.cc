#include "gproj/solver/inequality.h"

#include <gtest/gtest.h>

#include <cmath>

#include "constraint_test_util.h"
#include "gproj/solver/ceres_adapter.h"
#include "gproj/solver/guided_projection.h"

namespace gproj {
namespace {

// Points pulled to the origin (soft, weight w) and kept in the half-plane x ≥ 1.
Problem HalfPlaneProblem(const std::vector<Eigen::Vector2d>& start, double w) {
  Problem problem;
  const int points = problem.layout().AddBlock("points", static_cast<int>(start.size()), 2);
  problem.ResizeToLayout();
  for (size_t i = 0; i < start.size(); ++i) problem.x().segment<2>(2 * i) = start[i];
  const VariableLayout& layout = problem.layout();
  auto item = [&](int i) { return std::array<int, 1>{layout.Item(points, i)}; };
  problem
      .AddTerm<2, 2>(
          "to_origin", [](const auto* p, auto* r) { r[0] = p[0], r[1] = p[1]; }, FamilyRole::kSoft,
          w)
      ->AddElements(IndexRange(static_cast<int>(start.size())), item);
  AddInequalities<1, 2>(
      &problem, "half_plane", [](const auto* p, auto* r) { r[0] = p[0] - 1.0; },
      IndexRange(static_cast<int>(start.size())), item);
  return problem;
}

TEST(InequalityTest, SlacksStartAtTheRootOfTheMarginAndRowsAreGMinusSlackSquared) {
  Problem problem = HalfPlaneProblem({{3.0, 0.5}, {0.2, -1.0}}, 0.1);
  const int slack = problem.layout().FindBlock("half_plane_slack");
  ASSERT_GE(slack, 0);
  EXPECT_TRUE(problem.layout().block(slack).eliminable);
  EXPECT_DOUBLE_EQ(problem.x()[problem.layout().Index(slack, 0, 0)], std::sqrt(2.0));
  EXPECT_EQ(problem.x()[problem.layout().Index(slack, 1, 0)], 0.0);  // violated: s = 0
  ConstraintFamily* rows = problem.FindFamily("half_plane");
  ASSERT_NE(rows, nullptr);
  double phi = 0.0, jac[3];
  const double x_local[3] = {0.2, -1.0, 0.5};
  rows->EvaluateElement(1, x_local, &phi, jac);
  EXPECT_DOUBLE_EQ(phi, 0.2 - 1.0 - 0.25);
  EXPECT_EQ(jac[0], 1.0);
  EXPECT_EQ(jac[1], 0.0);
  EXPECT_DOUBLE_EQ(jac[2], -1.0);
  ExpectGradientMatchesFiniteDifferences(*rows, 0, {1.3, 0.4, 0.7});
}

TEST(InequalityTest, GuidedProjectionReachesTheBoundFromInsideAndOutside) {
  Problem problem = HalfPlaneProblem({{3.0, 0.5}, {0.2, -1.0}, {1.0, 2.0}}, 0.1);
  SolverOptions options;
  options.residual_tolerance = 1e-12;
  options.soft_weight_decay = 0.5;
  options.max_iterations = 100;
  const SolverSummary summary = Solve(options, &problem);
  ASSERT_TRUE(summary.converged()) << summary.FullReport();
  EXPECT_EQ(summary.eliminated_variables, 3);  // one slack per point
  for (int i = 0; i < 3; ++i) {
    // Pulled to the origin, every point ends on or inside the bound, never beyond it.
    EXPECT_GE(problem.x()[2 * i], 1.0 - 1e-10) << "point " << i;
    EXPECT_LT(problem.x()[2 * i], 3.0) << "point " << i;
  }
}

TEST(InequalityTest, CeresMinimisesTheSameRows) {
  // With fixed weights the minimiser is p = (1/(1 + w), 0) for a point pulled from outside.
  const double w = 0.25;
  Problem problem = HalfPlaneProblem({{0.2, -1.0}}, w);
  CeresOptions options;
  const CeresSummary summary = SolveWithCeres(options, &problem);
  ASSERT_TRUE(summary.IsSolutionUsable()) << summary.BriefReport();
  EXPECT_NEAR(problem.x()[0], 1.0 / (1.0 + w), 1e-6);
  EXPECT_NEAR(problem.x()[1], 0.0, 1e-6);
}

// Shifted targets (SolverOptions::shifted_constraints) leave the bounds alone: a target shifted
// while the bound was broken would keep pushing after it holds, i.e. tighten it. The start
// breaks x ≥ 1 and is pulled to the origin by a weight that fades, so the bound is active.
TEST(InequalityTest, ShiftedTargetsDoNotTightenABound) {
  Problem problem = HalfPlaneProblem({{0.2, -1.0}}, 1.0);
  SolverOptions options;
  options.shifted_constraints = true;
  options.soft_weight_decay = 0.5;
  options.residual_tolerance = 0.0;
  options.step_tolerance = 0.0;
  options.max_iterations = 60;
  const SolverSummary summary = Solve(options, &problem);
  EXPECT_TRUE(summary.usable) << summary.FullReport();
  EXPECT_NEAR(problem.x()[0], 1.0, 1e-6) << summary.FullReport();
  EXPECT_NEAR(problem.x()[1], 0.0, 1e-6);
}

}  // namespace
}  // namespace gproj
