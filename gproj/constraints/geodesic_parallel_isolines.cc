#include "gproj/constraints/geodesic_parallel_isolines.h"

#include <algorithm>
#include <cmath>
#include <utility>
#include <vector>

namespace gproj {

GeodesicAuxiliaries::GeodesicAuxiliaries(double weight, std::string name)
    : Term(std::move(name), GeodesicAuxiliariesResidual{}, FamilyRole::kConstraint, weight) {
  // Δᵏ from the sample's own forms item.
  SetUpdate([](GeodesicSample& s, const double*, const double* own, const double*, const double*,
               const double*, const double*) { s.delta = std::max(own[kDelta], 1e-300); });
}

int GeodesicAuxiliaries::AddSample(int g, int forms, int up, int um, int vp, int vm, double inv_du,
                                   double inv_dv) {
  return Add({g, forms, up, um, vp, vm}, GeodesicSample{inv_du, inv_dv, 1.0, inverse_sqrt_scale_});
}

void GeodesicAuxiliaries::SetGradientScales(double k_scale, double h_scale) {
  inverse_sqrt_scale_ = {1.0 / std::sqrt(k_scale), 1.0 / std::sqrt(h_scale)};
  for (int e = 0; e < num_elements(); ++e) data(e).inverse_sqrt_scale = inverse_sqrt_scale_;
}

void GeodesicParallelIsolines::Update(const VariableLayout& layout, const Eigen::VectorXd& x) {
  const int n = num_elements();
  for (int p = 0; p < 2; ++p) {
    const int grad = p == 0 ? kGradK : kGradH, off = p == 0 ? kCurvatureK : kCurvatureH;
    std::vector<double> product(n);
    double sum = 0.0;
    for (int e = 0; e < n; ++e) {
      const int* it = element_items(e);
      const ParallelSample& s = std::as_const(*this).data(e);
      auto d = [&](int i, int j, int o, double c) {
        return c * (AuxiliaryValue(layout, x, it[i], o) - AuxiliaryValue(layout, x, it[j], o));
      };
      const double qu = d(0, 1, grad, s.inv_du), qv = d(2, 3, grad, s.inv_dv);
      const double pu = d(4, 5, off, s.inv_du), pv = d(6, 7, off, s.inv_dv);
      product[e] = std::hypot(qu, qv) * std::hypot(pu, pv);
      sum += product[e] * product[e];
    }
    const double delta = n > 0 ? 0.1 * std::sqrt(sum / n) : 0.0;
    for (int e = 0; e < n; ++e)
      data(e).row_scale[p] = product[e] + delta > 0.0 ? 1.0 / (product[e] + delta) : 1.0;
  }
}

}  // namespace gproj
