#pragma once
// Inequalities g(x) ≥ 0 for any term (Tang et al. 2014; docs/method.md, "Inequalities"): each row
// becomes the equality
//   g(x) − s² = 0
// with one slack unknown s per row. Guided projection sets every slack to √max(g(x), 0) at the
// start and at each trial point (Project): the row's residual is then min(g, 0), it pulls only
// on a violated bound, and a slack that reached 0 cannot hold a satisfied bound at equality (the
// trap of free slacks, whose derivative 2s vanishes there). The slacks of an element form one
// item of an eliminable block ("<name>_slack"), so guided projection removes them with the
// other per-element auxiliaries before factorising; the Ceres cross-check sees the same rows
// with the slacks as free unknowns.
//
//   auto* bounds = AddInequalities<1, 2>(&problem, "above_line",
//       [](const auto* p, auto* r) { r[0] = p[0] - 1.0; },       // g(p) = p_x − 1 ≥ 0
//       IndexRange(n), [&](int i) { return std::array<int, 1>{layout.Item(points, i)}; });

#include <array>
#include <cmath>
#include <string>
#include <tuple>
#include <utility>
#include <vector>

#include "gproj/solver/problem.h"

namespace gproj {

// The residual g(…) − s², called as (data?, items…, slack, r): the last item is the slack.
template <typename Residual, int kRows>
struct SlackResidual {
  Residual g;

  template <typename... Args>
  void operator()(const Args&... args) const {
    constexpr size_t n = sizeof...(Args);
    const auto all = std::forward_as_tuple(args...);
    CallG(all, std::make_index_sequence<n - 2>());
    const auto& slack = std::get<n - 2>(all);
    const auto& r = std::get<n - 1>(all);
    for (int i = 0; i < kRows; ++i) r[i] -= slack[i] * slack[i];
  }

 private:
  template <typename Tuple, size_t... I>
  void CallG(const Tuple& all, std::index_sequence<I...>) const {
    g(std::get<I>(all)..., std::get<std::tuple_size_v<Tuple> - 1>(all));
  }
};

template <typename Data, typename Residual, int kRows, int... kDims>
class InequalityTerm : public Term<Data, SlackResidual<Residual, kRows>, kRows, kDims..., kRows> {
  using Base = Term<Data, SlackResidual<Residual, kRows>, kRows, kDims..., kRows>;

 public:
  using Base::Base;

  // Slack s = √max(g, 0) of every row, g evaluated at x with the slack set to 0.
  void Project(const VariableLayout& layout, Eigen::VectorXd* x) const override {
    constexpr int kLocalDim = (kDims + ...) + kRows;
    double x_local[kLocalDim], r[kRows];
    for (int e = 0; e < this->num_elements(); ++e) {
      const int* items = this->element_items(e);
      const int slack = items[sizeof...(kDims)];
      int l = 0;
      for (size_t k = 0; k <= sizeof...(kDims); ++k)
        for (int c = 0; c < layout.ItemDim(items[k]); ++c)
          x_local[l++] = items[k] == slack ? 0.0 : (*x)[layout.ItemOffset(items[k]) + c];
      this->Residuals(e, x_local, r);
      for (int i = 0; i < kRows; ++i)
        (*x)[layout.ItemOffset(slack) + i] =
            std::isfinite(r[i]) && r[i] > 0.0 ? std::sqrt(r[i]) : 0.0;
    }
  }

  bool ShiftsTargets() const override { return false; }
};

namespace internal {

// Adds the elements, their slack block and the slacks' start values.
template <typename Data, int kRows, int... kDims, typename Residual, typename Range, typename Make>
InequalityTerm<Data, Residual, kRows, kDims...>* AddInequalities(Problem* problem, std::string name,
                                                                 Residual g, const Range& range,
                                                                 Make make, double weight) {
  using Items = std::array<int, sizeof...(kDims)>;
  std::vector<std::pair<Items, Data>> elements;
  for (const auto& entry : range) {
    auto made = make(entry);
    if constexpr (std::is_same_v<std::decay_t<decltype(made)>, Items>)
      elements.emplace_back(made, Data());
    else
      elements.emplace_back(made.first, std::move(made.second));
  }
  VariableLayout& layout = problem->layout();
  const int slack_block = layout.AddBlock(name + "_slack", static_cast<int>(elements.size()), kRows,
                                          /*eliminable=*/true);
  problem->ResizeToLayout();
  auto* term = problem->AddFamily<InequalityTerm<Data, Residual, kRows, kDims...>>(
      std::move(name), SlackResidual<Residual, kRows>{std::move(g)}, FamilyRole::kConstraint,
      weight);
  for (size_t e = 0; e < elements.size(); ++e) {
    std::array<int, sizeof...(kDims) + 1> items;
    for (size_t k = 0; k < sizeof...(kDims); ++k) items[k] = elements[e].first[k];
    items.back() = layout.Item(slack_block, static_cast<int>(e));
    term->Add(items, std::move(elements[e].second));
  }
  term->Project(layout, &problem->x());
  return term;
}

}  // namespace internal

// Adds g(items) ≥ 0 for every entry of `range` (make(entry) gives the element's Items, or a
// std::pair<Items, Data>); problem->x() must hold the start. g is written like a term's
// residual: g(const T* item0, …, T* r), with Data first when given.
template <int kRows, int... kDims, typename Residual, typename Range, typename Make>
InequalityTerm<NoData, Residual, kRows, kDims...>* AddInequalities(Problem* problem,
                                                                   std::string name, Residual g,
                                                                   const Range& range, Make make,
                                                                   double weight = 1.0) {
  return internal::AddInequalities<NoData, kRows, kDims...>(problem, std::move(name), std::move(g),
                                                            range, make, weight);
}
template <typename Data, int kRows, int... kDims, typename Residual, typename Range, typename Make>
InequalityTerm<Data, Residual, kRows, kDims...>* AddInequalities(Problem* problem, std::string name,
                                                                 Residual g, const Range& range,
                                                                 Make make, double weight = 1.0) {
  return internal::AddInequalities<Data, kRows, kDims...>(problem, std::move(name), std::move(g),
                                                          range, make, weight);
}

}  // namespace gproj
