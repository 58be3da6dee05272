#include "gproj/constraints/line_quad_planarity.h"

#include <algorithm>

namespace gproj {

int LineQuadPlanarity::AddQuad(int normal, const std::array<int, 4>& t,
                               const std::array<Eigen::Vector3d, 4>& o,
                               const std::array<Eigen::Vector3d, 4>& d) {
  origins_.push_back(o);
  directions_.push_back(d);
  return AddElement({normal, t[0], t[1], t[2], t[3]});
}

void LineQuadPlanarity::EvaluateElement(int e, const double* x, double* phi, double* jac) const {
  constexpr int kDim = 7;
  std::fill(jac, jac + 5 * kDim, 0.0);
  const Eigen::Map<const Eigen::Vector3d> n(x);
  const auto& o = origins_[e];
  const auto& d = directions_[e];
  for (int j = 0; j < 4; ++j) {
    const int k = (j + 1) % 4;
    const Eigen::Vector3d edge = o[k] + x[3 + k] * d[k] - o[j] - x[3 + j] * d[j];
    double* row = jac + j * kDim;
    phi[j] = n.dot(edge);
    for (int c = 0; c < 3; ++c) row[c] = edge[c];
    row[3 + j] = -n.dot(d[j]);
    row[3 + k] = n.dot(d[k]);
  }
  phi[4] = n.squaredNorm() - 1.0;
  for (int c = 0; c < 3; ++c) jac[4 * kDim + c] = 2.0 * n[c];
}

bool LineQuadPlanarity::RowTouches(int, int row, int local) const {
  if (local < 3) return true;
  if (row == 4) return false;
  const int vertex = local - 3;
  return vertex == row || vertex == (row + 1) % 4;
}

}  // namespace gproj
