#pragma once
// Geodesic parallel isolines (003 §3.2.1, eq. 8): a second auxiliary item g (dimension 8)
//   K_u², K_u K_v, K_v², H_u², H_u H_v, H_v², ‖∇K‖², ‖∇H‖²
// with rows  K_u² − (K_u)² = 0, …  and  ‖∇ψ‖² Δᵏ − (G ψ_u² − 2 F ψ_u ψ_v + E ψ_v²) = 0
// (003 eq. 7; §3.2.1 prints E and G swapped and √Δᵏ, which is not eq. 7), then
//   (‖∇ψ‖²)_u ψ_v − (‖∇ψ‖²)_v ψ_u = 0 for ψ = H and K.

#include <array>
#include <cmath>
#include <string>
#include <utility>

#include "gproj/constraints/curvature_auxiliaries.h"
#include "gproj/solver/term.h"

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

// Per-sample values of the gradient definitions: the central-difference factors, the frozen
// Δᵏ and the gradient units.
struct GeodesicSample {
  double inv_du = 0.0, inv_dv = 0.0;
  double delta = 1.0;                                     // Δᵏ, refreshed at x^k
  std::array<double, 2> inverse_sqrt_scale = {1.0, 1.0};  // K, H
};

struct GeodesicAuxiliariesResidual {
  template <typename T>
  void operator()(const GeodesicSample& s, const T* g, const T* own, const T* up, const T* um,
                  const T* vp, const T* vm, T* r) const {
    const T& E = own[kE];
    const T& F = own[kF];
    const T& G = own[kG];
    for (int p = 0; p < 2; ++p) {  // p = 0: K, p = 1: H
      const int off = p == 0 ? kCurvatureK : kCurvatureH;
      const double su = s.inv_du * s.inverse_sqrt_scale[p], sv = s.inv_dv * s.inverse_sqrt_scale[p];
      const T du = su * (up[off] - um[off]);
      const T dv = sv * (vp[off] - vm[off]);
      const int r0 = 3 * p;
      // ψ_u², ψ_u ψ_v, ψ_v².
      r[r0] = g[r0] - du * du;
      r[r0 + 1] = g[r0 + 1] - du * dv;
      r[r0 + 2] = g[r0 + 2] - dv * dv;
      // ‖∇ψ‖² Δᵏ − (G ψ_u² − 2 F ψ_u ψ_v + E ψ_v²).
      const int grad = p == 0 ? kGradK : kGradH;
      r[6 + p] = g[grad] * s.delta - (G * g[r0] - 2.0 * F * g[r0 + 1] + E * g[r0 + 2]);
    }
  }
};

// Definitions of the geodesic-parallel auxiliaries at an inner sample; items
// {g (own), f (own forms), c(a+1,b), c(a−1,b), c(a,b+1), c(a,b−1)} (c: curvature items). Eight
// rows.
class GeodesicAuxiliaries
    : public Term<GeodesicSample, GeodesicAuxiliariesResidual, 8, kGeodesicAuxDim, kFormsDim,
                  kCurvatureDim, kCurvatureDim, kCurvatureDim, kCurvatureDim> {
 public:
  explicit GeodesicAuxiliaries(double weight = 1.0, std::string name = "gradient definitions");
  int AddSample(int g, int forms, int up, int um, int vp, int vm, double inv_du, double inv_dv);
  // Typical |∇K|² and |∇H|² (default 1). The auxiliaries are stored in these units
  // (K_u² / scale, …, ‖∇K‖² / scale), so they are O(1) like the other unknowns and the
  // proximal term ε² treats them alike.
  void SetGradientScales(double k_scale, double h_scale);

 private:
  std::array<double, 2> inverse_sqrt_scale_ = {1.0, 1.0};
};

// The central-difference factors of one sample and its two row scales (K, H), frozen at x^k.
struct ParallelSample {
  double inv_du = 0.0, inv_dv = 0.0;
  std::array<double, 2> row_scale = {1.0, 1.0};
};

struct GeodesicParallelResidual {
  template <typename T>
  void operator()(const ParallelSample& s, const T* g0, const T* g1, const T* g2, const T* g3,
                  const T* c0, const T* c1, const T* c2, const T* c3, T* r) const {
    for (int p = 0; p < 2; ++p) {
      const double cu = s.inv_du * s.row_scale[p], cv = s.inv_dv * s.row_scale[p];
      const int grad = p == 0 ? kGradK : kGradH, off = p == 0 ? kCurvatureK : kCurvatureH;
      // One factor of the row scale: q carries it, p uses the plain differences.
      const T qu = cu * (g0[grad] - g1[grad]), qv = cv * (g2[grad] - g3[grad]);
      const T pu = s.inv_du * (c0[off] - c1[off]), pv = s.inv_dv * (c2[off] - c3[off]);
      r[p] = qu * pv - qv * pu;
    }
  }
};

// (‖∇ψ‖²)_u ψ_v − (‖∇ψ‖²)_v ψ_u = 0 for ψ = K (row 0) and H (row 1); items
// {g(a+1,b), g(a−1,b), g(a,b+1), g(a,b−1), c(a+1,b), c(a−1,b), c(a,b+1), c(a,b−1)}.
// Rows are divided by |∇‖∇ψ‖²| |∇ψ| at x^k (+ δ, as for IsolineAlignment).
class GeodesicParallelIsolines
    : public Term<ParallelSample, GeodesicParallelResidual, 2, kGeodesicAuxDim, kGeodesicAuxDim,
                  kGeodesicAuxDim, kGeodesicAuxDim, kCurvatureDim, kCurvatureDim, kCurvatureDim,
                  kCurvatureDim> {
 public:
  explicit GeodesicParallelIsolines(double weight, std::string name = "geodesic parallel")
      : Term(std::move(name), GeodesicParallelResidual{}, FamilyRole::kConstraint, weight) {}
  int AddSample(const std::array<int, 4>& g, const std::array<int, 4>& c, double inv_du,
                double inv_dv) {
    return Add({g[0], g[1], g[2], g[3], c[0], c[1], c[2], c[3]}, ParallelSample{inv_du, inv_dv});
  }
  // Refreshes the row scales (they depend on all samples through δ).
  void Update(const VariableLayout& layout, const Eigen::VectorXd& x) override;
};

}  // namespace gproj
