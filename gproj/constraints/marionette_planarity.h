#pragma once
// Planarity of a quad over a fixed plan view, linear in the heights (002 eq. 2):
//   z_C − z_A − α (z_B − z_A) − β (z_D − z_A) = 0,  AC = α AB + β AD in the plan (x, y).
// Element items: {z_A, z_B, z_C, z_D}, each of dimension 1. One row per element.

#include <Eigen/Core>
#include <vector>

#include "gproj/solver/constraint_family.h"

namespace gproj {

class MarionettePlanarity : public ConstraintFamily {
 public:
  explicit MarionettePlanarity(double weight = 1.0, std::string name = "planarity")
      : ConstraintFamily(std::move(name), 1, FamilyRole::kConstraint, weight) {}

  // Adds one quad A, B, C, D (C opposite A) with its plan coefficients α, β.
  int AddQuad(int a, int b, int c, int d, double alpha, double beta);

  // α, β of a plan quad: AC = α AB + β AD. Returns false (α, β untouched) when A, B, D are
  // collinear within `tolerance` relative to |AB| |AD|.
  static bool PlanCoefficients(const Eigen::Vector2d& a, const Eigen::Vector2d& b,
                               const Eigen::Vector2d& c, const Eigen::Vector2d& d, double* alpha,
                               double* beta, double tolerance = 1e-12);

  void EvaluateElement(int e, const double* z, double* phi, double* jac) const override;

 private:
  std::vector<double> alpha_, beta_;
};

}  // namespace gproj
