#pragma once
// Isoline alignment (003 eq. 5 with central differences, eq. 10) at an inner sample:
//   H_u K_v − H_v K_u = 0,  ψ_u = (ψ(a+1, b) − ψ(a−1, b)) / (u_{a+1} − u_{a−1}), likewise v.

#include <array>
#include <string>
#include <vector>

#include "gproj/constraints/curvature_auxiliaries.h"

namespace gproj {

// H_u K_v − H_v K_u = 0; items {c(a+1,b), c(a−1,b), c(a,b+1), c(a,b−1)} (curvature items:
// K, H).
// With `normalized`, each row is divided by (|∇H| |∇K| + δ) at x^k (frozen, refreshed by
// Update; δ = 0.1 × the RMS of |∇H| |∇K| over the samples), so it measures the sine of the angle
// between the gradients. The raw residual scales with the cube of the curvature, so without
// this the cheapest way to lower it is to flatten the surface.
class IsolineAlignment : public ConstraintFamily {
 public:
  explicit IsolineAlignment(double weight, bool normalized = true,
                            std::string name = "isoline alignment")
      : ConstraintFamily(std::move(name), 1, FamilyRole::kConstraint, weight),
        normalized_(normalized) {}
  // inv_du = 1 / (u_{a+1} − u_{a−1}), inv_dv likewise.
  int AddSample(int up, int um, int vp, int vm, double inv_du, double inv_dv);
  void EvaluateElement(int e, const double* x, double* phi, double* jac) const override;
  void Update(const VariableLayout& layout, const Eigen::VectorXd& x) override;

 private:
  bool normalized_;
  std::vector<std::array<double, 2>> inv_;
  std::vector<double> row_scale_;
};

}  // namespace gproj
