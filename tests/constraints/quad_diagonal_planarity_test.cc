#include "gproj/constraints/quad_diagonal_planarity.h"

#include <gtest/gtest.h>

#include "constraint_test_util.h"

namespace gproj {
namespace {

TEST(QuadDiagonalPlanarityTest, GradientMatchesFiniteDifferences) {
  QuadDiagonalPlanarity family;
  family.Add({0, 1, 2, 3});
  ExpectGradientMatchesFiniteDifferences(family, 0, {0, 0, 0, 1, 0, 0.2, 1.1, 1, 0, 0, 0.9, -0.1});
  ExpectGradientMatchesFiniteDifferences(
      family, 0, {0.3, -0.2, 0.1, 1.4, 0.1, 0.5, 0.2, 1.3, -0.4, -1.0, 0.6, 0.3});
}

TEST(QuadDiagonalPlanarityTest, ZeroOnPlanarQuadAndDiagonalDistanceOtherwise) {
  QuadDiagonalPlanarity family;
  family.Add({0, 1, 2, 3});
  const double planar[12] = {0, 0, 1, 2, 0, 1, 2, 1.5, 1, -0.2, 1, 1};
  double phi, jac[12];
  family.EvaluateElement(0, planar, &phi, jac);
  EXPECT_NEAR(phi, 0.0, 1e-15);
  // Diagonals (0,0,0)-(1,1,0) and (1,0,h)-(0,1,h) are skew at distance h; n·d = ±h.
  const double h = 0.3;
  const double skew[12] = {0, 0, 0, 1, 0, h, 1, 1, 0, 0, 1, h};
  family.EvaluateElement(0, skew, &phi, jac);
  EXPECT_NEAR(std::abs(phi), h, 1e-15);
}

}  // namespace
}  // namespace gproj
