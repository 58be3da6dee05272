#include "gproj/constraints/curvature_relations.h"

#include <ceres/jet.h>

#include <Eigen/Dense>
#include <algorithm>
#include <cmath>
#include <limits>

#include "gproj/geometry/surface/bspline_basis.h"

namespace gproj {

LinearWeingarten::LinearWeingarten(double weight, bool fixed, const Eigen::Vector3d& coefficients,
                                   double curvature_scale, std::string name)
    : Term(std::move(name), LinearWeingartenResidual{}, FamilyRole::kConstraint, weight),
      fixed_(fixed),
      abc_(coefficients),
      curvature_scale_(curvature_scale) {}

double LinearWeingarten::RowScale(const Eigen::Vector3d& abc, double curvature_scale) {
  const double k = curvature_scale;
  const double s = std::abs(abc[0]) * k + std::abs(abc[1]) * k * k;
  return s > 0.0 ? 1.0 / s : 1.0;
}

void LinearWeingarten::Update(const VariableLayout& layout, const Eigen::VectorXd& x) {
  if (fixed_ || num_elements() < 2) return;
  std::vector<double> h, k;
  for (int e = 0; e < num_elements(); ++e) {
    h.push_back(AuxiliaryValue(layout, x, element_items(e)[0], kCurvatureH));
    k.push_back(AuxiliaryValue(layout, x, element_items(e)[0], kCurvatureK));
  }
  abc_ = FitLine(h, k);
  const LinearRelation relation = Relation();
  for (int e = 0; e < num_elements(); ++e) data(e) = relation;
}

SurfaceLinearWeingarten::SurfaceLinearWeingarten(double weight, const Eigen::Vector3d& coefficients,
                                                 double curvature_scale, std::string name)
    : ConstraintFamily(std::move(name), 1, FamilyRole::kConstraint, weight),
      abc_(coefficients),
      row_scale_(LinearWeingarten::RowScale(coefficients, curvature_scale)) {}

int SurfaceLinearWeingarten::AddSample(const std::vector<int>& control_items,
                                       const SampleStencil& stencil) {
  weights_.push_back(stencil.weights);
  return AddElement(control_items);
}

void SurfaceLinearWeingarten::EvaluateElement(int e, const double* x, double* phi,
                                              double* jac) const {
  // The 15 derivative scalars (s_u, s_v, s_uu, s_uv, s_vv) as Jets seeded with the identity.
  using Jet = ceres::Jet<double, 15>;
  const auto& w = weights_[e];
  const int m = static_cast<int>(w[0].size());
  Eigen::Matrix<Jet, 3, 1> d[5];
  for (int k = 0; k < 5; ++k)
    for (int c = 0; c < 3; ++c) {
      double value = 0.0;
      for (int j = 0; j < m; ++j) value += w[k][j] * x[3 * j + c];
      d[k][c] = Jet(value, 3 * k + c);
    }
  const Eigen::Matrix<Jet, 3, 1> cross = d[0].cross(d[1]);
  const Jet E = d[0].dot(d[0]), F = d[0].dot(d[1]), G = d[1].dot(d[1]);
  const Jet delta = E * G - F * F, root = ceres::sqrt(delta);
  const Jet L = d[2].dot(cross) / root, M = d[3].dot(cross) / root, N = d[4].dot(cross) / root;
  const Jet K = (L * N - M * M) / delta;
  const Jet H = (L * G - 2.0 * M * F + N * E) / (2.0 * delta);
  const Jet r = (abc_[0] * H + abc_[1] * K + abc_[2]) * row_scale_;
  phi[0] = r.a;
  for (int j = 0; j < m; ++j)
    for (int c = 0; c < 3; ++c) {
      double g = 0.0;
      for (int k = 0; k < 5; ++k) g += r.v[3 * k + c] * w[k][j];
      jac[3 * j + c] = g;
    }
}

Eigen::Vector3d LinearWeingarten::FitLine(const std::vector<double>& h,
                                          const std::vector<double>& k) {
  const int n = static_cast<int>(h.size());
  Eigen::Vector2d mean = Eigen::Vector2d::Zero();
  for (int i = 0; i < n; ++i) mean += Eigen::Vector2d(h[i], k[i]) / n;
  Eigen::Matrix2d cov = Eigen::Matrix2d::Zero();
  for (int i = 0; i < n; ++i) {
    const Eigen::Vector2d d = Eigen::Vector2d(h[i], k[i]) - mean;
    cov += d * d.transpose();
  }
  const Eigen::SelfAdjointEigenSolver<Eigen::Matrix2d> eig(cov);
  const Eigen::Vector2d normal = eig.eigenvectors().col(0);  // smallest spread
  return {normal[0], normal[1], -normal.dot(mean)};
}

namespace {

// Uniform clamped cubic B-spline basis on [0, 1] with `count` control points: values and first
// derivatives of the (up to) four non-zero functions, first index returned in *first.
void CubicBasis(int count, double t, int* first, double value[4], double derivative[4]) {
  const int degree = std::min(3, count - 1);
  const int spans = count - degree;
  // Uniform clamped knots, computed in place (no allocation: called for every curve sample).
  auto knot = [&](int i) { return std::clamp(static_cast<double>(i - degree) / spans, 0.0, 1.0); };
  t = std::clamp(t, 0.0, 1.0);
  int span = std::min(degree + static_cast<int>(t * spans), count - 1);
  double scratch[BasisScratchSize(3)], ders[2 * 4];
  const int n = std::min(1, degree);
  BasisFunctionDerivatives(knot, degree, span, t, n, scratch, ders);
  for (int r = 0; r < 4; ++r) value[r] = derivative[r] = 0.0;
  for (int r = 0; r <= degree; ++r) {
    value[r] = ders[r];
    if (n == 1) derivative[r] = ders[(degree + 1) + r];
  }
  *first = span - degree;
}

}  // namespace

Eigen::Vector2d CurvatureCurveRelation::Curve::Point(double t) const {
  int first;
  double b[4], d[4];
  CubicBasis(static_cast<int>(control.size()), t, &first, b, d);
  Eigen::Vector2d p = Eigen::Vector2d::Zero();
  for (int r = 0; r < 4 && first + r < static_cast<int>(control.size()); ++r)
    p += b[r] * control[first + r];
  return p;
}

Eigen::Vector2d CurvatureCurveRelation::Curve::Tangent(double t) const {
  int first;
  double b[4], d[4];
  CubicBasis(static_cast<int>(control.size()), t, &first, b, d);
  Eigen::Vector2d p = Eigen::Vector2d::Zero();
  for (int r = 0; r < 4 && first + r < static_cast<int>(control.size()); ++r)
    p += d[r] * control[first + r];
  return p;
}

double CurvatureCurveRelation::Curve::ClosestParameter(const Eigen::Vector2d& p) const {
  double best_t = 0.0, best = std::numeric_limits<double>::infinity();
  constexpr int kSamples = 200;
  for (int i = 0; i <= kSamples; ++i) {
    const double t = static_cast<double>(i) / kSamples;
    const double d = (Point(t) - p).squaredNorm();
    if (d < best) best = d, best_t = t;
  }
  // A few Newton-like refinements on ½‖γ(t) − p‖² (tangent direction projection).
  for (int it = 0; it < 5; ++it) {
    const Eigen::Vector2d tangent = Tangent(best_t);
    const double tt = tangent.squaredNorm();
    if (!(tt > 0.0)) break;
    best_t = std::clamp(best_t - (Point(best_t) - p).dot(tangent) / tt, 0.0, 1.0);
  }
  return best_t;
}

CurvatureCurveRelation::Curve CurvatureCurveRelation::FitCurve(const std::vector<double>& h,
                                                               const std::vector<double>& k,
                                                               int control_points) {
  const int n = static_cast<int>(h.size());
  const Eigen::Vector3d line = LinearWeingarten::FitLine(h, k);
  const Eigen::Vector2d axis(-line[1], line[0]);  // along the principal direction
  std::vector<double> s(n);
  double lo = std::numeric_limits<double>::infinity(), hi = -lo;
  for (int i = 0; i < n; ++i) {
    s[i] = axis.dot(Eigen::Vector2d(h[i], k[i]));
    lo = std::min(lo, s[i]);
    hi = std::max(hi, s[i]);
  }
  const int m = std::max(2, control_points);
  Eigen::MatrixXd a = Eigen::MatrixXd::Zero(n, m);
  Eigen::MatrixXd rhs(n, 2);
  for (int i = 0; i < n; ++i) {
    const double t = hi > lo ? (s[i] - lo) / (hi - lo) : 0.5;
    int first;
    double b[4], d[4];
    CubicBasis(m, t, &first, b, d);
    for (int r = 0; r < 4 && first + r < m; ++r) a(i, first + r) = b[r];
    rhs.row(i) << h[i], k[i];
  }
  // A little second-difference smoothing keeps empty spans well posed.
  Eigen::MatrixXd normal = a.transpose() * a;
  for (int j = 1; j + 1 < m; ++j) {
    Eigen::VectorXd d = Eigen::VectorXd::Zero(m);
    d[j - 1] = 1, d[j] = -2, d[j + 1] = 1;
    normal += 1e-6 * n * d * d.transpose();
  }
  const Eigen::MatrixXd c = normal.ldlt().solve(a.transpose() * rhs);
  Curve curve;
  for (int j = 0; j < m; ++j) curve.control.emplace_back(c(j, 0), c(j, 1));
  return curve;
}

CurvatureCurveRelation::CurvatureCurveRelation(double weight, int curve_control_points,
                                               std::string name)
    : Term(std::move(name), CurvatureCurveResidual{}, FamilyRole::kConstraint, weight),
      curve_control_points_(curve_control_points) {}

void CurvatureCurveRelation::Update(const VariableLayout& layout, const Eigen::VectorXd& x) {
  const int n = num_elements();
  std::vector<double> h(n), k(n);
  for (int e = 0; e < n; ++e) {
    h[e] = AuxiliaryValue(layout, x, element_items(e)[0], kCurvatureH);
    k[e] = AuxiliaryValue(layout, x, element_items(e)[0], kCurvatureK);
  }
  const Curve curve = FitCurve(h, k, curve_control_points_);
  for (int e = 0; e < n; ++e) {
    const double t = curve.ClosestParameter({h[e], k[e]});
    CurveTangentLine& line = data(e);
    line.foot = curve.Point(t);
    Eigen::Vector2d tangent = curve.Tangent(t);
    if (!(tangent.norm() > 0.0)) tangent = Eigen::Vector2d(1.0, 0.0);
    line.normal = Eigen::Vector2d(-tangent.y(), tangent.x()).normalized();
  }
}

}  // namespace gproj
