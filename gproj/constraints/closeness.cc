#include "gproj/constraints/closeness.h"

#include <algorithm>

namespace gproj {

int Closeness::AddTarget(int item, const double* target) {
  targets_.insert(targets_.end(), target, target + dim_);
  return AddElement({item});
}

void Closeness::EvaluateElement(int e, const double* x, double* phi, double* jac) const {
  std::fill(jac, jac + dim_ * dim_, 0.0);
  for (int c = 0; c < dim_; ++c) {
    phi[c] = x[c] - targets_[static_cast<size_t>(e) * dim_ + c];
    jac[c * dim_ + c] = 1.0;
  }
}

}  // namespace gproj
