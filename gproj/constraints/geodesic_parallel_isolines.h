#pragma once
// Geodesic parallel isolines (003 §3.2.1, eq. 8): a second auxiliary item g (dimension 8)
//   K_u², K_u K_v, K_v², H_u², H_u H_v, H_v², ‖∇K‖², ‖∇H‖²
// with rows  K_u² − (K_u)² = 0, …  and  ‖∇ψ‖² Δᵏ − (G ψ_u² − 2 F ψ_u ψ_v + E ψ_v²) = 0
// (003 eq. 7; §3.2.1 prints E and G swapped and √Δᵏ, which is not eq. 7), then
//   (‖∇ψ‖²)_u ψ_v − (‖∇ψ‖²)_v ψ_u = 0 for ψ = H and K.

#include <array>
#include <cmath>
#include <string>
#include <vector>

#include "gproj/constraints/curvature_auxiliaries.h"

namespace gproj {

// Offsets inside the geodesic-parallel auxiliary item.
enum GeodesicAux {
  kKuu = 0,
  kKuv = 1,
  kKvv = 2,
  kHuu = 3,
  kHuv = 4,
  kHvv = 5,
  kGradK = 6,
  kGradH = 7,
  kGeodesicAuxDim = 8
};

// Definitions of the geodesic-parallel auxiliaries at an inner sample; items
// {g (own), f (own forms), c(a+1,b), c(a−1,b), c(a,b+1), c(a,b−1)} (c: curvature items). Eight
// rows.
class GeodesicAuxiliaries : public ConstraintFamily {
 public:
  explicit GeodesicAuxiliaries(double weight = 1.0, std::string name = "gradient definitions")
      : ConstraintFamily(std::move(name), 8, FamilyRole::kConstraint, weight) {}
  int AddSample(int g, int forms, int up, int um, int vp, int vm, double inv_du, double inv_dv);
  // Typical |∇K|² and |∇H|² (default 1). The auxiliaries are stored in these units
  // (K_u² / scale, …, ‖∇K‖² / scale), so they are O(1) like the other unknowns and the
  // proximal term ε² treats them alike.
  void SetGradientScales(double k_scale, double h_scale) {
    inverse_sqrt_scale_ = {1.0 / std::sqrt(k_scale), 1.0 / std::sqrt(h_scale)};
  }
  void EvaluateElement(int e, const double* x, double* phi, double* jac) const override;
  bool RowTouches(int e, int row, int local) const override;
  void Update(const VariableLayout& layout, const Eigen::VectorXd& x) override;

 private:
  std::vector<std::array<double, 2>> inv_;
  std::vector<double> delta_;  // Δᵏ per element
  std::array<double, 2> inverse_sqrt_scale_ = {1.0, 1.0};
};

// (‖∇ψ‖²)_u ψ_v − (‖∇ψ‖²)_v ψ_u = 0 for ψ = K (row 0) and H (row 1); items
// {g(a+1,b), g(a−1,b), g(a,b+1), g(a,b−1), c(a+1,b), c(a−1,b), c(a,b+1), c(a,b−1)}.
// Rows are divided by |∇‖∇ψ‖²| |∇ψ| at x^k (+ δ, as for IsolineAlignment).
class GeodesicParallelIsolines : public ConstraintFamily {
 public:
  explicit GeodesicParallelIsolines(double weight, std::string name = "geodesic parallel")
      : ConstraintFamily(std::move(name), 2, FamilyRole::kConstraint, weight) {}
  int AddSample(const std::array<int, 4>& g, const std::array<int, 4>& c, double inv_du,
                double inv_dv);
  void EvaluateElement(int e, const double* x, double* phi, double* jac) const override;
  bool RowTouches(int e, int row, int local) const override;
  void Update(const VariableLayout& layout, const Eigen::VectorXd& x) override;

 private:
  std::vector<std::array<double, 2>> inv_;
  std::vector<std::array<double, 2>> row_scale_;
};

}  // namespace gproj
