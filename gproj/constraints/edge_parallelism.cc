#include "gproj/constraints/edge_parallelism.h"

#include <Eigen/Geometry>
#include <algorithm>
#include <cassert>

namespace gproj {

int EdgeParallelism::AddEdge(int a, int b, const Eigen::Vector3d& direction) {
  assert(direction.norm() > 0.0);
  directions_.push_back(direction.normalized());
  return AddElement({a, b});
}

void EdgeParallelism::EvaluateElement(int e, const double* x, double* phi, double* jac) const {
  const Eigen::Vector3d& d = directions_[e];
  const Eigen::Vector3d edge(x[3] - x[0], x[4] - x[1], x[5] - x[2]);
  const Eigen::Vector3d r = d.cross(edge);
  // ∂(d × edge)/∂edge = [d]_×, the cross-product matrix of d.
  Eigen::Matrix3d cross;
  cross << 0, -d.z(), d.y(), d.z(), 0, -d.x(), -d.y(), d.x(), 0;
  for (int row = 0; row < 3; ++row) {
    phi[row] = r[row];
    for (int c = 0; c < 3; ++c) {
      jac[row * 6 + c] = -cross(row, c);
      jac[row * 6 + 3 + c] = cross(row, c);
    }
  }
}

int EdgeVector::AddEdge(int a, int b, const Eigen::Vector3d& vector) {
  vectors_.push_back(vector);
  return AddElement({a, b});
}

void EdgeVector::EvaluateElement(int e, const double* x, double* phi, double* jac) const {
  std::fill(jac, jac + 18, 0.0);
  for (int row = 0; row < 3; ++row) {
    phi[row] = x[3 + row] - x[row] - vectors_[e][row];
    jac[row * 6 + row] = -1.0;
    jac[row * 6 + 3 + row] = 1.0;
  }
}

}  // namespace gproj
