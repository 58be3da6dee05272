#include "gproj/problems/marionette/marionette.h"

#include <gtest/gtest.h>

#include <Eigen/Dense>
#include <Eigen/Geometry>
#include <cmath>
#include <random>
#include <string>

#include "gproj/common/input_error.h"
#include "gproj/constraints/marionette_planarity.h"
#include "gproj/geometry/mesh/quad_grid.h"

namespace gproj::marionette {
namespace {

// A plan view: a (n+1) × (m+1)-vertex grid with jittered x, y (z is ignored).
MarionettePlan Plan(int n, int m, double jitter = 0.15, uint32_t seed = 3) {
  QuadGridOptions o;
  o.nu = n + 1;
  o.nv = m + 1;
  o.noise = jitter;
  o.seed = seed;
  return MakeMarionettePlan(MakeQuadGrid(o));
}

Eigen::VectorXd Smooth(int size, double phase) {
  Eigen::VectorXd v(size);
  for (int k = 0; k < size; ++k) v[k] = 0.5 * std::sin(0.7 * k + phase) + 0.1 * k;
  return v;
}

double MaxPlanarity(const MarionettePlan& plan, const Eigen::VectorXd& z) {
  double worst = 0.0;
  auto p = [&](int i, int j) {
    const int v = plan.Vertex(i, j);
    return Eigen::Vector3d(plan.xy[v].x(), plan.xy[v].y(), z[v]);
  };
  for (int i = 0; i < plan.rows; ++i)
    for (int j = 0; j < plan.cols; ++j) {
      const Eigen::Vector3d a = p(i, j), ab = p(i + 1, j) - a, ac = p(i + 1, j + 1) - a,
                            ad = p(i, j + 1) - a;
      worst = std::max(worst, std::abs(ab.cross(ac).dot(ad)) / (ab.norm() * ac.norm() * ad.norm()));
    }
  return worst;
}

TEST(MarionetteTest, LiftIsPlanarAndKeepsTheGuideCurves) {
  const MarionettePlan plan = Plan(12, 9);
  Eigen::VectorXd row = Smooth(10, 0.3), column = Smooth(13, 1.1);
  column[0] = row[0];
  const Eigen::VectorXd z = LiftMarionette(plan, row, column);
  EXPECT_LE(MaxPlanarity(plan, z), 1e-12);
  for (int j = 0; j <= 9; ++j) EXPECT_EQ(z[plan.Vertex(0, j)], row[j]);
  for (int i = 0; i <= 12; ++i) EXPECT_EQ(z[plan.Vertex(i, 0)], column[i]);
  // Not trivially flat.
  EXPECT_GT(z.maxCoeff() - z.minCoeff(), 0.5);
}

class MarionetteRankTest : public ::testing::TestWithParam<std::pair<int, int>> {};

TEST_P(MarionetteRankTest, PlanarHeightFieldsHaveDimensionNPlusMPlusOne) {
  const auto [n, m] = GetParam();
  const MarionettePlan plan = Plan(n, m);
  const Eigen::MatrixXd p = MarionettePlanarityMatrix(plan);
  Eigen::FullPivLU<Eigen::MatrixXd> lu(p);
  lu.setThreshold(1e-10);
  EXPECT_EQ(plan.num_vertices() - lu.rank(), n + m + 1);
  // The guide matrix spans that space: full column rank, and P A = 0.
  const Eigen::MatrixXd a = MarionetteGuideMatrix(plan);
  EXPECT_EQ(Eigen::FullPivLU<Eigen::MatrixXd>(a).rank(), n + m + 1);
  EXPECT_LT((p * a).cwiseAbs().maxCoeff(), 1e-10);
}

INSTANTIATE_TEST_SUITE_P(Sizes, MarionetteRankTest,
                         ::testing::Values(std::make_pair(1, 1), std::make_pair(3, 4),
                                           std::make_pair(5, 2), std::make_pair(8, 8)),
                         [](const ::testing::TestParamInfo<std::pair<int, int>>& info) {
                           return "Grid" + std::to_string(info.param.first) + "x" +
                                  std::to_string(info.param.second);
                         });

TEST(MarionetteTest, GuidedProjectionReachesTheDirectLiftInOneIteration) {
  const MarionettePlan plan = Plan(10, 10);
  Eigen::VectorXd row = Smooth(11, 0.2), column = Smooth(11, 2.0);
  column[0] = row[0];
  const Eigen::VectorXd direct = LiftMarionette(plan, row, column);
  std::vector<MarionetteTarget> guides;
  for (int j = 0; j <= 10; ++j) guides.push_back({plan.Vertex(0, j), row[j]});
  for (int i = 1; i <= 10; ++i) guides.push_back({plan.Vertex(i, 0), column[i]});
  Problem problem = MakeMarionetteProblem(plan, guides, {}, 1.0, 0.0);
  const SolverSummary summary = Solve(MarionetteSolverOptions(), &problem);
  ASSERT_EQ(summary.num_steps(), 1) << summary.FullReport();
  EXPECT_LE((problem.x() - direct).norm(), 1e-12 * direct.norm());
}

TEST(MarionetteTest, LeastSquaresFitEqualsTheNormalEquationsOfEq14) {
  const MarionettePlan plan = Plan(8, 6);
  // Target: heights of a saddle over the plan, not a Marionette mesh itself.
  Eigen::VectorXd z0(plan.num_vertices());
  for (int v = 0; v < plan.num_vertices(); ++v)
    z0[v] = plan.xy[v].x() * plan.xy[v].y() + 0.3 * std::sin(3 * plan.xy[v].x());
  const Eigen::MatrixXd a = MarionetteGuideMatrix(plan);
  const Eigen::VectorXd zp = (a.transpose() * a).ldlt().solve(a.transpose() * z0);
  const Eigen::VectorXd expected = a * zp;
  EXPECT_GT((expected - z0).norm(), 1e-3);  // a real fit, not an interpolation

  std::vector<MarionetteTarget> targets;
  for (int v = 0; v < plan.num_vertices(); ++v) targets.push_back({v, z0[v]});
  // Planarity (weight 1) against a target weight 1e-8: the constrained least-squares optimum up
  // to a bias of the order of the weight ratio (smaller ratios make the normal matrix too
  // ill-conditioned for one factorisation).
  Problem problem = MakeMarionetteProblem(plan, {}, targets, 1.0, 1e-8);
  Solve(MarionetteSolverOptions(), &problem);
  EXPECT_LE((problem.x() - expected).norm(), 1e-6 * expected.norm());
  EXPECT_LE(MaxPlanarity(plan, problem.x()), 5e-7);
}

TEST(MarionetteTest, RefusesDegeneratePlanViewNamingTheFace) {
  QuadGridOptions o;
  o.nu = 3;
  o.nv = 3;
  PolyMesh mesh = MakeQuadGrid(o);
  // Put vertex (1, 1) = 4 on the line through (0, 1) = 1 and (1, 0) = 3... make face 0's A, B, D
  // collinear instead: move vertex (0, 1) = 1 onto the line through (0, 0) and (1, 0).
  const auto p0 = mesh.point(PolyMesh::VertexHandle(0)), p3 = mesh.point(PolyMesh::VertexHandle(3));
  mesh.set_point(PolyMesh::VertexHandle(1), p0 + 0.5 * (p3 - p0));
  try {
    MakeMarionettePlan(mesh, "plan.obj");
    FAIL() << "degenerate plan accepted";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("plan.obj: face 0 has a degenerate plan view"),
              std::string::npos)
        << e.what();
  }
}

TEST(MarionetteTest, RefusesIncompatibleGuideCurves) {
  const MarionettePlan plan = Plan(3, 3);
  Eigen::VectorXd row = Smooth(4, 0.0), column = Smooth(4, 1.0);
  column[0] = row[0] + 0.5;
  try {
    LiftMarionette(plan, row, column);
    FAIL() << "incompatible guides accepted";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("incompatible guide curves"), std::string::npos)
        << e.what();
  }
}

TEST(MarionetteTest, RefusesMeshesThatAreNotGrids) {
  PolyMesh mesh;
  std::vector<PolyMesh::VertexHandle> v;
  for (int k = 0; k < 5; ++k) v.push_back(mesh.add_vertex({double(k), double(k * k % 3), 0}));
  mesh.add_face({v[0], v[1], v[2], v[3]});
  EXPECT_THROW(MakeMarionettePlan(mesh), InputError);
}

}  // namespace
}  // namespace gproj::marionette

namespace gproj::marionette {
namespace {

// Inner unit circle, outer ellipse with semi-axes 1.6 and 1.6 + stretch (mirror symmetric in
// both axes), every vertex jittered.
ClosedStrip Ring(int n, double jitter, double stretch = 0.0) {
  ClosedStrip strip;
  std::mt19937 rng(4);
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  for (int i = 0; i < n; ++i) {
    const double t = 2 * M_PI * i / n;
    const Eigen::Vector2d dir(std::cos(t), std::sin(t));
    strip.inner.push_back(1.0 * dir + jitter * Eigen::Vector2d(u(rng), u(rng)));
    strip.outer.push_back(Eigen::Vector2d(1.6 * dir.x(), (1.6 + stretch) * dir.y()) +
                          jitter * Eigen::Vector2d(u(rng), u(rng)));
  }
  return strip;
}

// Max normalised det over the N quads of the strip, the closing one included.
double StripPlanarity(const ClosedStrip& s, const ClosedStripLift& lift) {
  const int n = static_cast<int>(s.inner.size());
  double worst = 0.0;
  for (int i = 0; i < n; ++i) {
    const int k = (i + 1) % n;
    const Eigen::Vector3d a(s.inner[i].x(), s.inner[i].y(), lift.inner_heights[i]);
    const Eigen::Vector3d b(s.outer[i].x(), s.outer[i].y(), lift.outer_heights[i]);
    const Eigen::Vector3d c(s.outer[k].x(), s.outer[k].y(), lift.outer_heights[k]);
    const Eigen::Vector3d d(s.inner[k].x(), s.inner[k].y(), lift.inner_heights[k]);
    const Eigen::Vector3d ab = b - a, ac = c - a, ad = d - a;
    worst = std::max(worst, std::abs(ab.cross(ac).dot(ad)) / (ab.norm() * ac.norm() * ad.norm()));
  }
  return worst;
}

TEST(MarionetteClosedStripTest, GenericPlanHasOneClosingLift) {
  const ClosedStrip strip = Ring(24, 0.08);
  Eigen::VectorXd z(24);
  for (int i = 0; i < 24; ++i)
    z[i] = 0.3 * std::sin(2 * M_PI * i / 24) + 0.1 * std::cos(6 * M_PI * i / 24);
  const ClosedStripLift lift = LiftClosedStrip(strip, z);
  EXPECT_FALSE(lift.a_is_one) << lift.a;
  EXPECT_EQ(lift.inner_heights, z);  // the designer's curve is kept
  EXPECT_LE(StripPlanarity(strip, lift), 1e-12);
}

TEST(MarionetteClosedStripTest, SymmetricPlanHasAEqualOneAndProjectsTheInnerCurve) {
  const ClosedStrip strip = Ring(24, 0.0, 0.3);
  Eigen::VectorXd z(24);
  for (int i = 0; i < 24; ++i) z[i] = 0.3 * std::cos(0.9 * i) + 0.2;
  const ClosedStripLift lift = LiftClosedStrip(strip, z, 0.7);
  EXPECT_TRUE(lift.a_is_one) << lift.a;
  EXPECT_NEAR(lift.v.dot(lift.inner_heights), 0.0, 1e-12);
  EXPECT_NEAR(lift.outer_heights[0], 0.7, 1e-15);  // z_0* stays free
  EXPECT_LE(StripPlanarity(strip, lift), 1e-12);
  EXPECT_GT(lift.v.norm(), 0.1);
  EXPECT_GT(std::abs(lift.v.dot(z)), 1e-3);  // the designer's curve had to be projected
}

TEST(MarionetteClosedStripTest, ConcentricCirclesLeaveEveryInnerCurveFree) {
  const ClosedStrip strip = Ring(24, 0.0);  // α_i = 1, and z_N* = z_0* for every Z
  Eigen::VectorXd z(24);
  for (int i = 0; i < 24; ++i) z[i] = std::cos(0.9 * i);
  const ClosedStripLift lift = LiftClosedStrip(strip, z, 0.4);
  EXPECT_TRUE(lift.a_is_one);
  EXPECT_LT(lift.v.norm(), 1e-12);
  EXPECT_EQ(lift.inner_heights, z);
  EXPECT_LE(StripPlanarity(strip, lift), 1e-12);
}

// a and the lift are scale-free, and so are their computation and the degeneracy test: the
// plan scaled by 1e±300 (heights with it) gives the same a and heights (it used to be refused
// as collinear, the cross products overflowing or underflowing).
TEST(MarionetteClosedStripTest, LiftIsTheSameAtEveryScale) {
  const ClosedStrip strip = Ring(16, 0.08);
  Eigen::VectorXd z(16);
  for (int i = 0; i < 16; ++i) z[i] = 0.3 * std::sin(2 * M_PI * i / 16);
  const ClosedStripLift unit = LiftClosedStrip(strip, z);
  for (double scale : {1e-300, 1e300}) {
    ClosedStrip scaled = strip;
    for (auto* curve : {&scaled.inner, &scaled.outer})
      for (Eigen::Vector2d& p : *curve) p *= scale;
    ASSERT_EQ(DegenerateClosedStripQuad(scaled), -1) << scale;
    const ClosedStripLift lift = LiftClosedStrip(scaled, z * scale);
    EXPECT_NEAR(lift.a, unit.a, 1e-12) << scale;
    for (int i = 0; i < 16; ++i)
      EXPECT_NEAR(lift.outer_heights[i] / scale, unit.outer_heights[i], 1e-12) << scale;
  }
}

TEST(MarionetteClosedStripTest, RefusesDegenerateQuads) {
  ClosedStrip strip = Ring(8, 0.0);
  strip.outer[3] = strip.inner[3] + 0.5 * (strip.inner[4] - strip.inner[3]);
  EXPECT_THROW(LiftClosedStrip(strip, Eigen::VectorXd::Zero(8)), InputError);
}

double Det(const Eigen::Vector2d& a, const Eigen::Vector2d& b) {
  return a.x() * b.y() - a.y() * b.x();
}

// 002 Appendix A on a jittered ring (a generic plan, a ≠ 1). With A = P_k, B = P_{k+1},
// C = P_k*, D = P_{k+1}* (inner and outer curves), the propagation z*_k → z*_{k+1} multiplies
// z*_k by μ_k = det(AB, AD) / det(AB, AC), so a = ∏ μ_k (eq. 20). The paper's a_k (eq. 18) is
// the reciprocal, det(AB, AC) / det(AB, AD): its product is 1 / a, which is 1 exactly when a
// is (eq. 24 is unaffected). Since det(AB, AD) = det(AB, BD), μ_k = |BD| sin θ_B / (|AC| sin θ_A)
// with θ_A the angle at A from AB to AC and θ_B the angle at B from AB to BD; the transverse
// edges |AC| and |BD| telescope round the strip, leaving a = ∏ sin θ_B / sin θ_A (eq. 28's form).
TEST(MarionetteAppendixATest, ClosingFactorIsAProductOfQuadRatiosAndOfSines) {
  const int n = 24;
  const ClosedStrip strip = Ring(n, 0.08);
  const ClosedStripLift lift = LiftClosedStrip(strip, Eigen::VectorXd::Zero(n));
  double ratios = 1.0, sines = 1.0, paper = 1.0;
  for (int k = 0; k < n; ++k) {
    const Eigen::Vector2d a = strip.inner[k], b = strip.inner[(k + 1) % n], c = strip.outer[k],
                          d = strip.outer[(k + 1) % n];
    ratios *= Det(b - a, d - a) / Det(b - a, c - a);
    paper *= Det(b - a, c - a) / Det(b - a, d - a);
    const double sin_a = Det(b - a, c - a) / ((b - a).norm() * (c - a).norm());
    const double sin_b = Det(b - a, d - b) / ((b - a).norm() * (d - b).norm());
    sines *= sin_b / sin_a;
  }
  EXPECT_GT(std::abs(lift.a - 1.0), 1e-3);
  EXPECT_NEAR(lift.a, ratios, 1e-12 * std::abs(ratios));
  EXPECT_NEAR(lift.a, sines, 1e-12 * std::abs(sines));
  EXPECT_NEAR(lift.a * paper, 1.0, 1e-12);
}

// Appendix A.4: an affine map of the plan keeps every ratio, hence a. Under x ↦ M x + t a 2D
// determinant of two difference vectors is multiplied by det M (eq. 26 prints (det M)²).
TEST(MarionetteAppendixATest, AffineMapsOfThePlanKeepTheClosingFactor) {
  const int n = 16;
  const ClosedStrip strip = Ring(n, 0.08);
  Eigen::Matrix2d m;
  m << 2.0, 0.5, 0.3, 1.2;  // det M = 2.25
  const Eigen::Vector2d t(0.7, -1.3);
  ClosedStrip mapped = strip;
  for (auto* curve : {&mapped.inner, &mapped.outer})
    for (Eigen::Vector2d& p : *curve) p = m * p + t;
  Eigen::VectorXd z(n);
  for (int i = 0; i < n; ++i) z[i] = 0.3 * std::sin(2 * M_PI * i / n);
  const ClosedStripLift before = LiftClosedStrip(strip, z), after = LiftClosedStrip(mapped, z);
  EXPECT_NEAR(after.a, before.a, 1e-12);
  for (int i = 0; i < n; ++i) EXPECT_NEAR(after.outer_heights[i], before.outer_heights[i], 1e-12);
  const Eigen::Vector2d x0 = strip.outer[3] - strip.inner[3], x1 = strip.inner[4] - strip.inner[3];
  const Eigen::Vector2d y0 = mapped.outer[3] - mapped.inner[3],
                        y1 = mapped.inner[4] - mapped.inner[3];
  EXPECT_NEAR(Det(y0, y1), m.determinant() * Det(x0, x1), 1e-12);
  EXPECT_GT(std::abs(Det(y0, y1) - m.determinant() * m.determinant() * Det(x0, x1)), 0.1);
}

// 002 eq. 2 as printed gives the plane z = x over the unit square the wrong height at C: its
// (z_B − z_A) term carries d_DC / d_BD = −1 where −d_DC / d_BD = +1 belongs. gproj's
// coefficients (AC = α AB + β AD) give z_C = 1.
TEST(MarionetteAppendixATest, EquationTwoHasTheWrongSignOnItsSecondTerm) {
  const Eigen::Vector2d a(0, 0), b(1, 0), c(1, 1), d(0, 1);
  double alpha = 0.0, beta = 0.0;
  ASSERT_TRUE(MarionettePlanarity::PlanCoefficients(a, b, c, d, &alpha, &beta));
  const double za = 0.0, zb = 1.0, zd = 0.0;  // z = x
  EXPECT_NEAR(za + alpha * (zb - za) + beta * (zd - za), 1.0, 1e-15);
  const double d_bc = Det(b - a, c - a), d_bd = Det(b - a, d - a), d_dc = Det(d - a, c - a);
  EXPECT_NEAR(za + d_bc / d_bd * (zd - za) + d_dc / d_bd * (zb - za), -1.0, 1e-15);
}

// A target over a 10 × 8-face plan: a bump the planar lifts cannot follow exactly.
Eigen::VectorXd Bump(const MarionettePlan& plan) {
  Eigen::VectorXd z0(plan.num_vertices());
  for (int v = 0; v < plan.num_vertices(); ++v) {
    const Eigen::Vector2d p = plan.xy[v];
    z0[v] = 0.8 * std::exp(-((p.x() - 0.2) * (p.x() - 0.2) + p.y() * p.y()) * 3.0) + 0.1 * p.x();
  }
  return z0;
}

// 002 §3.3: the volume row is exact for planar faces: z = c gives c × plan area, and z = x + 2y
// over any plan gives ∫ (x + 2y) dA, here compared with the triangle-by-triangle integral.
TEST(MarionetteConstraintsTest, VolumeRowIntegratesAffineHeightsExactly) {
  const MarionettePlan plan = Plan(6, 5);
  const Eigen::RowVectorXd row = MarionetteVolumeRow(plan);
  double area = 0.0, moment = 0.0;
  for (int i = 0; i < plan.rows; ++i)
    for (int j = 0; j < plan.cols; ++j) {
      const int quad[4] = {plan.Vertex(i, j), plan.Vertex(i + 1, j), plan.Vertex(i + 1, j + 1),
                           plan.Vertex(i, j + 1)};
      for (int t : {1, 2}) {
        const Eigen::Vector2d a = plan.xy[quad[0]], b = plan.xy[quad[t]], c = plan.xy[quad[t + 1]];
        const double s = 0.5 * ((b - a).x() * (c - a).y() - (b - a).y() * (c - a).x());
        const Eigen::Vector2d centroid = (a + b + c) / 3.0;
        area += s;
        moment += s * (centroid.x() + 2.0 * centroid.y());
      }
    }
  if (area < 0) area = -area, moment = -moment;
  Eigen::VectorXd z(plan.num_vertices());
  z.setConstant(1.7);
  EXPECT_NEAR(row.dot(z), 1.7 * area, 1e-12);
  for (int v = 0; v < plan.num_vertices(); ++v) z[v] = plan.xy[v].x() + 2.0 * plan.xy[v].y();
  EXPECT_NEAR(row.dot(z), moment, 1e-12);
}

// Hard constraints are met exactly and the lift stays planar; the fit pays for them (a larger
// distance to the target than the unconstrained fit) and is the best under them: moving along
// the lifts that keep the constraints does not lower the distance.
TEST(MarionetteConstraintsTest, HeightsAndVolumeAreMetExactly) {
  const MarionettePlan plan = Plan(10, 8);
  const Eigen::VectorXd z0 = Bump(plan), w = Eigen::VectorXd::Ones(plan.num_vertices());
  const Eigen::VectorXd free = FitMarionette(plan, z0);
  MarionetteConstraints c;
  c.heights = {{plan.Vertex(5, 4), 1.0}, {plan.Vertex(0, 0), -0.2}};
  c.with_volume = true;
  c.volume = 1.2 * MarionetteVolumeRow(plan).dot(free);
  const Eigen::VectorXd z = FitMarionette(plan, z0, w, c);
  EXPECT_NEAR(z[plan.Vertex(5, 4)], 1.0, 1e-12);
  EXPECT_NEAR(z[plan.Vertex(0, 0)], -0.2, 1e-12);
  EXPECT_NEAR(MarionetteVolumeRow(plan).dot(z), c.volume, 1e-10);
  EXPECT_LE(MaxPlanarity(plan, z), 1e-10);
  EXPECT_GT((z - z0).norm(), (free - z0).norm());
  // Unconstrained directions of the lift space: the guide matrix's null space of the
  // constraint rows. None of them lowers the distance.
  const Eigen::MatrixXd a = MarionetteGuideMatrix(plan);
  Eigen::MatrixXd e(3, a.cols());
  e << a.row(plan.Vertex(5, 4)), a.row(plan.Vertex(0, 0)), MarionetteVolumeRow(plan) * a;
  const Eigen::MatrixXd directions = Eigen::FullPivLU<Eigen::MatrixXd>(e).kernel();
  const Eigen::VectorXd gradient = (a * directions).transpose() * (z - z0);
  EXPECT_LT(gradient.norm(), 1e-9 * (a * directions).norm() * (z - z0).norm());
  // No constraint and unit weights: the plain fit of eq. 14.
  EXPECT_LT((FitMarionette(plan, z0, w, {}) - free).norm(), 1e-10);
}

// A max height: no vertex above it, some at it, planar; without the bound the fit goes above.
TEST(MarionetteConstraintsTest, MaxHeightHoldsWithSomeVerticesAtTheBound) {
  const MarionettePlan plan = Plan(10, 8);
  const Eigen::VectorXd z0 = Bump(plan), w = Eigen::VectorXd::Ones(plan.num_vertices());
  const double bound = 0.4;
  ASSERT_GT(FitMarionette(plan, z0).maxCoeff(), bound + 0.05);
  MarionetteConstraints c;
  c.with_max_height = true;
  c.max_height = bound;
  const Eigen::VectorXd z = FitMarionette(plan, z0, w, c);
  EXPECT_LE(z.maxCoeff(), bound + 1e-10);
  EXPECT_NEAR(z.maxCoeff(), bound, 1e-10);
  EXPECT_LE(MaxPlanarity(plan, z), 1e-10);
}

// A partial target: heights given along the guide curves only (row 0 and column 0) determine
// the lift, and the fit is the propagation from them; three vertices do not, and the error
// says how many guide heights stay free.
TEST(MarionetteConstraintsTest, PartialTargetsOnTheGuidesGiveTheLift) {
  const MarionettePlan plan = Plan(7, 6);
  Eigen::VectorXd row = Smooth(7, 0.3), column = Smooth(8, 1.1);
  column[0] = row[0];
  const Eigen::VectorXd lift = LiftMarionette(plan, row, column);
  Eigen::VectorXd z0 = Eigen::VectorXd::Constant(plan.num_vertices(), 123.0);  // ignored
  Eigen::VectorXd w = Eigen::VectorXd::Zero(plan.num_vertices());
  for (int j = 0; j <= 6; ++j) z0[plan.Vertex(0, j)] = row[j], w[plan.Vertex(0, j)] = 1.0;
  for (int i = 0; i <= 7; ++i) z0[plan.Vertex(i, 0)] = column[i], w[plan.Vertex(i, 0)] = 1.0;
  EXPECT_LT((FitMarionette(plan, z0, w, {}) - lift).cwiseAbs().maxCoeff(), 1e-10);
  Eigen::VectorXd few = Eigen::VectorXd::Zero(plan.num_vertices());
  few.head(3).setOnes();
  try {
    FitMarionette(plan, z0, few, {});
    FAIL() << "three vertices cannot determine 14 guide heights";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("guide heights stay free"), std::string::npos) << e.what();
  }
}

}  // namespace
}  // namespace gproj::marionette
