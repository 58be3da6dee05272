#include "gproj/constraints/closeness.h"

#include <gtest/gtest.h>

#include "constraint_test_util.h"

namespace gproj {
namespace {

TEST(ClosenessTest, GradientMatchesFiniteDifferences) {
  Closeness family(3);
  const double target[3] = {1.0, -2.0, 0.5};
  family.AddTarget(0, target);
  ExpectGradientMatchesFiniteDifferences(family, 0, {0.3, 0.2, -0.1});
}

TEST(ClosenessTest, ZeroAtTargetAndDisplacementOtherwise) {
  Closeness family(3);
  const double a[3] = {1.0, -2.0, 0.5}, b[3] = {0.0, 0.0, 4.0};
  family.AddTarget(0, a);
  family.AddTarget(1, b);
  double phi[3], jac[9];
  family.EvaluateElement(1, b, phi, jac);
  for (double v : phi) EXPECT_EQ(v, 0.0);
  family.EvaluateElement(0, b, phi, jac);
  EXPECT_DOUBLE_EQ(phi[0], -1.0);
  EXPECT_DOUBLE_EQ(phi[1], 2.0);
  EXPECT_DOUBLE_EQ(phi[2], 3.5);
  EXPECT_EQ(family.role(), FamilyRole::kSoft);
}

}  // namespace
}  // namespace gproj
