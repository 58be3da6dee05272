#include "gproj/constraints/frame_point_planarity.h"

#include <gtest/gtest.h>

#include <Eigen/Geometry>

#include "constraint_test_util.h"

namespace gproj {
namespace {

TEST(FramePointPlanarityTest, GradientMatchesFiniteDifferences) {
  FramePointPlanarity family;
  family.AddEdge(0, 1, 2, 3, 4, 5, 6, 1.7, 0.6);
  std::vector<double> x = {0.2, -0.4, 0.9};
  for (int i = 0; i < 18; ++i) x.push_back(std::sin(1.3 * i + 0.2));
  ExpectGradientMatchesFiniteDifferences(family, 0, x);
}

TEST(FramePointPlanarityTest, ZeroWhenFramePointsLieInAPlaneThroughTheEdge) {
  // b0, b3 on the x axis; choose b1, b2, b4, b5 so that f1 and f4 are in the plane z = 0.
  const double wl = 2.0, wr = 0.5;
  const Eigen::Vector3d b0(0, 0, 0), b3(1, 0, 0), b1(0, 1, 0.4), b2(1, 1.2, -0.2);  // f1: z = 0
  const Eigen::Vector3d b4(1.1, -1, 0.6), b5(0, -1, -0.3);                          // f4: z = 0
  ASSERT_NEAR(((b1 + wl * b2) / (1 + wl)).z(), 0.0, 1e-15);
  ASSERT_NEAR(((b5 + wr * b4) / (1 + wr)).z(), 0.0, 1e-15);
  FramePointPlanarity family;
  family.AddEdge(0, 1, 2, 3, 4, 5, 6, wl, wr);
  std::vector<double> x = {0, 0, 1};
  for (const auto& b : {b0, b1, b2, b3, b4, b5})
    for (int c = 0; c < 3; ++c) x.push_back(b[c]);
  double phi[4], jac[84];
  family.EvaluateElement(0, x.data(), phi, jac);
  for (double v : phi) EXPECT_NEAR(v, 0.0, 1e-15);
  // Other weights move the frame points off the plane.
  family.SetShapeParameters(0, 1.0, 1.0);
  family.EvaluateElement(0, x.data(), phi, jac);
  EXPECT_GT(std::abs(phi[0]) + std::abs(phi[2]), 0.05);
}

}  // namespace
}  // namespace gproj
