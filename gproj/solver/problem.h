#pragma once
// A gproj problem: the variable layout, the current iterate x and the constraint families.

#include <Eigen/Core>
#include <memory>
#include <stdexcept>
#include <string>
#include <utility>
#include <vector>

#include "gproj/solver/constraint_family.h"
#include "gproj/solver/term.h"
#include "gproj/solver/variable_layout.h"

namespace gproj {

class Problem {
 public:
  Problem() = default;
  // Moves keep the families bound to the moved layout.
  Problem(Problem&& other) noexcept { *this = std::move(other); }
  Problem& operator=(Problem&& other) noexcept {
    layout_ = std::move(other.layout_);
    x_ = std::move(other.x_);
    constant_ = std::move(other.constant_);
    families_ = std::move(other.families_);
    for (auto& family : families_) family->BindLayout(&layout_);
    return *this;
  }

  VariableLayout& layout() { return layout_; }
  const VariableLayout& layout() const { return layout_; }

  // Sizes x to the layout (new entries zero). Call after the last AddBlock.
  void ResizeToLayout() {
    x_.conservativeResizeLike(Eigen::VectorXd::Zero(layout_.num_variables()));
  }
  Eigen::VectorXd& x() { return x_; }
  const Eigen::VectorXd& x() const { return x_; }

  // Holds an item (e.g. a fixed vertex) at its value in x: no row gets a derivative for it,
  // guided projection's steps leave it untouched bit for bit and the Ceres cross-check makes its
  // parameter block constant. Items of eliminable blocks cannot be held.
  void SetConstant(int item, bool constant = true) {
    if (static_cast<int>(constant_.size()) <= item) constant_.resize(layout_.num_items(), false);
    constant_[item] = constant;
  }
  bool IsConstant(int item) const {
    return item < static_cast<int>(constant_.size()) && constant_[item];
  }
  // Whether any item is held.
  bool HasConstantItems() const {
    for (bool c : constant_)
      if (c) return true;
    return false;
  }

  // Takes ownership; returns a pointer for adding elements, whose items are checked against the
  // layout (ConstraintFamily::AddElement). Names are unique (they are report keys): a second
  // family of a name is refused with std::invalid_argument.
  template <typename Family, typename... Args>
  Family* AddFamily(Args&&... args) {
    auto family = std::make_unique<Family>(std::forward<Args>(args)...);
    if (FindFamily(family->name()) != nullptr)
      throw std::invalid_argument("a family named '" + family->name() +
                                  "' is in the problem already (names are unique)");
    family->BindLayout(&layout_);
    Family* raw = family.get();
    families_.push_back(std::move(family));
    return raw;
  }
  // Adds a term (gproj/solver/term.h): kRows residuals per element from items of kDims scalars,
  // computed by `residual` (templated on the scalar; derivatives and sparsity automatic).
  // Without Data: residual(const T* item0, …, T* r); with Data: residual(const Data&, …).
  template <int kRows, int... kDims, typename Residual>
  Term<NoData, Residual, kRows, kDims...>* AddTerm(std::string name, Residual residual,
                                                   FamilyRole role = FamilyRole::kConstraint,
                                                   double weight = 1.0) {
    return AddFamily<Term<NoData, Residual, kRows, kDims...>>(std::move(name), std::move(residual),
                                                              role, weight);
  }
  template <typename Data, int kRows, int... kDims, typename Residual>
  Term<Data, Residual, kRows, kDims...>* AddTerm(std::string name, Residual residual,
                                                 FamilyRole role = FamilyRole::kConstraint,
                                                 double weight = 1.0) {
    return AddFamily<Term<Data, Residual, kRows, kDims...>>(std::move(name), std::move(residual),
                                                            role, weight);
  }

  int num_families() const { return static_cast<int>(families_.size()); }
  ConstraintFamily& family(int i) { return *families_[i]; }
  const ConstraintFamily& family(int i) const { return *families_[i]; }
  // Family by name, or nullptr.
  ConstraintFamily* FindFamily(const std::string& name) {
    for (auto& f : families_)
      if (f->name() == name) return f.get();
    return nullptr;
  }

 private:
  VariableLayout layout_;
  Eigen::VectorXd x_;
  std::vector<bool> constant_;  // per item, sized lazily
  std::vector<std::unique_ptr<ConstraintFamily>> families_;
};

}  // namespace gproj
