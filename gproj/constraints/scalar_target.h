#pragma once
// A scalar item held at a value: x − h = 0 (prescribed heights or line parameters of 002 §2,
// target heights of the fit of 002 eq. 14). Element items: {x} of dimension 1; one row; the
// value h is the element's data. The role decides whether the rows are constraints (guide
// curves) or soft (a target).

#include <string>

#include "gproj/solver/term.h"

namespace gproj {

struct ScalarTargetResidual {
  template <typename T>
  void operator()(double value, const T* x, T* r) const {
    r[0] = x[0] - value;
  }
};

class ScalarTarget : public Term<double, ScalarTargetResidual, 1, 1> {
 public:
  ScalarTarget(std::string name, FamilyRole role, double weight = 1.0)
      : Term(std::move(name), ScalarTargetResidual{}, role, weight) {
    DeclareQuadratic();
  }

  int AddTarget(int item, double value) { return Add({item}, value); }
};

}  // namespace gproj
