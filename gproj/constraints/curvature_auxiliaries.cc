#include "gproj/constraints/curvature_auxiliaries.h"

#include <Eigen/Geometry>
#include <algorithm>
#include <cmath>

namespace gproj {

namespace {

// Cross-product matrix: [a]× b = a × b.
Eigen::Matrix3d CrossMatrix(const Eigen::Vector3d& a) {
  Eigen::Matrix3d m;
  m << 0, -a.z(), a.y(), a.z(), 0, -a.x(), -a.y(), a.x(), 0;
  return m;
}

// Rows r of phi and of the row-major jac (dim columns) times scale[r]; rows of scale 1 are left.
void ScaleRows(const std::array<double, 12>& scale, int dim, double* phi, double* jac) {
  for (int r = 0; r < 12; ++r) {
    const double f = scale[r];
    if (f == 1.0) continue;
    phi[r] *= f;
    for (int l = 0; l < dim; ++l) jac[r * dim + l] *= f;
  }
}

}  // namespace

int CurvatureAuxiliaries::AddSample(int forms, int curvature, const std::vector<int>& control_items,
                                    const SampleStencil& stencil,
                                    const std::array<double, 12>* row_scale) {
  std::vector<int> items = {forms, curvature};
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
  ScaleRows(inverse_scale_[e], dim, phi, jac);
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
    const int forms = element_items(e)[0];
    const double e_ = AuxiliaryValue(layout, x, forms, kE),
                 f = AuxiliaryValue(layout, x, forms, kF), g = AuxiliaryValue(layout, x, forms, kG);
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

}  // namespace gproj
