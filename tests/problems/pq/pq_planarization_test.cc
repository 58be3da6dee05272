#include "gproj/problems/pq/pq_planarization.h"

#include <gtest/gtest.h>

#include "gproj/geometry/mesh/circle.h"
#include "gproj/geometry/mesh/parametric_grid.h"
#include "gproj/geometry/mesh/quad_grid.h"
#include "gproj/solver/internal/linearized_system.h"

namespace gproj::pq {
namespace {

const std::string kShippedGrid =
    std::string(GPROJ_SOURCE_DIR) + "/examples/data/noisy_grid_21x21.obj";

TEST(PQPlanarizationTest, ShippedNoisyGridReachesPlanarity1e9) {
  const PolyMesh mesh = ReadMesh(kShippedGrid, MeshRequirements{true});
  ASSERT_EQ(mesh.n_faces(), 400u);
  PQPlanarizationOptions options;
  options.tolerance = 1e-9;
  PQPlanarization pq(mesh, options);
  const PlanarityMeasures before = pq.Measures();
  EXPECT_GT(before.max_planarity, 1e-2);  // the input really is far from planar
  const RunReport report = pq.Run();
  ASSERT_TRUE(report.converged) << report.summary.FullReport();
  const PlanarityMeasures after = MeasurePlanarity(pq.Result(), mesh);
  EXPECT_LE(after.max_planarity, 1e-9);
  EXPECT_LE(after.max_displacement, 0.02);
  EXPECT_LE(report.iterations, 30);
  EXPECT_DOUBLE_EQ(ValueOf(report.final, "max_planarity"), after.max_planarity);
  EXPECT_DOUBLE_EQ(ValueOf(report.initial, "max_planarity"), before.max_planarity);
  ASSERT_EQ(report.history.size(), static_cast<size_t>(report.iterations + 1));
  EXPECT_DOUBLE_EQ(ValueOf(report.history.back().measures, "max_planarity"), after.max_planarity);
}

// The default schedule ties the soft weights and ε to the measured residual: once the quads are
// nearly planar the steps converge quadratically, where a fixed decay of the weights (and a
// fixed ε) gives exactly one digit per iteration. The result is the same mesh to the eye.
TEST(PQPlanarizationTest, ResidualTiedScheduleConvergesQuadratically) {
  QuadGridOptions grid;
  grid.nu = grid.nv = 31;
  grid.noise = 0.05;
  grid.seed = 3;
  const PolyMesh mesh = MakeQuadGrid(grid);
  PQPlanarizationOptions options;
  options.tolerance = 1e-12;
  PQPlanarization tied(mesh, options);
  const RunReport fast = tied.Run();
  ASSERT_TRUE(fast.converged) << fast.summary.FullReport();
  PQPlanarizationOptions fixed_options = options;
  fixed_options.solver.soft_weight_residual_factor = 0.0;
  fixed_options.solver.epsilon_min = 0.0;
  PQPlanarization fixed(mesh, fixed_options);
  const RunReport slow = fixed.Run();
  ASSERT_TRUE(slow.converged) << slow.summary.FullReport();
  EXPECT_LE(fast.iterations, 10);
  EXPECT_GE(slow.iterations, fast.iterations + 4);
  // The last steps: far faster than the weights' one digit per iteration.
  auto planarity = [&](int k) { return ValueOf(fast.history[k].measures, "max_planarity"); };
  const int n = fast.iterations;
  EXPECT_LT(planarity(n - 1), 1e-3 * planarity(n - 2));
  EXPECT_LT(planarity(n), 1e-2 * planarity(n - 1));
  // The same result: displacement and corner angles as with the fixed schedule.
  const PlanarityMeasures a = MeasurePlanarity(tied.Result(), mesh);
  const PlanarityMeasures b = MeasurePlanarity(fixed.Result(), mesh);
  EXPECT_NEAR(a.max_displacement, b.max_displacement, 0.05 * b.max_displacement);
  EXPECT_NEAR(a.shape.min_angle_deg, b.shape.min_angle_deg, 1.0);
  EXPECT_EQ(a.shape.non_convex, 0);
}

// Fixed soft weights as strong as at the start: the steps stall far above the tolerance. That
// is not convergence, whatever the solver's stop is called.
TEST(PQPlanarizationTest, AStallShortOfTheToleranceIsNotConvergence) {
  const PolyMesh mesh = ReadMesh(kShippedGrid, MeshRequirements{true});
  PQPlanarizationOptions options;
  options.solver.soft_weight_decay = 1.0;
  options.solver.soft_weight_floor = 1.0;
  PQPlanarization pq(mesh, options);
  const RunReport report = pq.Run();
  EXPECT_FALSE(report.converged);
  EXPECT_FALSE(report.failed);
  EXPECT_GT(pq.Measures().max_planarity, 1e-4);
  EXPECT_EQ(report.termination.rfind("STALLED short of the tolerance", 0), 0u)
      << report.termination;
}

// The problem is scale-free after normalisation, and so are the measures: the shipped grid
// scaled by 1e-150 … 1e200 runs exactly like the original (the planarity measure used to
// overflow to 0 at 1e78, so a non-planar mesh "converged" at iteration 0, and the solver
// failed at 1e200).
TEST(PQPlanarizationTest, AnyFiniteScaleRunsLikeTheOriginal) {
  const PolyMesh original = ReadMesh(kShippedGrid, MeshRequirements{true});
  PQPlanarization reference(original, PQPlanarizationOptions());
  const RunReport expected = reference.Run();
  ASSERT_TRUE(expected.converged);
  for (double scale : {1e-150, 1e78, 1e150, 1e200}) {
    PolyMesh mesh = original;
    for (auto v : mesh.vertices()) mesh.set_point(v, mesh.point(v) * scale);
    PQPlanarization pq(mesh, PQPlanarizationOptions());
    EXPECT_NEAR(pq.Measures().max_planarity, ValueOf(expected.initial, "max_planarity"), 1e-12)
        << scale;
    const RunReport report = pq.Run();
    ASSERT_TRUE(report.converged) << scale << " " << report.termination;
    EXPECT_EQ(report.iterations, expected.iterations) << scale;
    EXPECT_NEAR(pq.Measures().max_planarity, reference.Measures().max_planarity, 1e-12) << scale;
    const PolyMesh result = pq.Result();
    const PolyMesh back = reference.Result();
    double worst = 0.0;
    for (auto v : result.vertices())
      worst = std::max(worst, (result.point(v) / scale - back.point(v)).length());
    EXPECT_LE(worst, 1e-12) << scale;
  }
}

TEST(PQPlanarizationTest, CholmodAndEigenBackendsAgree) {
  QuadGridOptions grid;
  grid.nu = grid.nv = 8;
  grid.noise = 0.1;
  const PolyMesh mesh = MakeQuadGrid(grid);
  PQPlanarizationOptions options;
  options.solver.max_iterations = 5;
  options.tolerance = 1e-300;
  PQPlanarization a(mesh, options);
  options.solver.linear_solver = LinearSolverType::kEigen;
  PQPlanarization b(mesh, options);
  a.Run();
  b.Run();
  EXPECT_LT((a.problem().x() - b.problem().x()).lpNorm<Eigen::Infinity>(), 1e-10);
}

TEST(PQPlanarizationTest, EliminatingTheNormalsGivesTheSameIterates) {
  QuadGridOptions grid;
  grid.nu = grid.nv = 9;
  grid.noise = 0.1;
  const PolyMesh mesh = MakeQuadGrid(grid);
  PQPlanarizationOptions options;
  options.solver.max_iterations = 6;
  options.tolerance = 1e-300;
  PQPlanarization with(mesh, options), without(mesh, options);
  SolverOptions solver_options = options.solver;
  const SolverSummary s1 = Solve(solver_options, &with.problem());
  solver_options.eliminate_auxiliaries = false;
  const SolverSummary s2 = Solve(solver_options, &without.problem());
  // Per quad a normal (3) and four corner slacks, per edge (144) a length slack.
  EXPECT_EQ(s1.eliminated_variables, 64 * (3 + 4) + 144);
  EXPECT_EQ(s2.eliminated_variables, 0);
  EXPECT_LT((with.problem().x() - without.problem().x()).lpNorm<Eigen::Infinity>(), 1e-9);
}

// Fixed weights (no schedule): both solvers minimise ½ Σ w φ² + ½ ω_f² ‖P x‖² from the same
// start and must agree on the objective; small soft weights leave planarity residuals ≤ 1e-8.
TEST(PQPlanarizationTest, GuidedProjectionAndCeresReachTheSameObjective) {
  QuadGridOptions grid;
  grid.nu = 6;
  grid.nv = 5;
  grid.noise = 0.05;
  grid.seed = 7;
  const PolyMesh mesh = MakeQuadGrid(grid);
  PQPlanarizationOptions options;
  options.closeness_weight = 1e-7;
  options.solver.fairness_weight = 3e-4;
  options.solver.soft_weight_decay = 1.0;
  options.solver.epsilon = 1e-7;
  options.solver.max_iterations = 500;
  options.tolerance = 1e-300;      // run both to their own convergence
  options.ceres_soft_scale = 1.0;  // the same fixed weights as guided projection
  PQPlanarization gp(mesh, options);
  PQPlanarization ceres(mesh, options);
  // Both stop at a stationary point of the objective; the tolerance is out of reach.
  const RunReport report = gp.Run();
  ASSERT_TRUE(report.summary.converged()) << report.summary.FullReport();
  EXPECT_FALSE(report.converged);
  const RunReport cs = ceres.RunCeres(500);
  ASSERT_FALSE(cs.failed) << cs.termination;
  EXPECT_EQ(cs.solver, SolverKind::kCeres);

  const double e_gp =
      EvaluateObjective(&gp.problem(), options.solver.fairness_weight, gp.problem().x());
  const double e_ceres =
      EvaluateObjective(&ceres.problem(), options.solver.fairness_weight, ceres.problem().x());
  EXPECT_GT(e_gp, 0.0);
  EXPECT_NEAR(e_gp, e_ceres, 1e-6 * e_ceres);
  for (PQPlanarization* pq : {&gp, &ceres}) {
    LinearizedSystem system(&pq->problem());
    std::string why;
    ASSERT_TRUE(system.Assemble(pq->problem().x(), options.solver.fairness_weight, 1.0, &why));
    const int rows = pq->problem().family(0).num_rows();
    ASSERT_EQ(pq->problem().family(0).name(), "planarity");
    EXPECT_LT(system.phi().head(rows).cwiseAbs().maxCoeff(), 1e-8);
  }
}

// Circular mode (000 §2): a jittered circular net of a surface of revolution becomes circular
// again; plain planarisation leaves it planar but not concyclic.
TEST(PQPlanarizationTest, CircularModeMakesQuadsConcyclic) {
  ParametricGridOptions o;
  o.nu = o.nv = 12;
  o.jitter = 0.03;
  const PolyMesh mesh = MakeParametricGrid(RevolutionSurface, o);
  ASSERT_GT(MeasureCircularity(mesh).max_concyclicity, 1e-3);
  PQPlanarizationOptions options;
  options.circular = true;
  PQPlanarization circular(mesh, options);
  const RunReport s = circular.Run();
  ASSERT_TRUE(s.converged) << s.termination;
  EXPECT_LE(ValueOf(s.final, "max_concyclicity"), 1e-9);
  const PlanarityMeasures m = circular.Measures();
  EXPECT_LE(m.max_planarity, 1e-9);
  EXPECT_LE(m.max_concyclicity, 1e-9);
  EXPECT_LT(MeasureCircularity(circular.Result()).max_concyclicity, 1e-9);
  EXPECT_LT(m.max_displacement, 0.02);

  PQPlanarization planar(mesh, PQPlanarizationOptions{});
  ASSERT_TRUE(planar.Run().converged);
  EXPECT_TRUE(std::isnan(ValueOf(planar.Measure(), "max_concyclicity")));
  EXPECT_GT(MeasureCircularity(planar.Result()).max_concyclicity, 1e-5);
}

TEST(PQPlanarizationTest, RefusesAMeshOfTrianglesOnly) {
  PolyMesh mesh;
  auto a = mesh.add_vertex({0, 0, 0}), b = mesh.add_vertex({1, 0, 0}),
       c = mesh.add_vertex({0, 1, 0});
  mesh.add_face(a, b, c);
  try {
    PQPlanarization pq(mesh, PQPlanarizationOptions());
    FAIL() << "a triangle was accepted";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("every face is a triangle"), std::string::npos)
        << e.what();
  }
}

TEST(PQPlanarizationTest, DiagonalDistanceOfKnownQuad) {
  // Diagonals (0,0,0)-(1,1,0) and (1,0,h)-(0,1,h) are skew at distance h.
  EXPECT_NEAR(DiagonalDistance({0, 0, 0}, {1, 0, 0.3}, {1, 1, 0}, {0, 1, 0.3}), 0.3, 1e-15);
  EXPECT_NEAR(DiagonalDistance({0, 0, 0}, {1, 0, 0}, {1, 1, 0}, {0, 1, 0}), 0.0, 1e-15);
}

}  // namespace
}  // namespace gproj::pq
