#pragma once
// Quad planarity through the diagonal-distance approximation of 004 §3.2, option (ii):
//   F_quad(b0, b1, b2, b3) = (n · d)²,  n = b02 × b13 / ‖b02 × b13‖,  d = (b0 + b2 − b1 − b3) / 2,
// with n frozen at x^k (refreshed by Update), so the row n·d is linear in the vertices.
// Items {b0, b1, b2, b3} (vertices, dimension 3); one row. Used for the n − 2 quads that make a
// vertex star planar without auxiliary variables.

#include <Eigen/Core>
#include <vector>

#include "solver/constraint_family.h"

namespace gproj {

class FrozenQuadPlanarity : public ConstraintFamily {
 public:
  explicit FrozenQuadPlanarity(std::string name = "star_planarity", double weight = 1.0)
      : ConstraintFamily(std::move(name), 1, FamilyRole::kConstraint, weight) {}

  void Update(const VariableLayout& layout, const Eigen::VectorXd& x) override;
  void EvaluateElement(int e, const double* x, double* phi, double* jac) const override;

 private:
  std::vector<Eigen::Vector3d> normals_;  // #elements, frozen at x^k
};

}  // namespace gproj
