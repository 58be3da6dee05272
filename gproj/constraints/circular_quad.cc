#include "gproj/constraints/circular_quad.h"

#include <algorithm>

#include "gproj/constraints/quad_planarity.h"

namespace gproj {

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
