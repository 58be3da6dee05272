#include "constraints/frozen_quad_planarity.h"

#include <gtest/gtest.h>

#include "constraint_test_util.h"

namespace gproj {
namespace {

// Four vertices of dimension 3 as items 0..3.
struct Fixture {
  VariableLayout layout;
  Eigen::VectorXd x;
  FrozenQuadPlanarity family;
  explicit Fixture(const std::vector<double>& points) {
    layout.AddBlock("vertices", 4, 3);
    x = Eigen::Map<const Eigen::VectorXd>(points.data(), 12);
    family.AddElement({0, 1, 2, 3});
    family.Update(layout, x);
  }
};

TEST(FrozenQuadPlanarityTest, GradientMatchesFiniteDifferencesWithFrozenNormal) {
  Fixture f({0, 0, 0, 1, 0, 0.2, 1.1, 1, 0, 0, 0.9, -0.1});
  ExpectGradientMatchesFiniteDifferences(f.family, 0,
                                         std::vector<double>(f.x.data(), f.x.data() + 12));
}

TEST(FrozenQuadPlanarityTest, ZeroOnPlanarQuadAndDiagonalDistanceOtherwise) {
  Fixture planar({0, 0, 1, 2, 0, 1, 2, 1.5, 1, -0.2, 1, 1});
  double phi, jac[12];
  planar.family.EvaluateElement(0, planar.x.data(), &phi, jac);
  EXPECT_NEAR(phi, 0.0, 1e-15);
  // Diagonals (0,0,0)-(1,1,0) and (1,0,h)-(0,1,h): skew at distance h; n·d = ±h.
  const double h = 0.3;
  Fixture skew({0, 0, 0, 1, 0, h, 1, 1, 0, 0, 1, h});
  skew.family.EvaluateElement(0, skew.x.data(), &phi, jac);
  EXPECT_NEAR(std::abs(phi), h, 1e-15);
}

}  // namespace
}  // namespace gproj
