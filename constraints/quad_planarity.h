#pragma once
// Quad planarity with an auxiliary unit normal per face (004 §3.2; Tang et al. 2014):
//   n_f · (v_{j+1} − v_j) = 0  (j = 0..3, indices mod 4),   n_f · n_f − 1 = 0.
// Element items: {n_f, v0, v1, v2, v3}, each of dimension 3. Five rows per element.

#include <Eigen/Geometry>

#include "solver/constraint_family.h"

namespace gproj {

class QuadPlanarity : public ConstraintFamily {
 public:
  explicit QuadPlanarity(double weight = 1.0, std::string name = "planarity")
      : ConstraintFamily(std::move(name), 5, FamilyRole::kConstraint, weight) {}

  // Adds one face: its normal item and its four vertex items in cyclic order.
  int AddQuad(int normal, int v0, int v1, int v2, int v3) {
    return AddElement({normal, v0, v1, v2, v3});
  }

  void EvaluateElement(int e, const double* x, double* phi, double* jac) const override;
  bool RowTouches(int e, int row, int local) const override;

  // The unit normal of a quad from its diagonals: (v2 − v0) × (v3 − v1), normalised.
  static Eigen::Vector3d InitialNormal(const Eigen::Vector3d& v0, const Eigen::Vector3d& v1,
                                       const Eigen::Vector3d& v2, const Eigen::Vector3d& v3);
};

}  // namespace gproj
