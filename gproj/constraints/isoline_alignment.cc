#include "gproj/constraints/isoline_alignment.h"

#include <algorithm>
#include <cmath>

namespace gproj {

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
      return CentralGradient(AuxiliaryValue(layout, x, it[0], off),
                             AuxiliaryValue(layout, x, it[1], off),
                             AuxiliaryValue(layout, x, it[2], off),
                             AuxiliaryValue(layout, x, it[3], off), inv_[e][0], inv_[e][1]);
    };
    product[e] = GradientNormProduct(gradient(kCurvatureH), gradient(kCurvatureK));
    sum += product[e] * product[e];
  }
  const double delta = n > 0 ? 0.1 * std::sqrt(sum / n) : 0.0;
  for (int e = 0; e < n; ++e)
    row_scale_[e] = product[e] + delta > 0.0 ? 1.0 / (product[e] + delta) : 1.0;
}

void IsolineAlignment::EvaluateElement(int e, const double* x, double* phi, double* jac) const {
  constexpr int kDim = 4 * kCurvatureDim;
  std::fill(jac, jac + kDim, 0.0);
  double cu = inv_[e][0], cv = inv_[e][1];
  constexpr int up = 0, um = kCurvatureDim, vp = 2 * kCurvatureDim, vm = 3 * kCurvatureDim;
  constexpr int h = kCurvatureH, k = kCurvatureK;
  const double hu = cu * (x[up + h] - x[um + h]), ku = cu * (x[up + k] - x[um + k]);
  const double hv = cv * (x[vp + h] - x[vm + h]), kv = cv * (x[vp + k] - x[vm + k]);
  const double f = row_scale_[e];
  phi[0] = f * (hu * kv - hv * ku);
  cu *= f;
  cv *= f;
  jac[up + h] = cu * kv;
  jac[um + h] = -cu * kv;
  jac[up + k] = -cu * hv;
  jac[um + k] = cu * hv;
  jac[vp + h] = -cv * ku;
  jac[vm + h] = cv * ku;
  jac[vp + k] = cv * hu;
  jac[vm + k] = -cv * hu;
}

}  // namespace gproj
