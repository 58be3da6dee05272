#pragma once
// Isoline alignment (003 eq. 5 with central differences, eq. 10) at an inner sample:
//   H_u K_v − H_v K_u = 0,  ψ_u = (ψ(a+1, b) − ψ(a−1, b)) / (u_{a+1} − u_{a−1}), likewise v.

#include <string>
#include <utility>

#include "gproj/constraints/curvature_auxiliaries.h"
#include "gproj/solver/term.h"

namespace gproj {

// The central-difference factors of one sample and the row's scale, frozen at x^k.
struct IsolineSample {
  double inv_du = 0.0, inv_dv = 0.0;
  double row_scale = 1.0;
};

struct IsolineAlignmentResidual {
  template <typename T>
  void operator()(const IsolineSample& s, const T* up, const T* um, const T* vp, const T* vm,
                  T* r) const {
    constexpr int h = kCurvatureH, k = kCurvatureK;
    const T hu = s.inv_du * (up[h] - um[h]), ku = s.inv_du * (up[k] - um[k]);
    const T hv = s.inv_dv * (vp[h] - vm[h]), kv = s.inv_dv * (vp[k] - vm[k]);
    r[0] = s.row_scale * (hu * kv - hv * ku);
  }
};

using IsolineAlignmentTerm = Term<IsolineSample, IsolineAlignmentResidual, 1, kCurvatureDim,
                                  kCurvatureDim, kCurvatureDim, kCurvatureDim>;

// H_u K_v − H_v K_u = 0; items {c(a+1,b), c(a−1,b), c(a,b+1), c(a,b−1)} (curvature items:
// K, H).
// With `normalized`, each row is divided by (|∇H| |∇K| + δ) at x^k (frozen, refreshed by
// Update; δ = 0.1 × the RMS of |∇H| |∇K| over the samples), so it measures the sine of the angle
// between the gradients. The raw residual scales with the cube of the curvature, so without
// this the cheapest way to lower it is to flatten the surface.
class IsolineAlignment : public IsolineAlignmentTerm {
 public:
  explicit IsolineAlignment(double weight, bool normalized = true,
                            std::string name = "isoline alignment")
      : IsolineAlignmentTerm(std::move(name), IsolineAlignmentResidual{}, FamilyRole::kConstraint,
                             weight),
        normalized_(normalized) {}
  // inv_du = 1 / (u_{a+1} − u_{a−1}), inv_dv likewise.
  int AddSample(int up, int um, int vp, int vm, double inv_du, double inv_dv) {
    return Add({up, um, vp, vm}, IsolineSample{inv_du, inv_dv, 1.0});
  }
  // Refreshes the row scales (the scale of every row depends on all samples through δ).
  void Update(const VariableLayout& layout, const Eigen::VectorXd& x) override;

 private:
  bool normalized_;
};

}  // namespace gproj
