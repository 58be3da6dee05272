#include <gtest/gtest.h>

#include <Eigen/Geometry>
#include <random>

#include "constraint_test_util.h"
#include "gproj/constraints/control_net.h"
#include "gproj/constraints/curvature_relations.h"
#include "gproj/constraints/geodesic_parallel_isolines.h"
#include "gproj/constraints/isoline_alignment.h"

namespace gproj {
namespace {

std::vector<double> Random(int n, uint32_t seed, double lo = -1.0, double hi = 1.0) {
  std::mt19937 rng(seed);
  std::uniform_real_distribution<double> u(lo, hi);
  std::vector<double> x(n);
  for (double& v : x) v = u(rng);
  return x;
}

// A stencil of four control points with random derivative weights.
SampleStencil RandomStencil(uint32_t seed) {
  SampleStencil s;
  s.control = {0, 1, 2, 3};
  const auto w = Random(20, seed);
  for (int k = 0; k < 5; ++k) s.weights[k].assign(w.begin() + 4 * k, w.begin() + 4 * k + 4);
  return s;
}

TEST(CurvatureAuxiliariesTest, GradientMatchesFiniteDifferences) {
  CurvatureAuxiliaries family;
  family.AddSample(0, 1, {2, 3, 4, 5}, RandomStencil(3));
  for (uint32_t seed : {1u, 2u, 3u}) {
    std::vector<double> x = Random(24, seed);
    x[kDelta] = 0.8;  // keep away from zero
    ExpectGradientMatchesFiniteDifferences(family, 0, x, 1e-6, 2e-7);
  }
}

TEST(CurvatureAuxiliariesTest, ExactAuxiliaryGivesZeroResidualAndKnownCurvatures) {
  // Sphere of radius 2 at the point (0, 0, 2)·R, parametrised by (u, v) ↦ R(sin u cos v, ...):
  // take the derivatives at u = 0.7, v = 0.3 directly as a four-point stencil with unit weights.
  const double r = 2.0, u = 0.7, v = 0.3;
  const Eigen::Vector3d su(r * std::cos(u) * std::cos(v), r * std::cos(u) * std::sin(v),
                           -r * std::sin(u));
  const Eigen::Vector3d sv(-r * std::sin(u) * std::sin(v), r * std::sin(u) * std::cos(v), 0.0);
  const Eigen::Vector3d suu(-r * std::sin(u) * std::cos(v), -r * std::sin(u) * std::sin(v),
                            -r * std::cos(u));
  const Eigen::Vector3d suv(-r * std::cos(u) * std::sin(v), r * std::cos(u) * std::cos(v), 0.0);
  const Eigen::Vector3d svv(-r * std::sin(u) * std::cos(v), -r * std::sin(u) * std::sin(v), 0.0);
  const auto a = CurvatureAuxiliaries::ExactAuxiliary({su, sv, suu, suv, svv});
  EXPECT_NEAR(a[kK], 1.0 / (r * r), 1e-12);
  EXPECT_NEAR(std::abs(a[kH]), 1.0 / r, 1e-12);
  // Five control "points" that are the derivatives themselves, weights picking one each.
  SampleStencil stencil;
  stencil.control = {0, 1, 2, 3, 4};
  for (int k = 0; k < 5; ++k) {
    stencil.weights[k].assign(5, 0.0);
    stencil.weights[k][k] = 1.0;
  }
  CurvatureAuxiliaries family;
  VariableLayout layout;
  const int forms = layout.AddBlock("forms", 1, kFormsDim, /*eliminable=*/true);
  const int curvature = layout.AddBlock("curvature", 1, kCurvatureDim);
  const int control = layout.AddBlock("c", 5, 3);
  family.AddSample(layout.Item(forms, 0), layout.Item(curvature, 0),
                   {layout.Item(control, 0), layout.Item(control, 1), layout.Item(control, 2),
                    layout.Item(control, 3), layout.Item(control, 4)},
                   stencil);
  Eigen::VectorXd x(layout.num_variables());
  x.head<12>() = a;
  const Eigen::Vector3d d[5] = {su, sv, suu, suv, svv};
  for (int k = 0; k < 5; ++k) x.segment<3>(12 + 3 * k) = d[k];
  family.Update(layout, x);
  std::vector<double> phi(12), jac(12 * 27);
  family.EvaluateElement(0, x.data(), phi.data(), jac.data());
  for (int r = 0; r < 12; ++r) EXPECT_NEAR(phi[r], 0.0, 1e-12) << "row " << r;
}

TEST(SurfaceLinearWeingartenTest, GradientAndValueOnTheSurfaceItself) {
  const Eigen::Vector3d abc(0.6, -0.8, 0.3);
  SurfaceLinearWeingarten family(1.0, abc, 2.0);
  family.AddSample({0, 1, 2, 3}, RandomStencil(5));
  for (uint32_t seed : {4u, 5u, 6u}) {
    const std::vector<double> x = Random(12, seed);
    ExpectGradientMatchesFiniteDifferences(family, 0, x, 1e-6, 1e-6);
    // The value is the relation at the exact H and K of the stencil's derivatives.
    std::array<Eigen::Vector3d, 5> d;
    for (int k = 0; k < 5; ++k) {
      d[k].setZero();
      for (int j = 0; j < 4; ++j)
        d[k] += RandomStencil(5).weights[k][j] * Eigen::Vector3d(&x[3 * j]);
    }
    const auto a = CurvatureAuxiliaries::ExactAuxiliary(d);
    double phi = 0.0;
    std::vector<double> jac(12);
    family.EvaluateElement(0, x.data(), &phi, jac.data());
    const double row_scale = 1.0 / (0.6 * 2.0 + 0.8 * 4.0);  // |a| κ + |b| κ²
    EXPECT_NEAR(phi, row_scale * (abc[0] * a[kH] + abc[1] * a[kK] + abc[2]), 1e-12);
  }
}

TEST(IsolineAlignmentTest, GradientAndZeroWhenHIsAFunctionOfK) {
  IsolineAlignment family(1.0);
  family.AddSample(0, 1, 2, 3, 0.7, 1.3);
  ExpectGradientMatchesFiniteDifferences(family, 0, Random(4 * kCurvatureDim, 5));
  // H = 2 K + 1 at every sample: aligned isolines.
  std::vector<double> x = Random(4 * kCurvatureDim, 6);
  for (int s = 0; s < 4; ++s)
    x[kCurvatureDim * s + kCurvatureH] = 2.0 * x[kCurvatureDim * s + kCurvatureK] + 1.0;
  std::vector<double> phi(1), jac(4 * kCurvatureDim);
  family.EvaluateElement(0, x.data(), phi.data(), jac.data());
  EXPECT_NEAR(phi[0], 0.0, 1e-14);
  x[kCurvatureH] += 0.3;  // break it
  family.EvaluateElement(0, x.data(), phi.data(), jac.data());
  EXPECT_GT(std::abs(phi[0]), 1e-3);
}

TEST(GeodesicParallelTest, GradientsMatchFiniteDifferences) {
  GeodesicAuxiliaries definitions;
  definitions.AddSample(0, 1, 2, 3, 4, 5, 0.6, 0.9);
  std::vector<double> x = Random(kGeodesicAuxDim + kFormsDim + 4 * kCurvatureDim, 7);
  ExpectGradientMatchesFiniteDifferences(definitions, 0, x);
  GeodesicParallelIsolines parallel(1.0);
  parallel.AddSample({0, 1, 2, 3}, {4, 5, 6, 7}, 0.6, 0.9);
  ExpectGradientMatchesFiniteDifferences(parallel, 0,
                                         Random(4 * (kGeodesicAuxDim + kCurvatureDim), 8));
}

// 003 Lemma 2.1 and eq. 7: a distance function has ‖∇ₛψ‖² = 1. On the plane with the skewed
// parametrisation s(u, v) = (u + v/2, 0.8 v, 0) (E = 1, F = ½, G = 0.89, Δ = 0.64), ψ = x =
// u + v/2 is the distance to the y-axis: with ‖∇ψ‖² = 1 and the exact ψ_u², ψ_u ψ_v, ψ_v² the
// gradient definitions vanish, neighbours' ψ given by central differences. §3.2.1 prints E and
// G swapped, which gives (E ψ_u² − 2F ψ_u ψ_v + G ψ_v²) / Δ = 1.1289 instead.
TEST(GeodesicParallelTest, DistanceFunctionHasUnitGradientByEquation7) {
  const double E = 1.0, F = 0.5, G = 0.89, D = E * G - F * F, pu = 1.0, pv = 0.5, h = 0.1;
  VariableLayout layout;
  const int g = layout.AddBlock("g", 1, kGeodesicAuxDim);
  const int forms = layout.AddBlock("forms", 1, kFormsDim);
  const int c = layout.AddBlock("curvatures", 4, kCurvatureDim);
  GeodesicAuxiliaries family;
  family.AddSample(layout.Item(g, 0), layout.Item(forms, 0), layout.Item(c, 0), layout.Item(c, 1),
                   layout.Item(c, 2), layout.Item(c, 3), 1.0 / (2 * h), 1.0 / (2 * h));
  Eigen::VectorXd x = Eigen::VectorXd::Zero(layout.num_variables());
  double* gv = x.data() + layout.ItemOffset(layout.Item(g, 0));
  for (int p = 0; p < 2; ++p) {  // ψ is both K and H
    gv[3 * p] = pu * pu;
    gv[3 * p + 1] = pu * pv;
    gv[3 * p + 2] = pv * pv;
  }
  gv[kGradK] = gv[kGradH] = 1.0;
  double* f = x.data() + layout.ItemOffset(layout.Item(forms, 0));
  f[kE] = E, f[kF] = F, f[kG] = G, f[kDelta] = D;
  const double neighbour[4] = {pu * h, -pu * h, pv * h, -pv * h};  // ψ at (a±1, b), (a, b±1)
  for (int j = 0; j < 4; ++j)
    for (int o : {kCurvatureK, kCurvatureH})
      x[layout.ItemOffset(layout.Item(c, j)) + o] = neighbour[j];
  family.Update(layout, x);
  std::vector<double> phi(8), jac(8 * layout.num_variables());
  family.EvaluateElement(0, x.data(), phi.data(), jac.data());
  for (int r = 0; r < 8; ++r) EXPECT_NEAR(phi[r], 0.0, 1e-12) << "row " << r;
  EXPECT_NEAR((E * pu * pu - 2 * F * pu * pv + G * pv * pv) / D, 1.1289, 1e-4);
}

TEST(LinearWeingartenTest, FitLineRecoversTheRelation) {
  std::vector<double> h, k;
  for (int i = 0; i < 20; ++i) {
    h.push_back(0.1 * i - 1.0);
    k.push_back(3.0 * h.back() - 0.5);  // 3 H − K − 0.5 = 0
  }
  const Eigen::Vector3d abc = LinearWeingarten::FitLine(h, k);
  EXPECT_NEAR(abc.head<2>().norm(), 1.0, 1e-12);
  for (int i = 0; i < 20; ++i) EXPECT_NEAR(abc[0] * h[i] + abc[1] * k[i] + abc[2], 0.0, 1e-12);
}

TEST(CurvatureCurveRelationTest, FittedCurvePassesThroughPointsOfAParabola) {
  std::vector<double> h, k;
  for (int i = 0; i <= 40; ++i) {
    h.push_back(-1.0 + 0.05 * i);
    k.push_back(h.back() * h.back());
  }
  const auto curve = CurvatureCurveRelation::FitCurve(h, k, 8);
  for (int i = 0; i <= 40; i += 5) {
    const Eigen::Vector2d p(h[i], k[i]);
    EXPECT_LT((curve.Point(curve.ClosestParameter(p)) - p).norm(), 5e-3) << i;
  }
}

TEST(ControlNetTest, EdgeLengthAndGliding) {
  EdgeLengthPreservation length(1.0);
  length.AddEdge(0, 1, 2.0);
  ExpectGradientMatchesFiniteDifferences(length, 0, Random(6, 9));
  std::vector<double> phi(1), jac(6);
  const std::vector<double> x = {0, 0, 0, 0, 2, 0};
  length.EvaluateElement(0, x.data(), phi.data(), jac.data());
  EXPECT_NEAR(phi[0], 0.0, 1e-15);

  Eigen::Vector3d foot, direction;
  PolylineGliding::ClosestPoint({{0, 0, 0}, {1, 0, 0}, {1, 1, 0}}, {1.2, 0.4, 0.3}, &foot,
                                &direction);
  EXPECT_LT((foot - Eigen::Vector3d(1, 0.4, 0)).norm(), 1e-15);
  EXPECT_LT((direction - Eigen::Vector3d(0, 1, 0)).norm(), 1e-15);
}

}  // namespace
}  // namespace gproj
