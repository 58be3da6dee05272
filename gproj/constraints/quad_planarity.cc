#include "gproj/constraints/quad_planarity.h"

namespace gproj {

Eigen::Vector3d QuadPlanarity::InitialNormal(const Eigen::Vector3d& v0, const Eigen::Vector3d& v1,
                                             const Eigen::Vector3d& v2, const Eigen::Vector3d& v3) {
  const Eigen::Vector3d n = (v2 - v0).cross(v3 - v1);
  const double length = n.norm();
  return length > 0.0 ? Eigen::Vector3d(n / length) : Eigen::Vector3d(0.0, 0.0, 1.0);
}

}  // namespace gproj
