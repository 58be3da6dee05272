#include "constraints/curvature_isolines.h"

#include <ceres/jet.h>

#include <Eigen/Dense>
#include <Eigen/Geometry>
#include <algorithm>
#include <cmath>
#include <limits>

namespace gproj {
namespace {

// Cross-product matrix: [a]× b = a × b.
Eigen::Matrix3d CrossMatrix(const Eigen::Vector3d& a) {
  Eigen::Matrix3d m;
  m << 0, -a.z(), a.y(), a.z(), 0, -a.x(), -a.y(), a.x(), 0;
  return m;
}

// Reads item `item`'s component `offset` at x.
double Value(const VariableLayout& layout, const Eigen::VectorXd& x, int item, int offset) {
  return x[layout.ItemOffset(item) + offset];
}

}  // namespace

// ---------------------------------------------------------------------------------------------
int CurvatureAuxiliaries::AddSample(int aux, const std::vector<int>& control_items,
                                    const SampleStencil& stencil,
                                    const std::array<double, 12>* row_scale) {
  std::vector<int> items = {aux};
  items.insert(items.end(), control_items.begin(), control_items.end());
  weights_.push_back(stencil.weights);
  std::array<double, 12> inverse;
  inverse.fill(1.0);
  if (row_scale)
    for (int r = 0; r < 12; ++r) inverse[r] = (*row_scale)[r] > 0.0 ? 1.0 / (*row_scale)[r] : 1.0;
  inverse_scale_.push_back(inverse);
  sqrt_delta_.push_back(1.0);
  return AddElement(items);
}

void CurvatureAuxiliaries::EvaluateElement(int e, const double* x, double* phi, double* jac) const {
  const auto& w = weights_[e];
  const int nc = static_cast<int>(w[0].size());
  const int dim = 12 + 3 * nc;
  std::fill(jac, jac + 12 * dim, 0.0);
  std::array<Eigen::Vector3d, 5> d;
  for (auto& v : d) v.setZero();
  for (int j = 0; j < nc; ++j) {
    const Eigen::Vector3d c(x[12 + 3 * j], x[13 + 3 * j], x[14 + 3 * j]);
    for (int k = 0; k < 5; ++k) d[k] += w[k][j] * c;
  }
  const Eigen::Vector3d &su = d[0], &sv = d[1], &suu = d[2], &suv = d[3], &svv = d[4];
  const Eigen::Vector3d n(x[kN], x[kN + 1], x[kN + 2]);
  const double E = x[kE], F = x[kF], G = x[kG], D = x[kDelta], L = x[kL], M = x[kM], N = x[kNn],
               K = x[kK], H = x[kH];
  const double sigma = sqrt_delta_[e];
  auto J = [&](int row, int local) -> double& { return jac[row * dim + local]; };
  auto control_block = [&](int row, int j, const Eigen::RowVector3d& g) {
    for (int c = 0; c < 3; ++c) J(row, 12 + 3 * j + c) = g[c];
  };
  // n − s_u × s_v.
  const Eigen::Vector3d cross = su.cross(sv);
  const Eigen::Matrix3d bx = CrossMatrix(sv), ax = CrossMatrix(su);
  for (int r = 0; r < 3; ++r) {
    phi[r] = n[r] - cross[r];
    J(r, kN + r) = 1.0;
  }
  for (int j = 0; j < nc; ++j) {
    const Eigen::Matrix3d g = w[0][j] * bx - w[1][j] * ax;
    for (int r = 0; r < 3; ++r) control_block(r, j, g.row(r));
  }
  // E, F, G.
  phi[3] = E - su.dot(su);
  phi[4] = F - su.dot(sv);
  phi[5] = G - sv.dot(sv);
  J(3, kE) = J(4, kF) = J(5, kG) = 1.0;
  for (int j = 0; j < nc; ++j) {
    control_block(3, j, -2.0 * w[0][j] * su.transpose());
    control_block(4, j, -(w[0][j] * sv + w[1][j] * su).transpose());
    control_block(5, j, -2.0 * w[1][j] * sv.transpose());
  }
  // Δ − (E G − F²).
  phi[6] = D - (E * G - F * F);
  J(6, kDelta) = 1.0;
  J(6, kE) = -G;
  J(6, kG) = -E;
  J(6, kF) = 2.0 * F;
  // L σ − s_uu·n, M σ − s_uv·n, N σ − s_vv·n.
  const Eigen::Vector3d* second[3] = {&suu, &suv, &svv};
  const int coefficient[3] = {kL, kM, kNn};
  for (int k = 0; k < 3; ++k) {
    const int row = 7 + k;
    phi[row] = sigma * x[coefficient[k]] - second[k]->dot(n);
    J(row, coefficient[k]) = sigma;
    for (int c = 0; c < 3; ++c) J(row, kN + c) = -(*second[k])[c];
    for (int j = 0; j < nc; ++j) control_block(row, j, -w[2 + k][j] * n.transpose());
  }
  // K Δ − (L N − M²).
  phi[10] = K * D - (L * N - M * M);
  J(10, kK) = D;
  J(10, kDelta) = K;
  J(10, kL) = -N;
  J(10, kNn) = -L;
  J(10, kM) = 2.0 * M;
  // 2 H Δ − (L G − 2 M F + N E).
  phi[11] = 2.0 * H * D - (L * G - 2.0 * M * F + N * E);
  J(11, kH) = 2.0 * D;
  J(11, kDelta) = 2.0 * H;
  J(11, kL) = -G;
  J(11, kG) = -L;
  J(11, kM) = 2.0 * F;
  J(11, kF) = 2.0 * M;
  J(11, kNn) = -E;
  J(11, kE) = -N;
  for (int r = 0; r < 12; ++r) {
    const double f = inverse_scale_[e][r];
    if (f == 1.0) continue;
    phi[r] *= f;
    for (int l = 0; l < dim; ++l) J(r, l) *= f;
  }
}

std::array<double, 12> CurvatureAuxiliaries::RowMagnitudes(const Eigen::Matrix<double, 12, 1>& a,
                                                           double curvature) {
  const double eg = std::abs(a[kE]) + std::abs(a[kG]), d = std::max(std::abs(a[kDelta]), 1e-300);
  const double n = std::sqrt(d);
  return {n,
          n,
          n,
          eg,
          eg,
          eg,
          d,
          n * curvature * eg,
          n * curvature * eg,
          n * curvature * eg,
          d * curvature * curvature,
          2.0 * d * curvature};
}

bool CurvatureAuxiliaries::RowTouches(int, int row, int local) const {
  const bool control = local >= 12;
  switch (row) {
    case 0:
    case 1:
    case 2:
      return control ? (local - 12) % 3 != row : local == kN + row;
    case 3:
      return control || local == kE;
    case 4:
      return control || local == kF;
    case 5:
      return control || local == kG;
    case 6:
      return local == kDelta || local == kE || local == kF || local == kG;
    case 7:
    case 8:
    case 9:
      return control || local < 3 || local == kL + (row - 7);
    case 10:
      return local == kK || local == kDelta || local == kL || local == kM || local == kNn;
    default:
      return !control && local >= kE && local != kK;
  }
}

void CurvatureAuxiliaries::Update(const VariableLayout& layout, const Eigen::VectorXd& x) {
  for (int e = 0; e < num_elements(); ++e) {
    const int aux = element_items(e)[0];
    const double e_ = Value(layout, x, aux, kE), f = Value(layout, x, aux, kF),
                 g = Value(layout, x, aux, kG);
    sqrt_delta_[e] = std::sqrt(std::max(e_ * g - f * f, 1e-300));
  }
}

Eigen::Matrix<double, 12, 1> CurvatureAuxiliaries::ExactAuxiliary(
    const std::array<Eigen::Vector3d, 5>& d) {
  const Eigen::Vector3d n = d[0].cross(d[1]);
  const double E = d[0].dot(d[0]), F = d[0].dot(d[1]), G = d[1].dot(d[1]);
  const double D = E * G - F * F, s = std::sqrt(std::max(D, 1e-300));
  const double L = d[2].dot(n) / s, M = d[3].dot(n) / s, N = d[4].dot(n) / s;
  Eigen::Matrix<double, 12, 1> a;
  a << n, E, F, G, D, L, M, N, (L * N - M * M) / D, (L * G - 2 * M * F + N * E) / (2 * D);
  return a;
}

// ---------------------------------------------------------------------------------------------
int IsolineAlignment::AddSample(int up, int um, int vp, int vm, double inv_du, double inv_dv) {
  inv_.push_back({inv_du, inv_dv});
  row_scale_.push_back(1.0);
  return AddElement({up, um, vp, vm});
}

void IsolineAlignment::Update(const VariableLayout& layout, const Eigen::VectorXd& x) {
  if (!normalized_) return;
  const int n = num_elements();
  std::vector<double> product(n);
  double sum = 0.0;
  for (int e = 0; e < n; ++e) {
    const int* it = element_items(e);
    auto gradient = [&](int off) {
      return CentralGradient(Value(layout, x, it[0], off), Value(layout, x, it[1], off),
                             Value(layout, x, it[2], off), Value(layout, x, it[3], off), inv_[e][0],
                             inv_[e][1]);
    };
    product[e] = GradientNormProduct(gradient(kH), gradient(kK));
    sum += product[e] * product[e];
  }
  const double delta = n > 0 ? 0.1 * std::sqrt(sum / n) : 0.0;
  for (int e = 0; e < n; ++e)
    row_scale_[e] = product[e] + delta > 0.0 ? 1.0 / (product[e] + delta) : 1.0;
}

void IsolineAlignment::EvaluateElement(int e, const double* x, double* phi, double* jac) const {
  constexpr int kDim = 48;
  std::fill(jac, jac + kDim, 0.0);
  double cu = inv_[e][0], cv = inv_[e][1];
  const double* up = x;
  const double* um = x + 12;
  const double* vp = x + 24;
  const double* vm = x + 36;
  const double hu = cu * (up[kH] - um[kH]), ku = cu * (up[kK] - um[kK]);
  const double hv = cv * (vp[kH] - vm[kH]), kv = cv * (vp[kK] - vm[kK]);
  const double f = row_scale_[e];
  phi[0] = f * (hu * kv - hv * ku);
  cu *= f;
  cv *= f;
  jac[kH] = cu * kv;
  jac[12 + kH] = -cu * kv;
  jac[kK] = -cu * hv;
  jac[12 + kK] = cu * hv;
  jac[24 + kH] = -cv * ku;
  jac[36 + kH] = cv * ku;
  jac[24 + kK] = cv * hu;
  jac[36 + kK] = -cv * hu;
}

bool IsolineAlignment::RowTouches(int, int, int local) const {
  return local % 12 == kH || local % 12 == kK;
}

// ---------------------------------------------------------------------------------------------
int GeodesicAuxiliaries::AddSample(int g, int a, int up, int um, int vp, int vm, double inv_du,
                                   double inv_dv) {
  inv_.push_back({inv_du, inv_dv});
  delta_.push_back(1.0);
  return AddElement({g, a, up, um, vp, vm});
}

// Local layout: g (8) | a own (12) | a(a+1,b) | a(a−1,b) | a(a,b+1) | a(a,b−1) (12 each).
void GeodesicAuxiliaries::EvaluateElement(int e, const double* x, double* phi, double* jac) const {
  constexpr int kDim = 8 + 5 * 12;
  std::fill(jac, jac + 8 * kDim, 0.0);
  const double cu = inv_[e][0], cv = inv_[e][1];
  const double* g = x;
  const double* own = x + 8;
  const int up = 20, um = 32, vp = 44, vm = 56;
  auto J = [&](int row, int local) -> double& { return jac[row * kDim + local]; };
  const double E = own[kE], F = own[kF], G = own[kG];
  for (int p = 0; p < 2; ++p) {  // p = 0: K, p = 1: H
    const int off = p == 0 ? kK : kH;
    const double su = cu * inverse_sqrt_scale_[p], sv = cv * inverse_sqrt_scale_[p];
    const double du = su * (x[up + off] - x[um + off]);
    const double dv = sv * (x[vp + off] - x[vm + off]);
    const int r0 = 3 * p;
    // ψ_u² , ψ_u ψ_v, ψ_v².
    phi[r0] = g[r0] - du * du;
    phi[r0 + 1] = g[r0 + 1] - du * dv;
    phi[r0 + 2] = g[r0 + 2] - dv * dv;
    for (int k = 0; k < 3; ++k) J(r0 + k, r0 + k) = 1.0;
    J(r0, up + off) = -2.0 * du * su;
    J(r0, um + off) = 2.0 * du * su;
    J(r0 + 1, up + off) = -dv * su;
    J(r0 + 1, um + off) = dv * su;
    J(r0 + 1, vp + off) = -du * sv;
    J(r0 + 1, vm + off) = du * sv;
    J(r0 + 2, vp + off) = -2.0 * dv * sv;
    J(r0 + 2, vm + off) = 2.0 * dv * sv;
    // ‖∇ψ‖² Δᵏ − (G ψ_u² − 2 F ψ_u ψ_v + E ψ_v²).
    const int row = 6 + p, grad = p == 0 ? kGradK : kGradH;
    phi[row] = g[grad] * delta_[e] - (G * g[r0] - 2.0 * F * g[r0 + 1] + E * g[r0 + 2]);
    J(row, grad) = delta_[e];
    J(row, r0) = -G;
    J(row, r0 + 1) = 2.0 * F;
    J(row, r0 + 2) = -E;
    J(row, 8 + kG) = -g[r0];
    J(row, 8 + kF) = 2.0 * g[r0 + 1];
    J(row, 8 + kE) = -g[r0 + 2];
  }
}

bool GeodesicAuxiliaries::RowTouches(int, int row, int local) const {
  if (row < 6) {
    if (local < 8) return local == row;
    if (local < 20) return false;
    return (local - 20) % 12 == (row < 3 ? kK : kH);
  }
  const int p = row - 6;
  if (local < 8)
    return local == (p == 0 ? kGradK : kGradH) || (local >= 3 * p && local < 3 * p + 3);
  if (local < 20) return local - 8 == kE || local - 8 == kF || local - 8 == kG;
  return false;
}

void GeodesicAuxiliaries::Update(const VariableLayout& layout, const Eigen::VectorXd& x) {
  for (int e = 0; e < num_elements(); ++e)
    delta_[e] = std::max(Value(layout, x, element_items(e)[1], kDelta), 1e-300);
}

// ---------------------------------------------------------------------------------------------
int GeodesicParallelIsolines::AddSample(const std::array<int, 4>& g, const std::array<int, 4>& a,
                                        double inv_du, double inv_dv) {
  inv_.push_back({inv_du, inv_dv});
  row_scale_.push_back({1.0, 1.0});
  return AddElement({g[0], g[1], g[2], g[3], a[0], a[1], a[2], a[3]});
}

void GeodesicParallelIsolines::Update(const VariableLayout& layout, const Eigen::VectorXd& x) {
  const int n = num_elements();
  for (int p = 0; p < 2; ++p) {
    const int grad = p == 0 ? kGradK : kGradH, off = p == 0 ? kK : kH;
    std::vector<double> product(n);
    double sum = 0.0;
    for (int e = 0; e < n; ++e) {
      const int* it = element_items(e);
      auto d = [&](int i, int j, int o, double c) {
        return c * (Value(layout, x, it[i], o) - Value(layout, x, it[j], o));
      };
      const double qu = d(0, 1, grad, inv_[e][0]), qv = d(2, 3, grad, inv_[e][1]);
      const double pu = d(4, 5, off, inv_[e][0]), pv = d(6, 7, off, inv_[e][1]);
      product[e] = std::hypot(qu, qv) * std::hypot(pu, pv);
      sum += product[e] * product[e];
    }
    const double delta = n > 0 ? 0.1 * std::sqrt(sum / n) : 0.0;
    for (int e = 0; e < n; ++e)
      row_scale_[e][p] = product[e] + delta > 0.0 ? 1.0 / (product[e] + delta) : 1.0;
  }
}

// Local layout: g(a+1,b) g(a−1,b) g(a,b+1) g(a,b−1) (8 each) | a(a+1,b) … (12 each).
void GeodesicParallelIsolines::EvaluateElement(int e, const double* x, double* phi,
                                               double* jac) const {
  constexpr int kDim = 4 * 8 + 4 * 12;
  std::fill(jac, jac + 2 * kDim, 0.0);
  for (int p = 0; p < 2; ++p) {
    const double cu = inv_[e][0] * row_scale_[e][p], cv = inv_[e][1] * row_scale_[e][p];
    const int grad = p == 0 ? kGradK : kGradH, off = p == 0 ? kK : kH;
    const int gi[4] = {grad, 8 + grad, 16 + grad, 24 + grad};
    const int ai[4] = {32 + off, 44 + off, 56 + off, 68 + off};
    // One factor of the row scale: q carries it, p uses the plain differences.
    const double qu = cu * (x[gi[0]] - x[gi[1]]), qv = cv * (x[gi[2]] - x[gi[3]]);
    const double pu = inv_[e][0] * (x[ai[0]] - x[ai[1]]), pv = inv_[e][1] * (x[ai[2]] - x[ai[3]]);
    phi[p] = qu * pv - qv * pu;
    double* row = jac + p * kDim;
    row[gi[0]] = cu * pv;
    row[gi[1]] = -cu * pv;
    row[gi[2]] = -cv * pu;
    row[gi[3]] = cv * pu;
    row[ai[0]] = -inv_[e][0] * qv;
    row[ai[1]] = inv_[e][0] * qv;
    row[ai[2]] = inv_[e][1] * qu;
    row[ai[3]] = -inv_[e][1] * qu;
  }
}

bool GeodesicParallelIsolines::RowTouches(int, int row, int local) const {
  if (local < 32) return local % 8 == (row == 0 ? kGradK : kGradH);
  return (local - 32) % 12 == (row == 0 ? kK : kH);
}

// ---------------------------------------------------------------------------------------------
LinearWeingarten::LinearWeingarten(double weight, bool fixed, const Eigen::Vector3d& coefficients,
                                   double curvature_scale, std::string name)
    : ConstraintFamily(std::move(name), 1, FamilyRole::kConstraint, weight),
      fixed_(fixed),
      abc_(coefficients),
      curvature_scale_(curvature_scale) {}

double LinearWeingarten::RowScale(const Eigen::Vector3d& abc, double curvature_scale) {
  const double k = curvature_scale;
  const double s = std::abs(abc[0]) * k + std::abs(abc[1]) * k * k;
  return s > 0.0 ? 1.0 / s : 1.0;
}

void LinearWeingarten::EvaluateElement(int, const double* x, double* phi, double* jac) const {
  std::fill(jac, jac + 12, 0.0);
  const double f = RowScale();
  phi[0] = f * (abc_[0] * x[kH] + abc_[1] * x[kK] + abc_[2]);
  jac[kH] = f * abc_[0];
  jac[kK] = f * abc_[1];
}

void LinearWeingarten::Update(const VariableLayout& layout, const Eigen::VectorXd& x) {
  if (fixed_ || num_elements() < 2) return;
  std::vector<double> h, k;
  for (int e = 0; e < num_elements(); ++e) {
    h.push_back(Value(layout, x, element_items(e)[0], kH));
    k.push_back(Value(layout, x, element_items(e)[0], kK));
  }
  abc_ = FitLine(h, k);
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

// ---------------------------------------------------------------------------------------------
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
  // Cox–de Boor with derivatives (degree ≤ 3).
  double left[4], right[4], ndu[4][4];
  ndu[0][0] = 1.0;
  for (int j = 1; j <= degree; ++j) {
    left[j] = t - knot(span + 1 - j);
    right[j] = knot(span + j) - t;
    double saved = 0.0;
    for (int r = 0; r < j; ++r) {
      ndu[j][r] = right[r + 1] + left[j - r];
      const double temp = ndu[r][j - 1] / ndu[j][r];
      ndu[r][j] = saved + right[r + 1] * temp;
      saved = left[j - r] * temp;
    }
    ndu[j][j] = saved;
  }
  for (int r = 0; r < 4; ++r) value[r] = derivative[r] = 0.0;
  for (int r = 0; r <= degree; ++r) value[r] = ndu[r][degree];
  if (degree >= 1)
    for (int r = 0; r <= degree; ++r) {
      double d = 0.0;
      if (r >= 1) d += ndu[r - 1][degree - 1] / ndu[degree][r - 1];
      if (r <= degree - 1) d -= ndu[r][degree - 1] / ndu[degree][r];
      derivative[r] = degree * d;
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
    : ConstraintFamily(std::move(name), 1, FamilyRole::kConstraint, weight),
      curve_control_points_(curve_control_points) {}

void CurvatureCurveRelation::EvaluateElement(int e, const double* x, double* phi,
                                             double* jac) const {
  std::fill(jac, jac + 12, 0.0);
  const Eigen::Vector2d& q = foot_[e];
  const Eigen::Vector2d& nrm = normal_[e];
  phi[0] = nrm[0] * (x[kH] - q[0]) + nrm[1] * (x[kK] - q[1]);
  jac[kH] = nrm[0];
  jac[kK] = nrm[1];
}

void CurvatureCurveRelation::Update(const VariableLayout& layout, const Eigen::VectorXd& x) {
  const int n = num_elements();
  std::vector<double> h(n), k(n);
  for (int e = 0; e < n; ++e) {
    h[e] = Value(layout, x, element_items(e)[0], kH);
    k[e] = Value(layout, x, element_items(e)[0], kK);
  }
  const Curve curve = FitCurve(h, k, curve_control_points_);
  foot_.resize(n);
  normal_.resize(n);
  for (int e = 0; e < n; ++e) {
    const double t = curve.ClosestParameter({h[e], k[e]});
    foot_[e] = curve.Point(t);
    Eigen::Vector2d tangent = curve.Tangent(t);
    if (!(tangent.norm() > 0.0)) tangent = Eigen::Vector2d(1.0, 0.0);
    normal_[e] = Eigen::Vector2d(-tangent.y(), tangent.x()).normalized();
  }
}

}  // namespace gproj
