#include "gproj/constraints/edge_parallelism.h"

#include <gtest/gtest.h>

#include <Eigen/Geometry>
#include <random>

#include "constraint_test_util.h"

namespace gproj {
namespace {

TEST(EdgeParallelismTest, GradientMatchesFiniteDifferences) {
  EdgeParallelism family;
  family.AddEdge(0, 1, Eigen::Vector3d(0.3, -1.0, 0.7));
  family.Prepare();  // the term declared quadratic: evaluated from its coefficients
  std::mt19937 rng(2);
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  for (int trial = 0; trial < 4; ++trial) {
    std::vector<double> x(6);
    for (double& v : x) v = u(rng);
    ExpectGradientMatchesFiniteDifferences(family, 0, x);
  }
}

TEST(EdgeParallelismTest, ZeroOnParallelAndAntiParallelEdgesOnly) {
  EdgeParallelism family;
  const Eigen::Vector3d d(0.3, -1.0, 0.7);
  family.AddEdge(0, 1, d);
  family.Prepare();
  std::vector<double> phi(3), jac(18);
  for (double s : {2.5, -0.4}) {
    const std::vector<double> x = {1, 2, 3, 1 + s * d.x(), 2 + s * d.y(), 3 + s * d.z()};
    family.EvaluateElement(0, x.data(), phi.data(), jac.data());
    for (double p : phi) EXPECT_NEAR(p, 0.0, 1e-15);
  }
  const std::vector<double> skew = {0, 0, 0, d.x(), d.y() + 0.1, d.z()};
  family.EvaluateElement(0, skew.data(), phi.data(), jac.data());
  EXPECT_NEAR(Eigen::Vector3d(phi[0], phi[1], phi[2]).norm(),
              d.normalized().cross(Eigen::Vector3d(0, 0.1, 0)).norm(), 1e-15);
}

TEST(EdgeVectorTest, GradientAndResidual) {
  EdgeVector family;
  family.AddEdge(0, 1, Eigen::Vector3d(1, 2, 3));
  family.Prepare();
  ExpectGradientMatchesFiniteDifferences(family, 0, {0.1, 0.2, 0.3, 0.5, -0.4, 2.0});
  std::vector<double> phi(3), jac(18);
  const std::vector<double> x = {1, 1, 1, 2, 3, 4};
  family.EvaluateElement(0, x.data(), phi.data(), jac.data());
  for (double p : phi) EXPECT_EQ(p, 0.0);
}

}  // namespace
}  // namespace gproj
