#include "constraints/isoline_alignment.h"

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

}  // namespace gproj
