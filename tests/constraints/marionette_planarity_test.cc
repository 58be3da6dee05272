#include "gproj/constraints/marionette_planarity.h"

#include <gtest/gtest.h>

#include <vector>

#include "constraint_test_util.h"

namespace gproj {
namespace {

TEST(MarionettePlanarityTest, GradientMatchesFiniteDifferencesOnBothPaths) {
  MarionettePlanarity family;
  family.AddQuad(0, 1, 2, 3, 0.7, 1.3);
  family.AddQuad(4, 5, 6, 7, -0.2, 0.4);
  for (int e : {0, 1}) ExpectGradientMatchesFiniteDifferences(family, e, {0.3, -1.1, 2.0, 0.5});
  family.Prepare();  // the term declared quadratic: evaluated from its coefficients
  for (int e : {0, 1}) ExpectGradientMatchesFiniteDifferences(family, e, {0.3, -1.1, 2.0, 0.5});
}

// Heights of a plane over a plan quad meet the row; any other height of C misses it by its
// offset.
TEST(MarionettePlanarityTest, ZeroForAPlaneOverThePlan) {
  const Eigen::Vector2d a(0, 0), b(2, 0.3), c(2.4, 1.9), d(-0.1, 1.5);
  double alpha = 0.0, beta = 0.0;
  ASSERT_TRUE(MarionettePlanarity::PlanCoefficients(a, b, c, d, &alpha, &beta));
  MarionettePlanarity family;
  family.AddQuad(0, 1, 2, 3, alpha, beta);
  family.Prepare();
  const auto height = [](const Eigen::Vector2d& p) { return 0.5 + 0.3 * p.x() - 0.7 * p.y(); };
  std::vector<double> z = {height(a), height(b), height(c), height(d)};
  double phi = 1.0, jac[4];
  family.EvaluateElement(0, z.data(), &phi, jac);
  EXPECT_NEAR(phi, 0.0, 1e-14);
  z[2] += 0.25;
  family.EvaluateElement(0, z.data(), &phi, jac);
  EXPECT_NEAR(phi, 0.25, 1e-14);
  EXPECT_DOUBLE_EQ(jac[2], 1.0);
}

}  // namespace
}  // namespace gproj
