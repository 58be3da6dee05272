#include "geometry/helical_fit.h"

#include <gtest/gtest.h>

#include <cmath>

#include "geometry/input_error.h"

namespace gproj {
namespace {

// A helical surface: the profile z = 0.3 (r − 1.5)², r ∈ [1, 2], swept by half a turn about the
// z-axis with pitch 0.4 (per radian), plus `bump` × a smooth bump that breaks the symmetry;
// fitted by a bi-quartic B-spline of 10 × 12 control points.
BSplineSurface Helical(double bump) {
  return FitBSpline(
      [bump](double u, double v) {
        const double r = 1.0 + u, theta = M_PI * v;
        const double z = 0.3 * (r - 1.5) * (r - 1.5) + 0.4 * theta +
                         bump * std::exp(-20.0 * ((u - 0.5) * (u - 0.5) + (v - 0.4) * (v - 0.4)));
        return Eigen::Vector3d(r * std::cos(theta), r * std::sin(theta), z);
      },
      4, 4, 10, 12);
}

TEST(HelicalFitTest, RecoversTheMotionOfAHelicalSurface) {
  const HelicalDeviation d = MeasureHelicalDeviation(Helical(0.0), 30, 30);
  EXPECT_NEAR(std::abs(d.motion.axis.z()), 1.0, 1e-6);
  EXPECT_NEAR(d.motion.pitch, 0.4, 1e-5);
  EXPECT_LT(d.motion.axis_point.norm(), 1e-5);
  EXPECT_NEAR(d.mean_radius, 1.5, 0.01);
  EXPECT_LT(d.max_percent, 0.01);  // the B-spline fit's own error
}

TEST(HelicalFitTest, RotationalSurfaceHasPitchZero) {
  const BSplineSurface sphere_zone = FitBSpline(
      [](double u, double v) {
        const double polar = 0.6 + 0.8 * u, theta = 2.0 * v;
        return Eigen::Vector3d(2.0 * std::sin(polar) * std::cos(theta) + 1.0,
                               2.0 * std::sin(polar) * std::sin(theta) - 3.0,
                               2.0 * std::cos(polar));
      },
      4, 4, 8, 8);
  const HelicalDeviation d = MeasureHelicalDeviation(sphere_zone, 24, 24);
  EXPECT_LT(std::abs(d.motion.pitch), 1e-5);
  // A sphere turns in itself about every axis through its centre: the fitted one passes
  // through (1, −3, 0).
  const Eigen::Vector3d centre(1.0, -3.0, 0.0);
  const Eigen::Vector3d off = centre - d.motion.axis_point;
  EXPECT_LT((off - off.dot(d.motion.axis) * d.motion.axis).norm(), 1e-4);
  EXPECT_LT(d.max_percent, 0.01);
}

// The deviation grows with the bump that breaks the symmetry, roughly in proportion.
TEST(HelicalFitTest, DeviationGrowsWithTheDistanceFromHelical) {
  const double small = MeasureHelicalDeviation(Helical(0.02), 30, 30).max_percent;
  const double large = MeasureHelicalDeviation(Helical(0.08), 30, 30).max_percent;
  EXPECT_GT(small, 0.1);
  EXPECT_GT(large, 3.0 * small);
  EXPECT_LT(large, 5.0 * small);
}

TEST(HelicalFitTest, RefusesTooFewPoints) {
  EXPECT_THROW(FitHelicalMotion(Eigen::MatrixX3d::Zero(5, 3), Eigen::MatrixX3d::Zero(5, 3)),
               InputError);
  EXPECT_THROW(FitHelicalMotion(Eigen::MatrixX3d::Zero(8, 3), Eigen::MatrixX3d::Zero(7, 3)),
               InputError);
}

}  // namespace
}  // namespace gproj
