#include "gproj/geometry/surface/rational_bezier.h"

#include <gtest/gtest.h>

#include <Eigen/Geometry>
#include <random>

namespace gproj {
namespace {

RationalBezierPatch RandomPatch(int du, int dv, std::uint32_t seed) {
  std::mt19937 rng(seed);
  std::uniform_real_distribution<double> coordinate(-1.0, 1.0), weight(0.5, 2.0);
  RationalBezierPatch patch(du, dv);
  for (int i = 0; i <= du; ++i)
    for (int j = 0; j <= dv; ++j) {
      const double w = weight(rng);
      const Eigen::Vector3d p(i + 0.3 * coordinate(rng), j + 0.3 * coordinate(rng),
                              coordinate(rng));
      patch.At(i, j) << w * p, w;
    }
  return patch;
}

TEST(RationalBezierTest, DerivativesMatchFiniteDifferences) {
  for (auto [du, dv] : {std::pair{1, 1}, {2, 2}, {3, 2}}) {
    const RationalBezierPatch patch = RandomPatch(du, dv, 7 + du + dv);
    const double u = 0.37, v = 0.61, h = 1e-5;
    const PatchJet jet = EvaluateJet(patch, u, v);
    const auto point = [&](double a, double b) { return EvaluatePoint(patch, a, b); };
    const auto du_at = [&](double a, double b) { return EvaluateJet(patch, a, b).du; };
    const auto dv_at = [&](double a, double b) { return EvaluateJet(patch, a, b).dv; };
    EXPECT_LT((jet.point - point(u, v)).norm(), 1e-14);
    EXPECT_LT((jet.du - (point(u + h, v) - point(u - h, v)) / (2 * h)).norm(), 1e-8);
    EXPECT_LT((jet.dv - (point(u, v + h) - point(u, v - h)) / (2 * h)).norm(), 1e-8);
    EXPECT_LT((jet.duu - (du_at(u + h, v) - du_at(u - h, v)) / (2 * h)).norm(), 1e-7);
    EXPECT_LT((jet.duv - (du_at(u, v + h) - du_at(u, v - h)) / (2 * h)).norm(), 1e-7);
    EXPECT_LT((jet.dvv - (dv_at(u, v + h) - dv_at(u, v - h)) / (2 * h)).norm(), 1e-7);
  }
}

TEST(RationalBezierTest, ProductOfBernsteinCoefficientsIsTheProduct) {
  std::mt19937 rng(3);
  std::uniform_real_distribution<double> x(-2.0, 2.0);
  std::vector<double> f(2 * 3), g(3 * 2);
  for (double& c : f) c = x(rng);
  for (double& c : g) c = x(rng);
  const std::vector<double> p = MultiplyBernstein(f, 1, 2, g, 2, 1);
  ASSERT_EQ(p.size(), 4u * 4u);
  // Evaluate scalar polynomials through a patch with weights 1 and the values in x.
  const auto evaluate = [](const std::vector<double>& c, int du, int dv, double u, double v) {
    RationalBezierPatch patch(du, dv);
    for (std::size_t k = 0; k < c.size(); ++k) patch.control[k] << c[k], 0, 0, 1;
    return EvaluatePoint(patch, u, v).x();
  };
  for (double u : {0.0, 0.2, 0.9})
    for (double v : {0.1, 0.5, 1.0})
      EXPECT_NEAR(evaluate(p, 3, 3, u, v), evaluate(f, 1, 2, u, v) * evaluate(g, 2, 1, u, v),
                  1e-13);
}

// A sphere of radius 2 as a rational biquadratic patch (an octant: weights 1, √2/2, 1/2):
// K = 1/4 everywhere, H = ±1/2.
TEST(RationalBezierTest, CurvatureOfASphereOctant) {
  const double s = std::sqrt(0.5);
  const Eigen::Vector3d p[3][3] = {{{0, 0, 2}, {0, 0, 2}, {0, 0, 2}},
                                   {{2, 0, 2}, {2, 2, 2}, {0, 2, 2}},
                                   {{2, 0, 0}, {2, 2, 0}, {0, 2, 0}}};
  const double w[3][3] = {{1, s, 1}, {s, 0.5, s}, {1, s, 1}};
  RationalBezierPatch patch(2, 2);
  for (int i = 0; i < 3; ++i)
    for (int j = 0; j < 3; ++j) patch.At(i, j) << w[i][j] * p[i][j], w[i][j];
  for (double u : {0.2, 0.5, 0.8})
    for (double v : {0.3, 0.7}) {
      const PatchJet jet = EvaluateJet(patch, u, v);
      EXPECT_NEAR(jet.point.norm(), 2.0, 1e-12);
      const PatchCurvature c = CurvatureOf(jet);
      EXPECT_NEAR(c.gaussian, 0.25, 1e-10);
      EXPECT_NEAR(std::abs(c.mean), 0.5, 1e-10);
      EXPECT_NEAR(std::abs(c.normal.dot(jet.point.normalized())), 1.0, 1e-12);
    }
}

}  // namespace
}  // namespace gproj
