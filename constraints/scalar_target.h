#pragma once
// A scalar item held at a value: x − h = 0 (prescribed heights or line parameters of 002 §2,
// target heights of the fit of 002 eq. 14). Element items: {x} of dimension 1; one row.
// The role decides whether the rows are constraints (guide curves) or soft (a target).

#include <vector>

#include "solver/constraint_family.h"

namespace gproj {

class ScalarTarget : public ConstraintFamily {
 public:
  ScalarTarget(std::string name, FamilyRole role, double weight = 1.0)
      : ConstraintFamily(std::move(name), 1, role, weight) {}

  int AddTarget(int item, double value) {
    values_.push_back(value);
    return AddElement({item});
  }

  void EvaluateElement(int e, const double* x, double* phi, double* jac) const override {
    phi[0] = x[0] - values_[e];
    jac[0] = 1.0;
  }

 private:
  std::vector<double> values_;
};

}  // namespace gproj
