#pragma once
// Planarity of a quad over a fixed plan view, linear in the heights (002 eq. 2):
//   z_C − z_A − α (z_B − z_A) − β (z_D − z_A) = 0,  AC = α AB + β AD in the plan (x, y).
// Element items: {z_A, z_B, z_C, z_D}, each of dimension 1. One row per element.

#include <Eigen/Core>
#include <string>

#include "gproj/solver/term.h"

namespace gproj {

// α, β of one quad.
struct PlanCoefficientsData {
  double alpha = 0.0, beta = 0.0;
};

struct MarionettePlanarityResidual {
  template <typename T>
  void operator()(const PlanCoefficientsData& c, const T* za, const T* zb, const T* zc, const T* zd,
                  T* r) const {
    r[0] = (-1.0 + c.alpha + c.beta) * za[0] - c.alpha * zb[0] + zc[0] - c.beta * zd[0];
  }
};
using MarionettePlanarityTerm =
    Term<PlanCoefficientsData, MarionettePlanarityResidual, 1, 1, 1, 1, 1>;

// The term, declared quadratic (its row is linear).
class MarionettePlanarity : public MarionettePlanarityTerm {
 public:
  explicit MarionettePlanarity(double weight = 1.0, std::string name = "planarity")
      : MarionettePlanarityTerm(std::move(name), MarionettePlanarityResidual{},
                                FamilyRole::kConstraint, weight) {
    DeclareQuadratic();
  }

  // Adds one quad A, B, C, D (C opposite A) with its plan coefficients α, β.
  int AddQuad(int a, int b, int c, int d, double alpha, double beta) {
    return Add({a, b, c, d}, {alpha, beta});
  }

  // α, β of a plan quad: AC = α AB + β AD. Returns false (α, β untouched) when A, B, D are
  // collinear within `tolerance` relative to |AB| |AD|.
  static bool PlanCoefficients(const Eigen::Vector2d& a, const Eigen::Vector2d& b,
                               const Eigen::Vector2d& c, const Eigen::Vector2d& d, double* alpha,
                               double* beta, double tolerance = 1e-12);
};

}  // namespace gproj
