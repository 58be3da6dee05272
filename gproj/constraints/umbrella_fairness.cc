#include "gproj/constraints/umbrella_fairness.h"

#include <algorithm>

namespace gproj {

UmbrellaFairness::UmbrellaFairness(int dim, double weight, std::string name)
    : ConstraintFamily(std::move(name), dim, FamilyRole::kFairness, weight), dim_(dim) {}

void UmbrellaFairness::EvaluateElement(int e, const double* x, double* phi, double* jac) const {
  const int points = element_num_items(e);
  const int neighbours = points - 1;
  const int local_dim = points * dim_;
  std::fill(jac, jac + dim_ * local_dim, 0.0);
  const double share = 2.0 / neighbours;
  for (int c = 0; c < dim_; ++c) {
    phi[c] = -2.0 * x[c];
    jac[c * local_dim + c] = -2.0;
    for (int p = 1; p < points; ++p) {
      phi[c] += share * x[p * dim_ + c];
      jac[c * local_dim + p * dim_ + c] = share;
    }
  }
}

}  // namespace gproj
