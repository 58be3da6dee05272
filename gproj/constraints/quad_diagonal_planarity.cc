#include "gproj/constraints/quad_diagonal_planarity.h"

#include <Eigen/Geometry>
#include <algorithm>

namespace gproj {

void QuadDiagonalPlanarity::EvaluateElement(int, const double* x, double* phi, double* jac) const {
  const Eigen::Map<const Eigen::Vector3d> b0(x), b1(x + 3), b2(x + 6), b3(x + 9);
  const Eigen::Vector3d a = b2 - b0, e = b3 - b1, c = a.cross(e);
  const Eigen::Vector3d d = 0.5 * (b0 + b2 - b1 - b3);
  const double length = c.norm();
  if (length == 0.0) {  // parallel diagonals: no normal; leave the row inert
    phi[0] = 0.0;
    std::fill(jac, jac + 12, 0.0);
    return;
  }
  const Eigen::Vector3d u = c / length;
  phi[0] = u.dot(d);
  const Eigen::Vector3d g = (d - phi[0] * u) / length;  // ∂φ/∂c
  const Eigen::Vector3d da = e.cross(g), de = g.cross(a);
  Eigen::Map<Eigen::Matrix<double, 3, 4>> gradient(jac);  // columns: ∂φ/∂b0 .. ∂φ/∂b3
  gradient.col(0) = -da + 0.5 * u;
  gradient.col(1) = -de - 0.5 * u;
  gradient.col(2) = da + 0.5 * u;
  gradient.col(3) = de - 0.5 * u;
}

}  // namespace gproj
