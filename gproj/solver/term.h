#pragma once
// Terms: constraint families written once. A term is a residual function templated on the
// scalar type that computes an element's kRows residuals from the scalars of the items it
// touches (item k has kDims[k] scalars):
//
//   struct OnCircle {
//     template <typename T> void operator()(const T* p, T* r) const { r[0] = p[0]*p[0] + p[1]*p[1]
//     - 1.0; }
//   };
//   auto* circle = problem.AddTerm<1, 2>("on_circle", OnCircle{});   // 1 row, one item of 2
//   circle->Add({point_item});
//
// Derivatives come from forward-mode automatic differentiation (ceres::Jet, header-only); the
// structural sparsity of every row is derived by one evaluation per element with a
// dependency-tracking scalar (DependencyScalar), so no derivative code and no pattern code is
// written by hand. Per-element data (a target, a frozen coefficient) is a value of type Data
// stored next to the element and passed first to the residual function:
//   fn(const Data& d, const T* item0, ..., T* residuals).
// Coefficients frozen at x^k get an explicit update step (SetUpdate), run once per iteration.
// A term whose rows are polynomials of degree ≤ 2 (the form guided projection is built on) can
// say so with DeclareQuadratic(): its coefficients are then read off once per solve and the
// rows evaluated from them, as fast as a hand-written Jacobian (bench/term_benchmark.cc).
// Same-definition contract: guided projection and the Ceres cross-check both evaluate the term
// through EvaluateElement.

#include <ceres/jet.h>

#include <array>
#include <functional>
#include <stdexcept>
#include <string>
#include <type_traits>
#include <utility>
#include <vector>

#include "gproj/solver/constraint_family.h"
#include "gproj/solver/dependency_scalar.h"
#include "gproj/solver/quadratic_rows.h"

namespace gproj {

// Data of terms whose elements carry none.
struct NoData {};

// The integers [0, n), for adding elements over index ranges: term->AddElements(IndexRange(n), …).
class IndexRange {
 public:
  class Iterator {
   public:
    explicit Iterator(int i) : i_(i) {}
    int operator*() const { return i_; }
    Iterator& operator++() {
      ++i_;
      return *this;
    }
    bool operator!=(const Iterator& o) const { return i_ != o.i_; }

   private:
    int i_;
  };
  explicit IndexRange(int n) : n_(n) {}
  Iterator begin() const { return Iterator(0); }
  Iterator end() const { return Iterator(n_); }

 private:
  int n_;
};

namespace internal {
template <int>
using ConstDoublePtr = const double*;
}  // namespace internal

template <typename Data, typename Residual, int kRows, int... kDims>
class Term : public ConstraintFamily {
  static_assert(sizeof...(kDims) > 0, "a term touches at least one item");
  static_assert(kRows > 0, "a term has at least one row");

 public:
  static constexpr int kNumItems = sizeof...(kDims);
  static constexpr int kLocalDim = (kDims + ...);
  // Global item ids (VariableLayout::Item) of one element, in the residual function's order.
  using Items = std::array<int, kNumItems>;
  // update(data, item0 values, item1 values, …) at x^k.
  using UpdateFunction = std::function<void(Data&, internal::ConstDoublePtr<kDims>...)>;

  Term(std::string name, Residual residual, FamilyRole role = FamilyRole::kConstraint,
       double weight = 1.0)
      : ConstraintFamily(std::move(name), kRows, role, weight), residual_(std::move(residual)) {
    SetItemDims({kDims...});
  }

  // Appends one element; returns its index.
  int Add(const Items& items, Data data = Data()) {
    data_.push_back(std::move(data));
    return ConstraintFamily::AddElement(items.data(), kNumItems);
  }
  // Appends one element per entry of `range`; make(entry) returns the element's Items, or a
  // std::pair<Items, Data>.
  template <typename Range, typename Make>
  void AddElements(const Range& range, Make make) {
    for (const auto& entry : range) {
      auto made = make(entry);
      if constexpr (std::is_same_v<std::decay_t<decltype(made)>, Items>)
        Add(made);
      else
        Add(made.first, std::move(made.second));
    }
  }
  // Elements are added through Add / AddElements, which keep their data beside them.
  int AddElement(const std::vector<int>& items) = delete;

  // Element e's data; changing it through this reference takes effect at the next Prepare().
  Data& data(int e) {
    quadratic_rows_.Clear();
    return data_[e];
  }
  const Data& data(int e) const { return data_[e]; }

  // Sets the step that refreshes each element's frozen coefficients from x^k.
  void SetUpdate(UpdateFunction update) { update_ = std::move(update); }

  // Declares every row a polynomial of degree ≤ 2 in the element's scalars whose coefficients
  // depend on the element's data only. Prepare() then reads the coefficients off (one model for
  // a term without data, one per element otherwise) and throws std::logic_error, naming the
  // term and row, if a row is not such a polynomial. Terms with an update step keep the
  // automatic derivatives per evaluation.
  void DeclareQuadratic() { quadratic_ = true; }

  void Prepare() override {
    quadratic_rows_.Clear();
    if (!quadratic_ || update_) return;
    const int models = std::is_same_v<Data, NoData> ? 1 : num_elements();
    std::string why;
    for (int m = 0; m < models; ++m) {
      const Data& data = std::is_same_v<Data, NoData> ? DefaultData() : data_[m];
      auto evaluate = [&](const double* x, double* phi, double* jac) {
        EvaluateWithJets(data, x, phi, jac);
      };
      if (!quadratic_rows_.Append(evaluate, &why))
        throw std::logic_error("term '" + name() + "', element " + std::to_string(m) +
                               ", declared quadratic: " + why);
    }
  }

  // The residuals of element e at a local vector of any scalar type (double, Jet, …).
  template <typename T>
  void Residuals(int e, const T* x_local, T* residuals) const {
    Call(data_[e], x_local, residuals, std::make_index_sequence<kNumItems>());
  }

  void EvaluateElement(int e, const double* x, double* phi, double* jac) const override {
    const int models = quadratic_rows_.num_models();
    if (models > 0 && (models == 1 || models == num_elements()))
      quadratic_rows_.Evaluate(models == 1 ? 0 : e, x, phi, jac);
    else
      EvaluateWithJets(data_[e], x, phi, jac);
  }

  void RowPattern(int e, const double* x, int local_dim, bool* touches) const override {
    using Scalar = DependencyScalar<kLocalDim>;
    Scalar x_dep[kLocalDim];
    Scalar r_dep[kRows];
    for (int l = 0; l < kLocalDim; ++l) {
      x_dep[l].value = x[l];
      x_dep[l].inputs.set(l);
    }
    Residuals(e, x_dep, r_dep);
    for (int row = 0; row < kRows; ++row)
      for (int l = 0; l < kLocalDim; ++l) touches[row * local_dim + l] = r_dep[row].inputs.test(l);
  }
  bool RowTouches(int e, int row, int local) const override {
    bool touches[kRows * kLocalDim];
    double zeros[kLocalDim] = {};
    RowPattern(e, zeros, kLocalDim, touches);
    return touches[row * kLocalDim + local];
  }

  void Update(const VariableLayout& layout, const Eigen::VectorXd& x) override {
    if (!update_) return;
    for (int e = 0; e < num_elements(); ++e)
      CallUpdate(e, layout, x, std::make_index_sequence<kNumItems>());
  }

 private:
  static constexpr std::array<int, kNumItems> Offsets() {
    std::array<int, kNumItems> offsets{};
    constexpr int dims[] = {kDims...};
    for (int k = 1; k < kNumItems; ++k) offsets[k] = offsets[k - 1] + dims[k - 1];
    return offsets;
  }
  static constexpr std::array<int, kNumItems> kOffsets = Offsets();

  static const Data& DefaultData() {
    static const Data none{};
    return none;
  }

  // Values and row-major gradients by forward-mode automatic differentiation.
  void EvaluateWithJets(const Data& data, const double* x, double* phi, double* jac) const {
    using Jet = ceres::Jet<double, kLocalDim>;
    Jet x_jet[kLocalDim];
    Jet r_jet[kRows];
    for (int l = 0; l < kLocalDim; ++l) x_jet[l] = Jet(x[l], l);
    Call(data, x_jet, r_jet, std::make_index_sequence<kNumItems>());
    for (int row = 0; row < kRows; ++row) {
      phi[row] = r_jet[row].a;
      for (int l = 0; l < kLocalDim; ++l) jac[row * kLocalDim + l] = r_jet[row].v[l];
    }
  }

  template <typename T, size_t... I>
  void Call(const Data& data, const T* x, T* r, std::index_sequence<I...>) const {
    if constexpr (std::is_same_v<Data, NoData>)
      residual_((x + kOffsets[I])..., r);
    else
      residual_(data, (x + kOffsets[I])..., r);
  }
  template <size_t... I>
  void CallUpdate(int e, const VariableLayout& layout, const Eigen::VectorXd& x,
                  std::index_sequence<I...>) {
    const int* items = element_items(e);
    update_(data_[e], (x.data() + layout.ItemOffset(items[I]))...);
  }

  Residual residual_;
  std::vector<Data> data_;
  UpdateFunction update_;
  bool quadratic_ = false;
  QuadraticRowsTable quadratic_rows_{kRows, kLocalDim};
};

}  // namespace gproj
