#include "gproj/problems/nets/hnet.h"

#include <gtest/gtest.h>

#include "gproj/geometry/mesh/parametric_grid.h"

namespace gproj::nets {
namespace {

PolyMesh Grid(const std::string& surface, int n, double jitter = 0.0, uint32_t seed = 1) {
  ParametricGridOptions o;
  o.nu = o.nv = n;
  o.jitter = jitter;
  o.seed = seed;
  return MakeParametricGrid(AsymptoticSurface(surface), o);
}

std::vector<std::array<double, 4>> AllCornerWeights(const PolyMesh& mesh,
                                                    const std::vector<int>& colour,
                                                    const std::vector<double>& w) {
  std::vector<std::array<double, 4>> out;
  for (auto f : mesh.faces()) out.push_back(CornerWeights(mesh, colour, f, w[f.idx()]));
  return out;
}

TEST(HNetTest, HyparRulingGridGivesEqualWeightsAndSmoothJoins) {
  const PolyMesh mesh = Grid("hypar", 9);
  const std::vector<int> colour = TwoColourVertices(mesh);
  const ShapeParameters shape = PropagateShapeParameters(mesh, colour, 0);
  for (double w : shape.w) EXPECT_NEAR(w, 1.0, 1e-12);  // hyperbolic paraboloid patches
  EXPECT_LT(shape.max_inconsistency, 1e-12);
  EXPECT_LE(MaxTangentPlaneAngle(mesh, AllCornerWeights(mesh, colour, shape.w)), 1e-8);
}

TEST(HNetTest, HyperboloidRulingGridJoinsSmoothly) {
  const PolyMesh mesh = Grid("hyperboloid", 9);
  const std::vector<int> colour = TwoColourVertices(mesh);
  const ShapeParameters shape = PropagateShapeParameters(mesh, colour, 0);
  EXPECT_LT(shape.max_inconsistency, 1e-10);
  for (double w : shape.w) EXPECT_GT(w, 0.0);
  EXPECT_LE(MaxTangentPlaneAngle(mesh, AllCornerWeights(mesh, colour, shape.w)), 1e-7);
  // Equal weights (W = 1 everywhere) do not join smoothly here: the measure can fail.
  std::vector<double> ones(mesh.n_faces(), 1.0);
  EXPECT_GT(MaxTangentPlaneAngle(mesh, AllCornerWeights(mesh, colour, ones)), 0.01);
  EXPECT_TRUE(EquitwistViolations(mesh, colour).empty());
}

// The angle is scale-free, and so is its measure: the same mesh moved and scaled from 1e-99 to
// 1e100 gives the same angle (the patch normals used to overflow or underflow to 0 there).
TEST(HNetTest, TangentPlaneAngleIsTheSameAtEveryScale) {
  const PolyMesh mesh = Grid("hyperboloid", 7);
  const std::vector<int> colour = TwoColourVertices(mesh);
  const std::vector<std::array<double, 4>> ones =
      AllCornerWeights(mesh, colour, std::vector<double>(mesh.n_faces(), 1.0));
  const double angle = MaxTangentPlaneAngle(mesh, ones);
  ASSERT_GT(angle, 0.01);
  for (double scale : {1e-99, 1e-40, 1e40, 1e80, 1e100}) {
    PolyMesh scaled = mesh;
    for (auto v : scaled.vertices())
      scaled.set_point(v, (mesh.point(v) + PolyMesh::Point(3, -1, 2)) * scale);
    EXPECT_NEAR(MaxTangentPlaneAngle(scaled, ones), angle, 1e-9 * angle) << "scale " << scale;
  }
}

// A planar star of valence n around the origin with free vertices alternately above and below.
PolyMesh Star(int n, double tilt) {
  PolyMesh mesh;
  const auto c = mesh.add_vertex({0, 0, 0});
  std::vector<PolyMesh::VertexHandle> ring;
  for (int k = 0; k < 2 * n; ++k) {
    const double a = k * M_PI / n + 0.1 * std::sin(3.0 * k);
    const bool free = k % 2 == 1;
    const double r = free ? 1.7 + 0.2 * std::cos(k) : 1.0 + 0.15 * std::sin(2.0 * k);
    const double z = free ? ((k / 2) % 2 == 0 ? 0.3 : -0.25) + 0.05 * k : 0.0;
    ring.push_back(mesh.add_vertex({r * std::cos(a), r * std::sin(a), z + tilt * r * std::cos(a)}));
  }
  for (int k = 0; k < n; ++k)
    mesh.add_face({c, ring[2 * k], ring[2 * k + 1], ring[(2 * k + 2) % (2 * n)]});
  return mesh;
}

class ClosureTest : public ::testing::TestWithParam<int> {};

TEST_P(ClosureTest, ClosureProductHoldsAtPlanarEvenStars) {
  const PolyMesh mesh = Star(GetParam(), 0.0);
  const auto [lhs, rhs] = ClosureProducts(mesh, PolyMesh::VertexHandle(0));
  EXPECT_GT(std::abs(lhs), 1e-12);
  EXPECT_NEAR(lhs, rhs, 1e-10 * std::abs(lhs));
}

TEST_P(ClosureTest, ClosureProductFailsWhenTheStarIsNotPlanar) {
  PolyMesh mesh = Star(GetParam(), 0.0);
  auto p = mesh.point(PolyMesh::VertexHandle(1));
  p[2] += 0.2;
  mesh.set_point(PolyMesh::VertexHandle(1), p);
  const auto [lhs, rhs] = ClosureProducts(mesh, PolyMesh::VertexHandle(0));
  EXPECT_GT(std::abs(lhs - rhs), 1e-3 * std::abs(lhs));
}

INSTANTIATE_TEST_SUITE_P(Valences, ClosureTest, ::testing::Values(4, 6, 8),
                         [](const ::testing::TestParamInfo<int>& info) {
                           return "Valence" + std::to_string(info.param);
                         });

TEST(HNetTest, ClosureProductHoldsAtEveryInnerVertexOfAnExactANet) {
  const PolyMesh mesh = Grid("hyperboloid", 9);
  int checked = 0;
  for (auto v : mesh.vertices()) {
    if (mesh.is_boundary(v)) continue;
    const auto [lhs, rhs] = ClosureProducts(mesh, v);
    EXPECT_NEAR(lhs, rhs, 1e-10 * std::abs(lhs)) << "vertex " << v.idx();
    ++checked;
  }
  EXPECT_EQ(checked, 49);
}

TEST(HNetTest, OptimalScaleMatchesOneDimensionalMinimisation) {
  const std::vector<double> w = {0.3, 0.8, 1.7, 2.5, 0.45};
  auto f = [&w](double l) {
    double s = 0.0;
    for (double x : w) s += std::pow(l * x - 1, 2) + std::pow(1 / (l * x) - 1, 2);
    return s;
  };
  // Golden-section search on log λ.
  double a = std::log(1e-3), b = std::log(1e3);
  const double g = (std::sqrt(5.0) - 1) / 2;
  for (int i = 0; i < 200; ++i) {
    const double c = b - g * (b - a), d = a + g * (b - a);
    if (f(std::exp(c)) < f(std::exp(d)))
      b = d;
    else
      a = c;
  }
  const double numeric = std::exp(0.5 * (a + b));
  EXPECT_NEAR(OptimalShapeScale(w), numeric, 1e-7 * numeric);
  // Scaling every W by c scales the optimum by 1/c.
  std::vector<double> scaled = w;
  for (double& x : scaled) x *= 4.0;
  EXPECT_NEAR(OptimalShapeScale(scaled), numeric / 4.0, 1e-7 * numeric);
}

TEST(HNetTest, JitteredHyperboloidBecomesASmoothHNet) {
  const PolyMesh exact = Grid("hyperboloid", 11);
  const PolyMesh mesh = Grid("hyperboloid", 11, 0.03, 4);
  HNetOptions options;
  HNet hnet(mesh, &exact, options);
  const HNetSummary summary = hnet.Run();
  ASSERT_FALSE(summary.rounds.empty()) << summary.report.termination;
  EXPECT_TRUE(summary.anet_step_run);
  EXPECT_TRUE(summary.report.converged) << summary.report.termination;
  EXPECT_LE(summary.rounds.back().max_tangent_angle_deg, 0.01);
  EXPECT_GT(summary.rounds.back().min_w, 0.0);
  EXPECT_LE(MaxTangentPlaneAngle(hnet.mesh(), hnet.weights()), 0.01);
}

TEST(HNetTest, HeldVerticesStayThroughTheANetStepAndEveryRound) {
  const PolyMesh exact = Grid("hyperboloid", 11);
  const PolyMesh mesh = Grid("hyperboloid", 11, 0.03, 4);
  HNetOptions options;
  options.anet.vertices.fixed = {0, 10, 60};
  HNet hnet(mesh, &exact, options);
  const HNetSummary summary = hnet.Run();
  ASSERT_TRUE(summary.report.converged) << summary.report.termination;
  ASSERT_FALSE(summary.rounds.empty());
  for (int v : options.anet.vertices.fixed)
    EXPECT_EQ(hnet.mesh().point(hnet.mesh().vertex_handle(v)), mesh.point(mesh.vertex_handle(v)))
        << v;
  EXPECT_GT(MaxDisplacement(hnet.mesh(), mesh), 1e-4);  // the others moved
}

// A flat grid (all stars planar in one plane) has no asymptotic directions: the weights come
// out undefined, and the run stops saying so and naming a face, instead of "the start x is not
// finite".
TEST(HNetTest, AFlatMeshStopsWithADiagnosisNamingAFace) {
  PolyMesh flat = Grid("hypar", 7);
  for (auto v : flat.vertices()) {
    auto p = flat.point(v);
    p[2] = 0.0;
    flat.set_point(v, p);
  }
  HNet hnet(flat, nullptr, HNetOptions());
  const HNetSummary summary = hnet.Run();
  EXPECT_TRUE(summary.report.failed);
  EXPECT_NE(summary.report.termination.find("face "), std::string::npos)
      << summary.report.termination;
  EXPECT_NE(summary.report.termination.find("negative Gaussian curvature"), std::string::npos)
      << summary.report.termination;
}

// The rounds' formulas multiply coordinates: a mesh at 1e150 is refused up front with the
// reason, instead of failing after the A-net step with undefined weights.
TEST(HNetTest, RefusesAScaleItsFormulasCannotTake) {
  PolyMesh huge = Grid("hyperboloid", 7);
  for (auto v : huge.vertices()) huge.set_point(v, huge.point(v) * 1e150);
  try {
    HNet hnet(huge, nullptr, HNetOptions());
    FAIL() << "accepted";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("rescale the mesh"), std::string::npos) << e.what();
  }
  PolyMesh small = Grid("hyperboloid", 7);
  for (auto v : small.vertices()) small.set_point(v, small.point(v) * 1e-6);
  EXPECT_NO_THROW(HNet(small, nullptr, HNetOptions()));
}

TEST(HNetTest, RefusesMeshesThatAreNotSimplyConnected) {
  // A 4 × 4 grid with the middle face removed: an annulus.
  PolyMesh grid = Grid("hypar", 5);
  PolyMesh annulus;
  for (auto v : grid.vertices()) annulus.add_vertex(grid.point(v));
  int k = 0;
  for (auto f : grid.faces()) {
    if (k++ == 5) continue;
    std::vector<PolyMesh::VertexHandle> vs;
    for (auto fv : grid.fv_range(f)) vs.push_back(PolyMesh::VertexHandle(fv.idx()));
    annulus.add_face(vs);
  }
  EXPECT_NE(SimplyConnectedProblem(annulus), "");
  EXPECT_EQ(SimplyConnectedProblem(grid), "");
  try {
    HNet hnet(annulus, nullptr, HNetOptions());
    FAIL() << "annulus accepted";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("not simply connected"), std::string::npos) << e.what();
  }
  HNetOptions allow;
  allow.allow_not_simply_connected = true;
  EXPECT_NO_THROW(HNet(annulus, nullptr, allow));
}

}  // namespace
}  // namespace gproj::nets
