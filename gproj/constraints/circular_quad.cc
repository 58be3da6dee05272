#include "gproj/constraints/circular_quad.h"

#include <algorithm>

#include "gproj/constraints/quad_planarity.h"

namespace gproj {

void CircularQuad::EvaluateElement(int, const double* x, double* phi, double* jac) const {
  constexpr int kDim = 7 + 12;
  std::fill(jac, jac + 10 * kDim, 0.0);
  const double* n = x;
  const double* m = x + 3;
  const double* v[4] = {x + 7, x + 10, x + 13, x + 16};
  for (int j = 0; j < 4; ++j) {
    const int k = (j + 1) % 4;
    double* row = jac + j * kDim;
    phi[j] = 0.0;
    for (int c = 0; c < 3; ++c) {
      phi[j] += n[c] * (v[k][c] - v[j][c]);
      row[c] = v[k][c] - v[j][c];
      row[7 + 3 * j + c] = -n[c];
      row[7 + 3 * k + c] = n[c];
    }
  }
  phi[4] = n[0] * n[0] + n[1] * n[1] + n[2] * n[2] - 1.0;
  for (int c = 0; c < 3; ++c) jac[4 * kDim + c] = 2.0 * n[c];
  for (int j = 0; j < 4; ++j) {
    double* row = jac + (5 + j) * kDim;
    phi[5 + j] = -x[6];
    row[6] = -1.0;
    for (int c = 0; c < 3; ++c) {
      const double d = v[j][c] - m[c];
      phi[5 + j] += d * d;
      row[3 + c] = -2.0 * d;
      row[7 + 3 * j + c] = 2.0 * d;
    }
  }
  double* row = jac + 9 * kDim;
  phi[9] = 0.0;
  for (int c = 0; c < 3; ++c) {
    phi[9] += n[c] * (m[c] - v[0][c]);
    row[c] = m[c] - v[0][c];
    row[3 + c] = n[c];
    row[7 + c] = -n[c];
  }
}

bool CircularQuad::RowTouches(int, int row, int local) const {
  const int vertex = local >= 7 ? (local - 7) / 3 : -1;
  if (row < 4) return local < 3 || vertex == row || vertex == (row + 1) % 4;
  if (row == 4) return local < 3;
  if (row < 9) return (local >= 3 && local < 7) || vertex == row - 5;
  return local < 6 || vertex == 0;
}

Eigen::Matrix<double, 7, 1> CircularQuad::InitialAuxiliary(
    const std::array<Eigen::Vector3d, 4>& quad) {
  const Eigen::Vector3d n = QuadPlanarity::InitialNormal(quad[0], quad[1], quad[2], quad[3]);
  // Centre: the circumcentre of v0 v1 v2; ρ: the mean squared distance of the four vertices.
  const Eigen::Vector3d& a = quad[0];
  const Eigen::Vector3d ab = quad[1] - a, ac = quad[2] - a;
  const Eigen::Vector3d normal = ab.cross(ac);
  const Eigen::Vector3d m =
      a + (ac.squaredNorm() * normal.cross(ab) + ab.squaredNorm() * ac.cross(normal)) /
              (2.0 * normal.squaredNorm());
  double rho = 0.0;
  for (const auto& v : quad) rho += (v - m).squaredNorm() / 4.0;
  Eigen::Matrix<double, 7, 1> c;
  c << n, m, rho;
  return c;
}

}  // namespace gproj
