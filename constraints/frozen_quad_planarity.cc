#include "constraints/frozen_quad_planarity.h"

#include <Eigen/Geometry>

namespace gproj {

void FrozenQuadPlanarity::Update(const VariableLayout& layout, const Eigen::VectorXd& x) {
  normals_.resize(num_elements());
  for (int e = 0; e < num_elements(); ++e) {
    const int* items = element_items(e);
    Eigen::Vector3d b[4];
    for (int j = 0; j < 4; ++j) b[j] = x.segment<3>(layout.ItemOffset(items[j]));
    const Eigen::Vector3d n = (b[2] - b[0]).cross(b[3] - b[1]);
    const double length = n.norm();
    normals_[e] = length > 0.0 ? Eigen::Vector3d(n / length) : Eigen::Vector3d::Zero();
  }
}

void FrozenQuadPlanarity::EvaluateElement(int e, const double* x, double* phi, double* jac) const {
  const Eigen::Vector3d& n = normals_[e];
  static constexpr double kSign[4] = {0.5, -0.5, 0.5, -0.5};
  phi[0] = 0.0;
  for (int j = 0; j < 4; ++j)
    for (int c = 0; c < 3; ++c) {
      phi[0] += kSign[j] * n[c] * x[3 * j + c];
      jac[3 * j + c] = kSign[j] * n[c];
    }
}

}  // namespace gproj
