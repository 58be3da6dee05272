#include "gproj/constraints/polyline_fairness.h"

#include <algorithm>
#include <cassert>

namespace gproj {
namespace {
constexpr double kSecond[] = {1.0, -2.0, 1.0};
constexpr double kThird[] = {1.0, -3.0, 3.0, -1.0};
}  // namespace

PolylineFairness::PolylineFairness(int order, int dim, double weight, std::string name)
    : ConstraintFamily(std::move(name), dim, FamilyRole::kFairness, weight),
      order_(order),
      dim_(dim) {
  assert(order == 2 || order == 3);
}

void PolylineFairness::EvaluateElement(int, const double* x, double* phi, double* jac) const {
  const double* coefficients = order_ == 2 ? kSecond : kThird;
  const int points = order_ + 1;
  const int local_dim = points * dim_;
  std::fill(jac, jac + dim_ * local_dim, 0.0);
  for (int c = 0; c < dim_; ++c) {
    phi[c] = 0.0;
    for (int p = 0; p < points; ++p) {
      phi[c] += coefficients[p] * x[p * dim_ + c];
      jac[c * local_dim + p * dim_ + c] = coefficients[p];
    }
  }
}

}  // namespace gproj
