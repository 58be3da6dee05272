#pragma once
// Curvature isolines of a B-spline surface (003 §3.1–3.2). Per sample point one auxiliary item
// a (dimension 12) holds
//   n (3), E, F, G, Δ, L, M, N, K, H          (indices kN..kH below)
// defined by twelve rows (003 §3.1.2; s_u, s_v, s_uu, s_uv, s_vv are linear in the control
// points through fixed weights):
//   n − s_u × s_v = 0,  E − s_u·s_u = 0,  F − s_u·s_v = 0,  G − s_v·s_v = 0,
//   Δ − (E G − F²) = 0,
//   L √Δᵏ − s_uu·n = 0,  M √Δᵏ − s_uv·n = 0,  N √Δᵏ − s_vv·n = 0   (√Δᵏ frozen at x^k),
//   K Δ − (L N − M²) = 0,  2 H Δ − (L G − 2 M F + N E) = 0.
// Isoline alignment (003 eq. 5 with central differences, eq. 10) at an inner sample:
//   H_u K_v − H_v K_u = 0,  ψ_u = (ψ(a+1, b) − ψ(a−1, b)) / (u_{a+1} − u_{a−1}), likewise v.
// Geodesic parallel isolines (003 §3.2.1, eq. 8): a second auxiliary item g (dimension 8)
//   K_u², K_u K_v, K_v², H_u², H_u H_v, H_v², ‖∇K‖², ‖∇H‖²
// with rows  K_u² − (K_u)² = 0, …  and  ‖∇ψ‖² Δᵏ − (G ψ_u² − 2 F ψ_u ψ_v + E ψ_v²) = 0
// (003 eq. 7; §3.2.1 prints E and G swapped and √Δᵏ, which is not eq. 7), then
//   (‖∇ψ‖²)_u ψ_v − (‖∇ψ‖²)_v ψ_u = 0 for ψ = H and K.
// Linear Weingarten relation (003 §3.2.2): a H + b K + c = 0 per sample, (a, b, c) given or
// fitted to the (H, K) points at x^k (orthogonal regression). B-spline curvature relation
// (003 §3.2.3): each (H, K) point held to the tangent line of a curve γ at its closest point,
// γ a cubic B-spline fitted to the points at x^k.

#include <Eigen/Core>
#include <array>
#include <cmath>
#include <vector>

#include "solver/constraint_family.h"

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

// Offsets inside the curvature auxiliary item.
enum CurvatureAux {
  kN = 0,
  kE = 3,
  kF = 4,
  kG = 5,
  kDelta = 6,
  kL = 7,
  kM = 8,
  kNn = 9,
  kK = 10,
  kH = 11,
  kCurvatureAuxDim = 12
};
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

// Derivative weights of one sample: s_d = Σ_j w[d][j] c_j for d = u, v, uu, uv, vv.
struct SampleStencil {
  std::vector<int> control;                    // control point indices (into the control block)
  std::array<std::vector<double>, 5> weights;  // per derivative, one weight per control point
};

class CurvatureAuxiliaries : public ConstraintFamily {
 public:
  explicit CurvatureAuxiliaries(double weight = 1.0, std::string name = "curvature definitions")
      : ConstraintFamily(std::move(name), 12, FamilyRole::kConstraint, weight) {}

  // `aux` the sample's auxiliary item; `control_items` the items of stencil.control.
  // `row_scale` (12 values, optional) divides each row, e.g. by the row's natural magnitude at
  // the start so that every definition is weighed as a relative error.
  int AddSample(int aux, const std::vector<int>& control_items, const SampleStencil& stencil,
                const std::array<double, 12>* row_scale = nullptr);
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

// H_u K_v − H_v K_u = 0; items {a(a+1,b), a(a−1,b), a(a,b+1), a(a,b−1)} (curvature items).
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
  bool RowTouches(int e, int row, int local) const override;
  void Update(const VariableLayout& layout, const Eigen::VectorXd& x) override;

 private:
  bool normalized_;
  std::vector<std::array<double, 2>> inv_;
  std::vector<double> row_scale_;
};

// Definitions of the geodesic-parallel auxiliaries at an inner sample; items
// {g (own), a (own), a(a+1,b), a(a−1,b), a(a,b+1), a(a,b−1)}. Eight rows.
class GeodesicAuxiliaries : public ConstraintFamily {
 public:
  explicit GeodesicAuxiliaries(double weight = 1.0, std::string name = "gradient definitions")
      : ConstraintFamily(std::move(name), 8, FamilyRole::kConstraint, weight) {}
  int AddSample(int g, int a, int up, int um, int vp, int vm, double inv_du, double inv_dv);
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
// {g(a+1,b), g(a−1,b), g(a,b+1), g(a,b−1), a(a+1,b), a(a−1,b), a(a,b+1), a(a,b−1)}.
// Rows are divided by |∇‖∇ψ‖²| |∇ψ| at x^k (+ δ, as for IsolineAlignment).
class GeodesicParallelIsolines : public ConstraintFamily {
 public:
  explicit GeodesicParallelIsolines(double weight, std::string name = "geodesic parallel")
      : ConstraintFamily(std::move(name), 2, FamilyRole::kConstraint, weight) {}
  int AddSample(const std::array<int, 4>& g, const std::array<int, 4>& a, double inv_du,
                double inv_dv);
  void EvaluateElement(int e, const double* x, double* phi, double* jac) const override;
  bool RowTouches(int e, int row, int local) const override;
  void Update(const VariableLayout& layout, const Eigen::VectorXd& x) override;

 private:
  std::vector<std::array<double, 2>> inv_;
  std::vector<std::array<double, 2>> row_scale_;
};

// a H + b K + c = 0 per sample; items {a (curvature item)}.
class LinearWeingarten : public ConstraintFamily {
 public:
  // fixed: use `coefficients` (a, b, c) throughout; otherwise fit them at every Update.
  // `curvature_scale` κ (typical |principal curvature|): rows are divided by |a| κ + |b| κ², so
  // they are relative errors like the auxiliary definitions.
  LinearWeingarten(double weight, bool fixed, const Eigen::Vector3d& coefficients,
                   double curvature_scale = 1.0, std::string name = "linear relation");
  int AddSample(int aux) { return AddElement({aux}); }
  void EvaluateElement(int e, const double* x, double* phi, double* jac) const override;
  bool RowTouches(int e, int row, int local) const override { return local == kH || local == kK; }
  void Update(const VariableLayout& layout, const Eigen::VectorXd& x) override;
  const Eigen::Vector3d& coefficients() const { return abc_; }
  // 1 / (|a| κ + |b| κ²), the factor that makes a row a relative error (1 if a = b = 0).
  static double RowScale(const Eigen::Vector3d& abc, double curvature_scale);
  // Orthogonal regression of the line a H + b K + c = 0 (a² + b² = 1) through the points.
  static Eigen::Vector3d FitLine(const std::vector<double>& h, const std::vector<double>& k);

 private:
  double RowScale() const { return RowScale(abc_, curvature_scale_); }
  bool fixed_;
  Eigen::Vector3d abc_;
  double curvature_scale_;
};

// a H + b K + c = 0 per sample, with H and K those of the surface itself: computed from the
// control points of the sample's stencil (s_u … s_vv) with their exact Jacobian (forward-mode
// automatic differentiation), not from the auxiliaries. Items: the stencil's control items.
// Rows are divided by |a| κ + |b| κ² like LinearWeingarten's. Newton-like on the relation: the
// definitions cannot absorb the residual, so a fixed relation is met on the surface.
class SurfaceLinearWeingarten : public ConstraintFamily {
 public:
  SurfaceLinearWeingarten(double weight, const Eigen::Vector3d& coefficients,
                          double curvature_scale = 1.0, std::string name = "linear relation");
  int AddSample(const std::vector<int>& control_items, const SampleStencil& stencil);
  void EvaluateElement(int e, const double* x, double* phi, double* jac) const override;
  const Eigen::Vector3d& coefficients() const { return abc_; }

 private:
  Eigen::Vector3d abc_;
  double row_scale_;
  std::vector<std::array<std::vector<double>, 5>> weights_;
};

// (H, K) held to the tangent line of a fitted curve γ at its closest point (frozen at x^k).
class CurvatureCurveRelation : public ConstraintFamily {
 public:
  explicit CurvatureCurveRelation(double weight, int curve_control_points = 6,
                                  std::string name = "B-spline relation");
  int AddSample(int aux) { return AddElement({aux}); }
  void EvaluateElement(int e, const double* x, double* phi, double* jac) const override;
  bool RowTouches(int e, int row, int local) const override { return local == kH || local == kK; }
  void Update(const VariableLayout& layout, const Eigen::VectorXd& x) override;

  // A uniform clamped cubic B-spline curve in the (H, K) plane fitted to the points by least
  // squares, parameters from the projection onto the points' principal axis.
  struct Curve {
    std::vector<Eigen::Vector2d> control;
    Eigen::Vector2d Point(double t) const;
    Eigen::Vector2d Tangent(double t) const;
    double ClosestParameter(const Eigen::Vector2d& p) const;
  };
  static Curve FitCurve(const std::vector<double>& h, const std::vector<double>& k,
                        int control_points);

 private:
  int curve_control_points_;
  std::vector<Eigen::Vector2d> foot_, normal_;  // per element
};

}  // namespace gproj
