#pragma once
// Quad planarity by the diagonal-distance approximation of 004 §3.2, option (ii):
//   φ(b0, b1, b2, b3) = n · d,  n = b02 × b13 / ‖b02 × b13‖,  d = (b0 + b2 − b1 − b3) / 2,
// (F_quad = φ²). φ is not quadratic, so its exact gradient (normal included) is used: with
// frozen n the linearisation misses terms of the size of ‖d‖/‖b02‖, which is O(1) for the
// quads of a vertex star, and the iteration diverges.
// Items {b0, b1, b2, b3} (vertices, dimension 3); one row. A vertex star of valence n is made
// planar by n − 2 such quads, without auxiliary variables.

#include "gproj/solver/constraint_family.h"

namespace gproj {

class QuadDiagonalPlanarity : public ConstraintFamily {
 public:
  explicit QuadDiagonalPlanarity(std::string name = "star_planarity", double weight = 1.0)
      : ConstraintFamily(std::move(name), 1, FamilyRole::kConstraint, weight) {}
  void EvaluateElement(int e, const double* x, double* phi, double* jac) const override;
};

}  // namespace gproj
