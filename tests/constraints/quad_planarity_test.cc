#include "gproj/constraints/quad_planarity.h"

#include <gtest/gtest.h>

#include <Eigen/Geometry>
#include <random>

#include "constraint_test_util.h"

namespace gproj {
namespace {

TEST(QuadPlanarityTest, GradientMatchesFiniteDifferences) {
  QuadPlanarity family;
  family.AddQuad(0, 1, 2, 3, 4);
  family.Prepare();  // evaluated from its quadratic coefficients
  std::mt19937 rng(3);
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  for (int trial = 0; trial < 5; ++trial) {
    std::vector<double> x(15);
    for (double& v : x) v = u(rng);
    ExpectGradientMatchesFiniteDifferences(family, 0, x);
  }
}

TEST(QuadPlanarityTest, ZeroResidualOnPlanarQuadWithItsNormal) {
  QuadPlanarity family;
  family.AddQuad(0, 1, 2, 3, 4);
  // A planar, non-rectangular quad in the plane through (1,2,3) with normal (1,1,1)/√3.
  const Eigen::Vector3d n = Eigen::Vector3d(1, 1, 1).normalized();
  const Eigen::Vector3d t1 = Eigen::Vector3d(1, -1, 0).normalized(), t2 = n.cross(t1);
  const Eigen::Vector3d o(1, 2, 3);
  const Eigen::Vector3d v[4] = {o, o + 2.0 * t1, o + 1.5 * t1 + 1.2 * t2, o - 0.3 * t1 + t2};
  const Eigen::Vector3d n0 = QuadPlanarity::InitialNormal(v[0], v[1], v[2], v[3]);
  EXPECT_NEAR(std::abs(n0.dot(n)), 1.0, 1e-14);
  std::vector<double> x(15);
  for (int c = 0; c < 3; ++c) {
    x[c] = n0[c];
    for (int j = 0; j < 4; ++j) x[3 + 3 * j + c] = v[j][c];
  }
  std::vector<double> phi(5), jac(75);
  family.EvaluateElement(0, x.data(), phi.data(), jac.data());
  for (int r = 0; r < 5; ++r) EXPECT_NEAR(phi[r], 0.0, 1e-14) << "row " << r;
}

TEST(QuadPlanarityTest, NonPlanarQuadHasResidual) {
  QuadPlanarity family;
  family.AddQuad(0, 1, 2, 3, 4);
  const Eigen::Vector3d v[4] = {{0, 0, 0}, {1, 0, 0}, {1, 1, 0.2}, {0, 1, 0}};
  const Eigen::Vector3d n = QuadPlanarity::InitialNormal(v[0], v[1], v[2], v[3]);
  std::vector<double> x(15), phi(5), jac(75);
  for (int c = 0; c < 3; ++c) {
    x[c] = n[c];
    for (int j = 0; j < 4; ++j) x[3 + 3 * j + c] = v[j][c];
  }
  family.EvaluateElement(0, x.data(), phi.data(), jac.data());
  double max_abs = 0.0;
  for (int r = 0; r < 4; ++r) max_abs = std::max(max_abs, std::abs(phi[r]));
  EXPECT_GT(max_abs, 0.05);
  EXPECT_NEAR(phi[4], 0.0, 1e-14);
}

}  // namespace
}  // namespace gproj
