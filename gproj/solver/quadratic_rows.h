#pragma once
// Rows that are polynomials of degree ≤ 2 in an element's local scalars (the form of every
// guided-projection constraint, docs/method.md), stored by their coefficients
//   φ_r(x) = c_r + Σ_i b_i x_i + Σ_{i<j} h_ij x_i x_j + Σ_i ½ h_ii x_i²,
// so that evaluating a value and gradient costs about what a hand-written Jacobian does. The
// coefficients are read off a differentiable evaluation at 0 and at the unit vectors, and
// checked at a further point. A table holds many such models (one per element, or one shared
// by all elements of a term without per-element data).

#include <functional>
#include <string>
#include <vector>

namespace gproj {

class QuadraticRowsTable {
 public:
  // evaluate(x, phi, jac): values (rows) and row-major gradients (rows × dim) at x (dim).
  using Evaluator = std::function<void(const double* x, double* phi, double* jac)>;

  QuadraticRowsTable(int rows, int dim) : rows_(rows), dim_(dim) {}

  void Clear();
  // Appends the model of `evaluate`; false (and `why`, naming the row) when the rows are not
  // quadratic polynomials.
  bool Append(const Evaluator& evaluate, std::string* why);
  int num_models() const { return static_cast<int>(constants_.size()) / rows_; }

  // Values (rows) and row-major gradients (rows × dim) of model m at x.
  void Evaluate(int m, const double* x, double* phi, double* jac) const;

 private:
  struct Entry {
    int i, j;  // b_i (linear), h_ii (diagonal) or h_ij, i < j (mixed)
    double value;
  };
  int rows_, dim_;
  std::vector<double> constants_;  // models × rows
  // Per row the linear, then the diagonal, then the mixed entries: row k's are
  // entries_[row_begin_[3k] .. row_begin_[3k + 3]), kinds split at 3k + 1 and 3k + 2.
  std::vector<Entry> entries_;
  std::vector<int> row_begin_ = {0};  // 3 × models × rows + 1
};

}  // namespace gproj
