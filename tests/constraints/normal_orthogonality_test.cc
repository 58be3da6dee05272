#include "gproj/constraints/normal_orthogonality.h"

#include <gtest/gtest.h>

#include "constraint_test_util.h"

namespace gproj {
namespace {

TEST(EdgeNormalOrthogonalityTest, GradientMatchesFiniteDifferences) {
  EdgeNormalOrthogonality family;
  family.Add({0, 1, 2});
  ExpectGradientMatchesFiniteDifferences(family, 0, {0.3, -0.5, 0.8, 1, 2, 3, -1, 0.5, 2});
}

TEST(EdgeNormalOrthogonalityTest, ZeroForAnEdgeInThePlane) {
  EdgeNormalOrthogonality family;
  family.Add({0, 1, 2});
  const double x[9] = {0, 0, 1, 1, 2, 5, -3, 4, 5};  // n = e_z, both points at z = 5
  double phi, jac[9];
  family.EvaluateElement(0, x, &phi, jac);
  EXPECT_EQ(phi, 0.0);
  const double y[9] = {0, 0, 1, 1, 2, 5, -3, 4, 5.25};
  family.EvaluateElement(0, y, &phi, jac);
  EXPECT_DOUBLE_EQ(phi, 0.25);
}

TEST(UnitNormalTest, GradientAndZeroOnUnitVectors) {
  UnitNormal family;
  family.Add({0});
  ExpectGradientMatchesFiniteDifferences(family, 0, {0.3, -0.5, 0.8});
  const double n[3] = {0.6, 0.0, -0.8};
  double phi, jac[3];
  family.EvaluateElement(0, n, &phi, jac);
  EXPECT_NEAR(phi, 0.0, 1e-15);
}

}  // namespace
}  // namespace gproj
