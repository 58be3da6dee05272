#include "gproj/constraints/surface_closeness.h"

#include <gtest/gtest.h>

#include "constraint_test_util.h"

namespace gproj {
namespace {

// The unit sphere: closest point q/|q|, normal the same.
void Sphere(const Eigen::Vector3d& q, Eigen::Vector3d* p, Eigen::Vector3d* n) {
  *p = q.normalized();
  *n = *p;
}

TEST(SurfaceClosenessTest, TangentRowIsSignedDistanceToTheTangentPlane) {
  VariableLayout layout;
  layout.AddBlock("v", 1, 3);
  Eigen::VectorXd x(3);
  x << 0.0, 0.0, 1.5;
  SurfaceTangentCloseness tangent(Sphere, 1.0);
  tangent.AddPoint(0);
  tangent.Update(layout, x);
  double phi, jac[3];
  tangent.EvaluateElement(0, x.data(), &phi, jac);
  EXPECT_DOUBLE_EQ(phi, 0.5);
  // A point sliding in the tangent plane keeps the frozen row at zero distance change.
  const double slid[3] = {0.3, -0.2, 1.0};
  tangent.EvaluateElement(0, slid, &phi, jac);
  EXPECT_NEAR(phi, 0.0, 1e-15);
  ExpectGradientMatchesFiniteDifferences(tangent, 0, {0.1, 0.2, 1.3});
}

TEST(SurfaceClosenessTest, PointRowsVanishOnTheSurface) {
  VariableLayout layout;
  layout.AddBlock("v", 1, 3);
  Eigen::VectorXd x(3);
  x << 0.6, 0.0, 0.8;
  SurfacePointCloseness point(Sphere, 1.0);
  point.AddPoint(0);
  point.Update(layout, x);
  double phi[3], jac[9];
  point.EvaluateElement(0, x.data(), phi, jac);
  for (double v : phi) EXPECT_NEAR(v, 0.0, 1e-15);
  ExpectGradientMatchesFiniteDifferences(point, 0, {0.1, 0.2, 1.3});
}

}  // namespace
}  // namespace gproj
