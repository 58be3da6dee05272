// Valid panels on generated inputs whose grid lines are not conjugate (issue: results that hold
// on inputs nobody tuned for): planar to the tolerance with no new non-convex quad and little
// motion, and a clear failure where no valid planar mesh is near.
#include <gtest/gtest.h>

#include <algorithm>

#include "geometry/quad_grid.h"
#include "geometry/quad_shape.h"
#include "problems/pq_planarization.h"

namespace gproj {
namespace {

QuadGridOptions Twisted(int n) {  // z = 0.3 x² + 0.2 y² + 0.3 x y
  QuadGridOptions g;
  g.nu = g.nv = n;
  g.c = 0.3;
  g.noise = 0.05;
  return g;
}

QuadGridOptions Wave(int n) {  // z = 0.3 x² + 0.2 y² + 0.05 sin(πx) sin(πy)
  QuadGridOptions g;
  g.nu = g.nv = n;
  g.wave = 0.05;
  g.noise = 0.05;
  return g;
}

// Without noise: a smooth grid that is not conjugate. A floor under the fading soft weights
// held it at max planarity 8e-9 against the default tolerance 1e-9.
QuadGridOptions SmoothWave(int n) {
  QuadGridOptions g = Wave(n);
  g.noise = 0.0;
  return g;
}

struct ValidityCase {
  const char* name;
  QuadGridOptions grid;
};

class NonConjugateGridTest : public ::testing::TestWithParam<ValidityCase> {};

TEST_P(NonConjugateGridTest, PlanarWithNoNewNonConvexQuadAndLittleMotion) {
  const PolyMesh mesh = MakeQuadGrid(GetParam().grid);
  const QuadShapeSummary before = Summarize(MeasureQuadShapes(mesh));
  ASSERT_EQ(before.non_convex, 0);
  PQPlanarization pq(mesh, PQPlanarizationOptions());
  const RunReport report = pq.Run();
  ASSERT_TRUE(report.converged) << report.termination;
  const PolyMesh result = pq.Result();
  const PlanarityMeasures m = MeasurePlanarity(result, mesh);
  EXPECT_LE(m.max_planarity, 1e-6);
  EXPECT_EQ(m.shape.non_convex, 0);
  EXPECT_GE(m.shape.min_angle_deg, 5.0);
  EXPECT_LE(m.max_displacement, 0.02);
  EXPECT_EQ(ValueOf(report.final, "non_convex_quads"), 0.0);
  // The input really is far from conjugate: the quads had to change shape.
  EXPECT_GT(CompareCornerAngles(mesh, result).max_corner_change_deg, 10.0);
}

INSTANTIATE_TEST_SUITE_P(Generated, NonConjugateGridTest,
                         ::testing::Values(ValidityCase{"Twisted41", Twisted(41)},
                                           ValidityCase{"Wave41", Wave(41)},
                                           ValidityCase{"SmoothWave41", SmoothWave(41)},
                                           ValidityCase{"Twisted81", Twisted(81)},
                                           ValidityCase{"Wave81", Wave(81)}),
                         [](const auto& info) { return std::string(info.param.name); });

TEST(PQPlanarizationValidityTest, WithoutTheBoundsTheSameGridFolds) {
  // What the bounds prevent: a closeness-dominated solve without them folds quads.
  const PolyMesh mesh = MakeQuadGrid(Twisted(41));
  PQPlanarizationOptions options;
  options.solver.fairness_weight = 0.0;
  options.panels.AllowFolds();
  PQPlanarization pq(mesh, options);
  ASSERT_TRUE(pq.Run().converged);
  EXPECT_GT(pq.Measures().shape.non_convex, 5);
}

TEST(PQPlanarizationValidityTest, EnergyNeverRisesFromOneIterationToTheNext) {
  // Each record's energy uses that iteration's weights, which only fade; a monotone step lowers
  // the energy with the weights it was taken with, so the history cannot rise. Plain
  // Gauss–Newton steps on the same input (the old defaults) jump.
  const PolyMesh mesh = MakeQuadGrid(Twisted(41));
  auto max_rise = [&](const PQPlanarizationOptions& options) {
    PQPlanarization pq(mesh, options);
    const RunReport report = pq.Run();
    double rise = 0.0;
    for (size_t k = 1; k < report.history.size(); ++k)
      rise = std::max(rise, report.history[k].energy / report.history[k - 1].energy);
    return rise;
  };
  EXPECT_LE(max_rise(PQPlanarizationOptions()), 1.0);
  PQPlanarizationOptions plain;
  plain.solver.monotone = false;
  plain.closeness_weight = 1.0;
  plain.panels.AllowFolds();
  EXPECT_GT(max_rise(plain), 2.0);
}

TEST(PQPlanarizationValidityTest, DefaultMovesLittleMoreThanAClosenessDominatedSolve) {
  QuadGridOptions grid;  // a noisy paraboloid grid: conjugate up to the noise
  grid.nu = grid.nv = 41;
  grid.noise = 0.05;
  const PolyMesh mesh = MakeQuadGrid(grid);
  PQPlanarization by_default(mesh, PQPlanarizationOptions());
  ASSERT_TRUE(by_default.Run().converged);
  PQPlanarizationOptions closeness;
  closeness.solver.fairness_weight = 0.0;
  closeness.closeness_weight = 100.0;
  closeness.panels.AllowFolds();
  PQPlanarization dominated(mesh, closeness);
  ASSERT_TRUE(dominated.Run().converged);
  EXPECT_LE(by_default.Measures().max_displacement, 1.5 * dominated.Measures().max_displacement);
}

TEST(PQPlanarizationValidityTest, NoValidPlanarMeshNearbyEndsUnconvergedWithoutFolding) {
  // z = 0.1 sin(πx) sin(πy): at the saddles the grid lines are asymptotic, where planar quads
  // must degenerate. The run must not fold its way to the tolerance.
  QuadGridOptions grid;
  grid.nu = grid.nv = 41;
  grid.a = grid.b = 0.0;
  grid.wave = 0.1;
  grid.noise = 0.05;
  const PolyMesh mesh = MakeQuadGrid(grid);
  PQPlanarization pq(mesh, PQPlanarizationOptions());
  const RunReport report = pq.Run();
  EXPECT_FALSE(report.converged);
  EXPECT_FALSE(report.failed);
  EXPECT_EQ(pq.Measures().shape.non_convex, 0);
  const std::vector<int> above = pq.FacesAboveTolerance();
  ASSERT_FALSE(above.empty());
  EXPECT_LT(above.size(), mesh.n_faces());
}

}  // namespace
}  // namespace gproj
