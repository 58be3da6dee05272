#pragma once
// Fairness along polylines (004 §3.2, 003 §3.3): second differences
//   v_{i−1} − 2 v_i + v_{i+1}            (order 2, items {v_{i−1}, v_i, v_{i+1}})
// or third differences
//   v_{i−1} − 3 v_i + 3 v_{i+1} − v_{i+2} (order 3, items {v_{i−1}, …, v_{i+2}}),
// one row per coordinate. Linear rows: the family is the P of ‖P x‖² (role kFairness).

#include "gproj/solver/constraint_family.h"

namespace gproj {

class PolylineFairness : public ConstraintFamily {
 public:
  // `order` 2 or 3; `dim` the dimension of the items (3 for vertices).
  explicit PolylineFairness(int order = 2, int dim = 3, double weight = 1.0,
                            std::string name = "fairness");

  int order() const { return order_; }
  void EvaluateElement(int e, const double* x, double* phi, double* jac) const override;
  bool RowTouches(int e, int row, int local) const override { return local % dim_ == row; }

 private:
  int order_;
  int dim_;
};

}  // namespace gproj
