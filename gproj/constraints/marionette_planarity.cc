#include "gproj/constraints/marionette_planarity.h"

#include <algorithm>
#include <cmath>

namespace gproj {

bool MarionettePlanarity::PlanCoefficients(const Eigen::Vector2d& a, const Eigen::Vector2d& b,
                                           const Eigen::Vector2d& c, const Eigen::Vector2d& d,
                                           double* alpha, double* beta, double tolerance) {
  auto cross = [](const Eigen::Vector2d& u, const Eigen::Vector2d& v) {
    return u.x() * v.y() - u.y() * v.x();
  };
  Eigen::Vector2d ab = b - a, ac = c - a, ad = d - a;
  // Scaled by a power of two (exactly) to an extent near 1, so that the cross products neither
  // overflow nor underflow for any finite plan; alpha and beta are ratios and do not change.
  const double extent =
      std::max({ab.cwiseAbs().maxCoeff(), ac.cwiseAbs().maxCoeff(), ad.cwiseAbs().maxCoeff()});
  if (extent > 0.0 && std::isfinite(extent)) {
    const int exponent = -std::ilogb(extent);
    for (Eigen::Vector2d* v : {&ab, &ac, &ad})
      *v = v->unaryExpr([&](double x) { return std::ldexp(x, exponent); });
  }
  const double det = cross(ab, ad);
  if (!(std::abs(det) > tolerance * ab.norm() * ad.norm())) return false;
  *alpha = cross(ac, ad) / det;
  *beta = cross(ab, ac) / det;
  return true;
}

}  // namespace gproj
