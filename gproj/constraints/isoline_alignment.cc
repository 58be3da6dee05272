#include "gproj/constraints/isoline_alignment.h"

#include <cmath>
#include <utility>
#include <vector>

namespace gproj {

void IsolineAlignment::Update(const VariableLayout& layout, const Eigen::VectorXd& x) {
  if (!normalized_) return;
  const int n = num_elements();
  std::vector<double> product(n);
  double sum = 0.0;
  for (int e = 0; e < n; ++e) {
    const int* it = element_items(e);
    const IsolineSample& s = std::as_const(*this).data(e);
    auto gradient = [&](int off) {
      return CentralGradient(AuxiliaryValue(layout, x, it[0], off),
                             AuxiliaryValue(layout, x, it[1], off),
                             AuxiliaryValue(layout, x, it[2], off),
                             AuxiliaryValue(layout, x, it[3], off), s.inv_du, s.inv_dv);
    };
    product[e] = GradientNormProduct(gradient(kCurvatureH), gradient(kCurvatureK));
    sum += product[e] * product[e];
  }
  const double delta = n > 0 ? 0.1 * std::sqrt(sum / n) : 0.0;
  for (int e = 0; e < n; ++e)
    data(e).row_scale = product[e] + delta > 0.0 ? 1.0 / (product[e] + delta) : 1.0;
}

}  // namespace gproj
