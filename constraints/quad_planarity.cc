#include "constraints/quad_planarity.h"

#include <algorithm>

namespace gproj {

void QuadPlanarity::EvaluateElement(int, const double* x, double* phi, double* jac) const {
  constexpr int kDim = 15;
  std::fill(jac, jac + 5 * kDim, 0.0);
  const double* n = x;
  for (int j = 0; j < 4; ++j) {
    const double* a = x + 3 + 3 * j;
    const double* b = x + 3 + 3 * ((j + 1) % 4);
    double* row = jac + j * kDim;
    phi[j] = 0.0;
    for (int c = 0; c < 3; ++c) {
      phi[j] += n[c] * (b[c] - a[c]);
      row[c] = b[c] - a[c];
      row[3 + 3 * j + c] = -n[c];
      row[3 + 3 * ((j + 1) % 4) + c] = n[c];
    }
  }
  phi[4] = n[0] * n[0] + n[1] * n[1] + n[2] * n[2] - 1.0;
  for (int c = 0; c < 3; ++c) jac[4 * kDim + c] = 2.0 * n[c];
}

bool QuadPlanarity::RowTouches(int, int row, int local) const {
  if (local < 3) return true;
  if (row == 4) return false;
  const int vertex = (local - 3) / 3;
  return vertex == row || vertex == (row + 1) % 4;
}

Eigen::Vector3d QuadPlanarity::InitialNormal(const Eigen::Vector3d& v0, const Eigen::Vector3d& v1,
                                             const Eigen::Vector3d& v2, const Eigen::Vector3d& v3) {
  const Eigen::Vector3d n = (v2 - v0).cross(v3 - v1);
  const double length = n.norm();
  return length > 0.0 ? Eigen::Vector3d(n / length) : Eigen::Vector3d(0.0, 0.0, 1.0);
}

}  // namespace gproj
