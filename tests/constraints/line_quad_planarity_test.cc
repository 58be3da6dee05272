#include "gproj/constraints/line_quad_planarity.h"

#include <gtest/gtest.h>

#include <Eigen/Geometry>
#include <random>

#include "constraint_test_util.h"

namespace gproj {
namespace {

TEST(LineQuadPlanarityTest, GradientMatchesFiniteDifferences) {
  std::mt19937 rng(5);
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  std::array<Eigen::Vector3d, 4> o, d;
  for (int j = 0; j < 4; ++j) {
    o[j] = Eigen::Vector3d(u(rng), u(rng), u(rng));
    d[j] = Eigen::Vector3d(u(rng), u(rng), u(rng)).normalized();
  }
  LineQuadPlanarity family;
  family.AddQuad(0, {1, 2, 3, 4}, o, d);
  family.Prepare();  // the term declared quadratic: evaluated from its coefficients
  for (int trial = 0; trial < 5; ++trial) {
    std::vector<double> x(7);
    for (double& v : x) v = u(rng);
    ExpectGradientMatchesFiniteDifferences(family, 0, x);
  }
}

TEST(LineQuadPlanarityTest, ZeroResidualWhenThePointsOnTheLinesAreCoplanar) {
  // Four points of the plane z = 0.5 x + 1 on lines through the origin (a central projection).
  const Eigen::Vector3d p[4] = {{1, 0, 1.5}, {2, 0.2, 2}, {1.8, 1.5, 1.9}, {0.9, 1.2, 1.45}};
  std::array<Eigen::Vector3d, 4> o, d;
  std::vector<double> x(7);
  for (int j = 0; j < 4; ++j) {
    o[j] = Eigen::Vector3d::Zero();
    d[j] = p[j].normalized();
    x[3 + j] = p[j].norm();
  }
  const Eigen::Vector3d n = Eigen::Vector3d(-0.5, 0, 1).normalized();
  for (int c = 0; c < 3; ++c) x[c] = n[c];
  LineQuadPlanarity family;
  family.AddQuad(0, {1, 2, 3, 4}, o, d);
  family.Prepare();  // the term declared quadratic: evaluated from its coefficients
  std::vector<double> phi(5), jac(35);
  family.EvaluateElement(0, x.data(), phi.data(), jac.data());
  for (double r : phi) EXPECT_NEAR(r, 0.0, 1e-14);
  // Moving one point along its line breaks it.
  x[5] += 0.1;
  family.EvaluateElement(0, x.data(), phi.data(), jac.data());
  EXPECT_GT(std::abs(phi[1]) + std::abs(phi[2]), 1e-3);
}

}  // namespace
}  // namespace gproj
