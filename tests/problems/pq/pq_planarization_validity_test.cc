// Valid panels on generated inputs whose grid lines are not conjugate (issue: results that hold
// on inputs nobody tuned for): planar to the tolerance with no new non-convex quad and little
// motion, and a clear failure where no valid planar mesh is near.
#include <gtest/gtest.h>

#include <algorithm>

#include "gproj/geometry/mesh/circle.h"
#include "gproj/geometry/mesh/quad_grid.h"
#include "gproj/geometry/mesh/quad_shape.h"
#include "gproj/problems/pq/pq_planarization.h"

namespace gproj::pq {
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

// Shortest edge of `result` over its length in `input` (one connectivity).
double ShortestEdgeRatio(const PolyMesh& input, const PolyMesh& result) {
  double ratio = HUGE_VAL;
  for (auto e : input.edges()) {
    const auto h = input.halfedge_handle(e, 0);
    const auto a = input.from_vertex_handle(h), b = input.to_vertex_handle(h);
    ratio = std::min(ratio, (result.point(b) - result.point(a)).norm() /
                                (input.point(b) - input.point(a)).norm());
  }
  return ratio;
}

// --circular on a grid that is not a circular net (principal directions of the paraboloid
// bent by the wave): circular to the tolerance with no collapsed edge and no bow-tie.
TEST(PQPlanarizationValidityTest, CircularOnANonCircularGridKeepsEdgesAndConvexity) {
  const PolyMesh mesh = MakeQuadGrid(Wave(41));
  PQPlanarizationOptions options;
  options.circular = true;
  PQPlanarization pq(mesh, options);
  const RunReport report = pq.Run();
  ASSERT_TRUE(report.converged) << report.termination;
  const PolyMesh result = pq.Result();
  EXPECT_LE(MeasureCircularity(result).max_concyclicity, 1e-9);
  EXPECT_EQ(pq.Measures().shape.non_convex, 0);
  EXPECT_GE(pq.Measures().shape.min_angle_deg, 5.0);
  EXPECT_GE(ShortestEdgeRatio(mesh, result), 0.1 * (1.0 - 1e-6));
  EXPECT_GT(CompareCornerAngles(mesh, result).max_corner_change_deg, 10.0);  // it had to work
}

// An input with folded quads: those are only kept from getting worse, and no quad that was
// convex comes out non-convex (without bounds such runs multiplied the folds).
TEST(PQPlanarizationValidityTest, AnAlreadyFoldedInputGetsNoNewFold) {
  QuadGridOptions grid;
  grid.nu = grid.nv = 21;
  grid.noise = 0.05;
  PolyMesh mesh = MakeQuadGrid(grid);
  for (int v : {5 * 21 + 5, 12 * 21 + 8, 15 * 21 + 15}) {  // pushed past a diagonal neighbour
    const auto h = mesh.vertex_handle(v);
    const auto across = mesh.vertex_handle(v + 21 + 1);
    mesh.set_point(h, mesh.point(h) + 1.3 * (mesh.point(across) - mesh.point(h)));
  }
  const std::vector<QuadShape> before = MeasureQuadShapes(mesh);
  const int folded = Summarize(before).non_convex;
  ASSERT_GE(folded, 3);
  PQPlanarization pq(mesh, PQPlanarizationOptions());
  pq.Run();
  const std::vector<QuadShape> after = MeasureQuadShapes(pq.Result());
  ASSERT_EQ(after.size(), before.size());
  for (size_t f = 0; f < before.size(); ++f) {
    if (!before[f].convex) continue;
    EXPECT_TRUE(after[f].convex) << "face " << f;
  }
  EXPECT_LE(Summarize(after).non_convex, folded);
}

// z = 0.1 sin(πx) sin(πy): at the saddles the grid lines are asymptotic, where planar quads
// must degenerate; with an edge bound of |e|² (flat at zero length) edges collapsed there and
// the run stalled. The bound along the input direction keeps them at a tenth of their length,
// and the run reaches the tolerance with every quad convex.
TEST(PQPlanarizationValidityTest, ASaddleGridIsPlanarisedWithShortEdgesHeldAtTheirBound) {
  QuadGridOptions grid;
  grid.nu = grid.nv = 41;
  grid.a = grid.b = 0.0;
  grid.wave = 0.1;
  grid.noise = 0.05;
  const PolyMesh mesh = MakeQuadGrid(grid);
  PQPlanarization pq(mesh, PQPlanarizationOptions());
  const RunReport report = pq.Run();
  ASSERT_TRUE(report.converged) << report.termination;
  const PolyMesh result = pq.Result();
  EXPECT_EQ(pq.Measures().shape.non_convex, 0);
  EXPECT_GE(ShortestEdgeRatio(mesh, result), 0.1 * (1.0 - 1e-6));
  const std::vector<std::array<int, 2>> held = pq.EdgesAtLengthBound();
  ASSERT_FALSE(held.empty());   // the bound is what the result leans on
  for (const auto& e : held) {  // the part along the input edge is a tenth of its length
    const auto at = [](const PolyMesh& m, int v) { return ToEigen(m.point(m.vertex_handle(v))); };
    const Eigen::Vector3d before = at(mesh, e[1]) - at(mesh, e[0]);
    const double ratio = (at(result, e[1]) - at(result, e[0])).dot(before) / before.squaredNorm();
    EXPECT_NEAR(ratio, 0.1, 1e-3) << e[0] << "-" << e[1];
  }
}

}  // namespace
}  // namespace gproj::pq
