#pragma once
// Closeness to fixed positions (004 §3.2, 003 §3.1.4): v − v⁰ = 0, one row per coordinate.
// Role kSoft by default: a regulariser whose weight may fade with the solver's soft schedule;
// kConstraint for positions that must hold throughout (e.g. held boundary corners).

#include <vector>

#include "gproj/solver/constraint_family.h"

namespace gproj {

class Closeness : public ConstraintFamily {
 public:
  explicit Closeness(int dim = 3, double weight = 1.0, std::string name = "closeness",
                     FamilyRole role = FamilyRole::kSoft)
      : ConstraintFamily(std::move(name), dim, role, weight), dim_(dim) {}

  // Holds `item` at `target` (dim values).
  int AddTarget(int item, const double* target);

  void EvaluateElement(int e, const double* x, double* phi, double* jac) const override;
  bool RowTouches(int e, int row, int local) const override { return local == row; }

 private:
  int dim_;
  std::vector<double> targets_;  // #elements × dim
};

}  // namespace gproj
