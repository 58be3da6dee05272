#include "gproj/problems/weingarten/helical_fit.h"

#include <gtest/gtest.h>

#include <cmath>

#include "gproj/common/input_error.h"

namespace gproj::weingarten {
namespace {

// The helical test surface (10 × 12 bi-quartic), with a dent that breaks the symmetry.
BSplineSurface Helical(double bump) {
  HelicalTestSurface spec;
  spec.bump = bump;
  return MakeHelicalBSpline(10, 12, 4, spec);
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
}  // namespace gproj::weingarten
