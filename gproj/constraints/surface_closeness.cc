#include "gproj/constraints/surface_closeness.h"

#include <algorithm>

namespace gproj {

void SurfaceTangentCloseness::Update(const VariableLayout& layout, const Eigen::VectorXd& x) {
  points_.resize(num_elements());
  normals_.resize(num_elements());
  for (int e = 0; e < num_elements(); ++e)
    projector_(x.segment<3>(layout.ItemOffset(element_items(e)[0])), &points_[e], &normals_[e]);
}

void SurfaceTangentCloseness::EvaluateElement(int e, const double* x, double* phi,
                                              double* jac) const {
  const Eigen::Vector3d& n = normals_[e];
  const Eigen::Vector3d& p = points_[e];
  phi[0] = n[0] * (x[0] - p[0]) + n[1] * (x[1] - p[1]) + n[2] * (x[2] - p[2]);
  for (int c = 0; c < 3; ++c) jac[c] = n[c];
}

void SurfacePointCloseness::Update(const VariableLayout& layout, const Eigen::VectorXd& x) {
  points_.resize(num_elements());
  Eigen::Vector3d unused;
  for (int e = 0; e < num_elements(); ++e)
    projector_(x.segment<3>(layout.ItemOffset(element_items(e)[0])), &points_[e], &unused);
}

void SurfacePointCloseness::EvaluateElement(int e, const double* x, double* phi,
                                            double* jac) const {
  std::fill(jac, jac + 9, 0.0);
  for (int c = 0; c < 3; ++c) {
    phi[c] = x[c] - points_[e][c];
    jac[4 * c] = 1.0;
  }
}

}  // namespace gproj
