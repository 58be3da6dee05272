#pragma once
// Linear Weingarten relation (003 §3.2.2): a H + b K + c = 0 per sample, (a, b, c) given or
// fitted to the (H, K) points at x^k (orthogonal regression). B-spline curvature relation
// (003 §3.2.3): each (H, K) point held to the tangent line of a curve γ at its closest point,
// γ a cubic B-spline fitted to the points at x^k.

#include <Eigen/Core>
#include <string>
#include <vector>

#include "gproj/constraints/curvature_auxiliaries.h"
#include "gproj/solver/term.h"

namespace gproj {

// The relation of one sample, frozen at x^k: (a, b, c) and the row's factor f.
struct LinearRelation {
  Eigen::Vector3d abc = Eigen::Vector3d::Zero();
  double scale = 1.0;
};

struct LinearWeingartenResidual {
  template <typename T>
  void operator()(const LinearRelation& l, const T* c, T* r) const {
    r[0] = l.scale * (l.abc[0] * c[kCurvatureH] + l.abc[1] * c[kCurvatureK] + l.abc[2]);
  }
};

// a H + b K + c = 0 per sample; items {c (the sample's curvature item: K, H)}.
class LinearWeingarten : public Term<LinearRelation, LinearWeingartenResidual, 1, kCurvatureDim> {
 public:
  // fixed: use `coefficients` (a, b, c) throughout; otherwise fit them at every Update.
  // `curvature_scale` κ (typical |principal curvature|): rows are divided by |a| κ + |b| κ², so
  // they are relative errors like the auxiliary definitions.
  LinearWeingarten(double weight, bool fixed, const Eigen::Vector3d& coefficients,
                   double curvature_scale = 1.0, std::string name = "linear relation");
  int AddSample(int curvature) { return Add({curvature}, Relation()); }
  void Update(const VariableLayout& layout, const Eigen::VectorXd& x) override;
  const Eigen::Vector3d& coefficients() const { return abc_; }
  // 1 / (|a| κ + |b| κ²), the factor that makes a row a relative error (1 if a = b = 0).
  static double RowScale(const Eigen::Vector3d& abc, double curvature_scale);
  // Orthogonal regression of the line a H + b K + c = 0 (a² + b² = 1) through the points.
  static Eigen::Vector3d FitLine(const std::vector<double>& h, const std::vector<double>& k);

 private:
  LinearRelation Relation() const { return {abc_, RowScale(abc_, curvature_scale_)}; }
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

// The tangent line of the fitted curve at a sample's closest point, frozen at x^k.
struct CurveTangentLine {
  Eigen::Vector2d foot = Eigen::Vector2d::Zero();
  Eigen::Vector2d normal = Eigen::Vector2d::Zero();
};

struct CurvatureCurveResidual {
  template <typename T>
  void operator()(const CurveTangentLine& l, const T* c, T* r) const {
    r[0] = l.normal[0] * (c[kCurvatureH] - l.foot[0]) + l.normal[1] * (c[kCurvatureK] - l.foot[1]);
  }
};

// (H, K) held to the tangent line of a fitted curve γ at its closest point (frozen at x^k);
// items {c (the sample's curvature item)}.
class CurvatureCurveRelation
    : public Term<CurveTangentLine, CurvatureCurveResidual, 1, kCurvatureDim> {
 public:
  explicit CurvatureCurveRelation(double weight, int curve_control_points = 6,
                                  std::string name = "B-spline relation");
  int AddSample(int curvature) { return Add({curvature}); }
  // Fits the curve to every sample's (H, K) and refreshes each sample's tangent line.
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
};

}  // namespace gproj
