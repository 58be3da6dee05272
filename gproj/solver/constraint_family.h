#pragma once
// A constraint family: many elements of the same kind (all faces, all inner vertices, ...),
// each touching a few items of x and owning `rows_per_element` rows
//   φ_r(x) = ½ xᵀA_r x + b_rᵀx + c_r = 0.
// A family only writes each row's value and gradient at x; guided projection and the Ceres
// adapter both consume this one definition. See examples/custom_constraint.cc.

#include <Eigen/Core>
#include <string>
#include <vector>

#include "gproj/solver/variable_layout.h"

namespace gproj {

enum class FamilyRole {
  kConstraint,  // must vanish; counts towards convergence
  kSoft,        // regulariser (closeness): weight fades with the soft-weight schedule
  kFairness,    // linear fairness rows P x; weight is ω_f² × weight(), fades like kSoft
};

// The weight of every row of a family with this role and own weight, given the fairness weight
// ω_f and the soft-weight factor of the iteration: kConstraint w, kSoft w·s, kFairness w·ω_f²·s.
// Guided projection and the Ceres cross-check both weigh rows by this rule.
double RowWeight(FamilyRole role, double weight, double fairness_weight, double soft_scale);

class ConstraintFamily {
 public:
  ConstraintFamily(std::string name, int rows_per_element,
                   FamilyRole role = FamilyRole::kConstraint, double weight = 1.0);
  virtual ~ConstraintFamily() = default;

  // Appends an element touching the given global item ids (VariableLayout::Item); returns its
  // index. The local vector of the element is the items' scalars concatenated in this order.
  // In a Problem (AddFamily binds its layout) an item that is not in the layout, or whose size
  // is not the one the family declared (SetItemDims), is refused: std::invalid_argument naming
  // the family, the element, the item and its block.
  int AddElement(const std::vector<int>& items);
  int AddElement(const int* items, int count);

  // The layout the family's items belong to (Problem::AddFamily sets it; null: unchecked).
  void BindLayout(const VariableLayout* layout) { layout_ = layout; }

  // Values and gradients of element e's rows at its local vector.
  // x_local: local_dim values; phi: rows_per_element(); jac: rows_per_element() × local_dim,
  // row-major.
  virtual void EvaluateElement(int e, const double* x_local, double* phi, double* jac) const = 0;

  // Whether row `row` of element e can depend on local scalar `local` (structural sparsity,
  // asked once when the solver builds its pattern). The default says every row uses every
  // scalar; override it to keep the factor sparse.
  virtual bool RowTouches(int e, int row, int local) const { return true; }

  // The structural sparsity of element e in one call: touches[row × local_dim + local] set to
  // whether the row can depend on the scalar. x_local is the element's local vector at the
  // start (for families whose pattern is derived by evaluating them). The default asks
  // RowTouches for every pair.
  virtual void RowPattern(int e, const double* x_local, int local_dim, bool* touches) const {
    for (int row = 0; row < rows_per_element_; ++row)
      for (int l = 0; l < local_dim; ++l) touches[row * local_dim + l] = RowTouches(e, row, l);
  }

  // Called once before a solve, after the last element was added (guided projection and the
  // Ceres adapter both call it); families that precompute per-element state do it here.
  virtual void Prepare() {}

  // Refreshes coefficients frozen at x^k (called once per iteration before evaluation).
  virtual void Update(const VariableLayout& layout, const Eigen::VectorXd& x) {}

  // Sets unknowns the family owns outright to their exact values at the others (an
  // inequality's slacks s = √max(g, 0)). Guided projection calls it on the start and on every
  // trial point, so such unknowns never lag behind the ones they are made from.
  virtual void Project(const VariableLayout& layout, Eigen::VectorXd* x) const {}

  // Whether shifted targets (SolverOptions::shifted_constraints) apply to the rows. Bounds
  // (inequalities with their slacks, φ = min(g, 0)) say no: a shifted target would keep
  // pushing a bound that is met.
  virtual bool ShiftsTargets() const { return true; }

  const std::string& name() const { return name_; }
  FamilyRole role() const { return role_; }
  double weight() const { return weight_; }
  void set_weight(double w) { weight_ = w; }
  int rows_per_element() const { return rows_per_element_; }
  int num_elements() const { return static_cast<int>(element_begin_.size()) - 1; }
  int num_rows() const { return num_elements() * rows_per_element_; }
  // Items of element e: element_items(e)[0 .. element_num_items(e)).
  const int* element_items(int e) const { return items_.data() + element_begin_[e]; }
  int element_num_items(int e) const { return element_begin_[e + 1] - element_begin_[e]; }

 protected:
  // The number of scalars of each item of an element, in order (a Term's kDims); empty: any.
  void SetItemDims(std::vector<int> dims) { item_dims_ = std::move(dims); }

 private:
  std::string name_;
  int rows_per_element_;
  FamilyRole role_;
  double weight_;
  std::vector<int> items_;
  std::vector<int> element_begin_ = {0};
  const VariableLayout* layout_ = nullptr;
  std::vector<int> item_dims_;
};

}  // namespace gproj
