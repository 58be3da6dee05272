#pragma once
// Curvature auxiliaries of a B-spline surface (003 §3.1); shared by the Weingarten families
// (isoline_alignment.h, geodesic_parallel_isolines.h, curvature_relations.h).
// Per sample point two auxiliary items hold twelve unknowns:
//   the forms item f (dimension 10): n (3), E, F, G, Δ, L, M, N   (indices kN..kNn below),
//   the curvature item c (dimension 2): K, H                       (kCurvatureK, kCurvatureH).
// Only the sample's own definition rows touch f, so the solver eliminates it by a Schur
// complement; c is shared with the neighbours' alignment and relation rows. They are
// defined by twelve rows (003 §3.1.2; s_u, s_v, s_uu, s_uv, s_vv are linear in the control
// points through fixed weights):
//   n − s_u × s_v = 0,  E − s_u·s_u = 0,  F − s_u·s_v = 0,  G − s_v·s_v = 0,
//   Δ − (E G − F²) = 0,
//   L √Δᵏ − s_uu·n = 0,  M √Δᵏ − s_uv·n = 0,  N √Δᵏ − s_vv·n = 0   (√Δᵏ frozen at x^k),
//   K Δ − (L N − M²) = 0,  2 H Δ − (L G − 2 M F + N E) = 0.

#include <Eigen/Core>
#include <array>
#include <cmath>
#include <string>
#include <vector>

#include "gproj/solver/constraint_family.h"

namespace gproj {

// The central-difference gradient (ψ_u, ψ_v) of 003 eq. 5 at an inner sample (a, b), from ψ at
// (a+1, b), (a−1, b), (a, b+1), (a, b−1) and the factors cu = 1 / (u_{a+1} − u_{a−1}),
// cv = 1 / (v_{b+1} − v_{b−1}).
inline Eigen::Vector2d CentralGradient(double up, double um, double vp, double vm, double cu,
                                       double cv) {
  return Eigen::Vector2d(cu * (up - um), cv * (vp - vm));
}
// |∇φ| |∇ψ| of two such gradients: the size that H_u K_v − H_v K_u is measured against.
inline double GradientNormProduct(const Eigen::Vector2d& a, const Eigen::Vector2d& b) {
  return std::hypot(a.x(), a.y()) * std::hypot(b.x(), b.y());
}

// Offsets inside the forms item, and of K and H in the twelve values of one sample (the local
// layout of a CurvatureAuxiliaries element and of ExactAuxiliary: f, then c).
enum CurvatureAux {
  kN = 0,
  kE = 3,
  kF = 4,
  kG = 5,
  kDelta = 6,
  kL = 7,
  kM = 8,
  kNn = 9,
  kFormsDim = 10,
  kK = 10,
  kH = 11,
  kCurvatureAuxDim = 12
};
// Offsets inside the curvature item.
enum CurvatureValue { kCurvatureK = 0, kCurvatureH = 1, kCurvatureDim = 2 };
static_assert(kK == kFormsDim + kCurvatureK && kH == kFormsDim + kCurvatureH &&
                  kCurvatureAuxDim == kFormsDim + kCurvatureDim,
              "a sample's twelve values are its forms item followed by its curvature item");

// Derivative weights of one sample: s_d = Σ_j w[d][j] c_j for d = u, v, uu, uv, vv.
struct SampleStencil {
  std::vector<int> control;                    // control point indices (into the control block)
  std::array<std::vector<double>, 5> weights;  // per derivative, one weight per control point
};

class CurvatureAuxiliaries : public ConstraintFamily {
 public:
  explicit CurvatureAuxiliaries(double weight = 1.0, std::string name = "curvature definitions")
      : ConstraintFamily(std::move(name), 12, FamilyRole::kConstraint, weight) {}

  // `forms` and `curvature` the sample's two auxiliary items; `control_items` the items of
  // stencil.control. Local layout of the element: f (10) | c (2) | control points (3 each).
  // `row_scale` (12 values, optional) divides each row, e.g. by the row's natural magnitude at
  // the start so that every definition is weighed as a relative error.
  int AddSample(int forms, int curvature, const std::vector<int>& control_items,
                const SampleStencil& stencil, const std::array<double, 12>* row_scale = nullptr);
  // Natural magnitudes of the twelve rows for auxiliary values `a` and a curvature scale κ:
  // |n|, E + G (three rows), Δ, √Δ κ (E + G) (three rows), Δ κ², 2 Δ κ.
  static std::array<double, 12> RowMagnitudes(const Eigen::Matrix<double, 12, 1>& a,
                                              double curvature);

  void EvaluateElement(int e, const double* x, double* phi, double* jac) const override;
  bool RowTouches(int e, int row, int local) const override;
  void Update(const VariableLayout& layout, const Eigen::VectorXd& x) override;

  // The exact auxiliary values for the given derivatives (s_u, s_v, s_uu, s_uv, s_vv):
  // residuals vanish when √Δᵏ is the current √Δ.
  static Eigen::Matrix<double, 12, 1> ExactAuxiliary(const std::array<Eigen::Vector3d, 5>& d);

 private:
  std::vector<std::array<std::vector<double>, 5>> weights_;
  std::vector<double> sqrt_delta_;  // √Δᵏ per element
  std::vector<std::array<double, 12>> inverse_scale_;
};

// Reads component `offset` of item `item` at x (the families' Update steps read auxiliaries).
inline double AuxiliaryValue(const VariableLayout& layout, const Eigen::VectorXd& x, int item,
                             int offset) {
  return x[layout.ItemOffset(item) + offset];
}

}  // namespace gproj
