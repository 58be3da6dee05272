#include "gproj/constraints/geodesic_parallel_isolines.h"

#include <algorithm>
#include <cmath>

namespace gproj {

int GeodesicAuxiliaries::AddSample(int g, int forms, int up, int um, int vp, int vm, double inv_du,
                                   double inv_dv) {
  inv_.push_back({inv_du, inv_dv});
  delta_.push_back(1.0);
  return AddElement({g, forms, up, um, vp, vm});
}

// Local layout: g (8) | f own (10) | c(a+1,b) | c(a−1,b) | c(a,b+1) | c(a,b−1) (2 each).
void GeodesicAuxiliaries::EvaluateElement(int e, const double* x, double* phi, double* jac) const {
  constexpr int kOwn = kGeodesicAuxDim, kNeighbours = kOwn + kFormsDim;
  constexpr int kDim = kNeighbours + 4 * kCurvatureDim;
  std::fill(jac, jac + 8 * kDim, 0.0);
  const double cu = inv_[e][0], cv = inv_[e][1];
  const double* g = x;
  const double* own = x + kOwn;
  constexpr int up = kNeighbours, um = up + kCurvatureDim, vp = um + kCurvatureDim,
                vm = vp + kCurvatureDim;
  auto J = [&](int row, int local) -> double& { return jac[row * kDim + local]; };
  const double E = own[kE], F = own[kF], G = own[kG];
  for (int p = 0; p < 2; ++p) {  // p = 0: K, p = 1: H
    const int off = p == 0 ? kCurvatureK : kCurvatureH;
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
    J(row, kOwn + kG) = -g[r0];
    J(row, kOwn + kF) = 2.0 * g[r0 + 1];
    J(row, kOwn + kE) = -g[r0 + 2];
  }
}

bool GeodesicAuxiliaries::RowTouches(int, int row, int local) const {
  constexpr int kOwn = kGeodesicAuxDim, kNeighbours = kOwn + kFormsDim;
  if (row < 6) {
    if (local < kOwn) return local == row;
    if (local < kNeighbours) return false;
    return (local - kNeighbours) % kCurvatureDim == (row < 3 ? kCurvatureK : kCurvatureH);
  }
  const int p = row - 6;
  if (local < kOwn)
    return local == (p == 0 ? kGradK : kGradH) || (local >= 3 * p && local < 3 * p + 3);
  if (local < kNeighbours) return local - kOwn == kE || local - kOwn == kF || local - kOwn == kG;
  return false;
}

void GeodesicAuxiliaries::Update(const VariableLayout& layout, const Eigen::VectorXd& x) {
  for (int e = 0; e < num_elements(); ++e)
    delta_[e] = std::max(AuxiliaryValue(layout, x, element_items(e)[1], kDelta), 1e-300);
}

int GeodesicParallelIsolines::AddSample(const std::array<int, 4>& g, const std::array<int, 4>& c,
                                        double inv_du, double inv_dv) {
  inv_.push_back({inv_du, inv_dv});
  row_scale_.push_back({1.0, 1.0});
  return AddElement({g[0], g[1], g[2], g[3], c[0], c[1], c[2], c[3]});
}

void GeodesicParallelIsolines::Update(const VariableLayout& layout, const Eigen::VectorXd& x) {
  const int n = num_elements();
  for (int p = 0; p < 2; ++p) {
    const int grad = p == 0 ? kGradK : kGradH, off = p == 0 ? kCurvatureK : kCurvatureH;
    std::vector<double> product(n);
    double sum = 0.0;
    for (int e = 0; e < n; ++e) {
      const int* it = element_items(e);
      auto d = [&](int i, int j, int o, double c) {
        return c * (AuxiliaryValue(layout, x, it[i], o) - AuxiliaryValue(layout, x, it[j], o));
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

// Local layout: g(a+1,b) g(a−1,b) g(a,b+1) g(a,b−1) (8 each) | c(a+1,b) … (2 each).
void GeodesicParallelIsolines::EvaluateElement(int e, const double* x, double* phi,
                                               double* jac) const {
  constexpr int kCurvatures = 4 * kGeodesicAuxDim, kDim = kCurvatures + 4 * kCurvatureDim;
  std::fill(jac, jac + 2 * kDim, 0.0);
  for (int p = 0; p < 2; ++p) {
    const double cu = inv_[e][0] * row_scale_[e][p], cv = inv_[e][1] * row_scale_[e][p];
    const int grad = p == 0 ? kGradK : kGradH, off = p == 0 ? kCurvatureK : kCurvatureH;
    int gi[4], ai[4];
    for (int j = 0; j < 4; ++j) {
      gi[j] = j * kGeodesicAuxDim + grad;
      ai[j] = kCurvatures + j * kCurvatureDim + off;
    }
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
  constexpr int kCurvatures = 4 * kGeodesicAuxDim;
  if (local < kCurvatures) return local % kGeodesicAuxDim == (row == 0 ? kGradK : kGradH);
  return (local - kCurvatures) % kCurvatureDim == (row == 0 ? kCurvatureK : kCurvatureH);
}

}  // namespace gproj
