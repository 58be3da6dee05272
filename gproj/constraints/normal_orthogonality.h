#pragma once
// Rows that tie an auxiliary normal to the edges it must be orthogonal to (004 §3.2, option
// (i); Deng et al. 2011):
//   EdgeNormalOrthogonality:  n · (b − a) = 0,  items {n, a, b}, one row per element
//   UnitNormal:               n · n − 1 = 0,    items {n},       one row per element
// Vertex-star planarity is one UnitNormal per inner vertex v plus one orthogonality row per
// edge (v, v_j) of its star.

#include "gproj/solver/constraint_family.h"

namespace gproj {

class EdgeNormalOrthogonality : public ConstraintFamily {
 public:
  explicit EdgeNormalOrthogonality(std::string name = "star_planarity", double weight = 1.0)
      : ConstraintFamily(std::move(name), 1, FamilyRole::kConstraint, weight) {}
  void EvaluateElement(int e, const double* x, double* phi, double* jac) const override;
};

class UnitNormal : public ConstraintFamily {
 public:
  explicit UnitNormal(std::string name = "unit_normal", double weight = 1.0)
      : ConstraintFamily(std::move(name), 1, FamilyRole::kConstraint, weight) {}
  void EvaluateElement(int e, const double* x, double* phi, double* jac) const override;
};

}  // namespace gproj
