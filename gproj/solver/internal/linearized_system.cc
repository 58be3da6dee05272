#include "gproj/solver/internal/linearized_system.h"

#include <algorithm>
#include <cmath>
#include <memory>
#include <utility>
#include <vector>

namespace gproj {

namespace {

// Scratch of the pattern pass, reused across elements.
struct PatternScratch {
  std::vector<std::pair<int, int>> used;  // (global index, local index)
  std::vector<double> x_local;
  std::unique_ptr<bool[]> touches;
  size_t touches_capacity = 0;
};

// Per scalar: whether it belongs to a held item. Scalars of held items get no derivative: their
// rows of A stay empty, so the step leaves them.
std::vector<bool> HeldScalars(const Problem& problem) {
  const VariableLayout& layout = problem.layout();
  std::vector<bool> held(layout.num_variables(), false);
  for (int item = 0; item < layout.num_items(); ++item)
    if (problem.IsConstant(item))
      for (int c = 0; c < layout.ItemDim(item); ++c) held[layout.ItemOffset(item) + c] = true;
  return held;
}

// Element e of `fam`: its scalars' global indices appended to *index (and its end to *begin),
// and one column of A per row of the element, with the sorted, unique row indices it touches;
// *scatter gets, for every (row, local scalar), the position in A's values (or −1).
void AddElementColumns(const ConstraintFamily& fam, int e, const VariableLayout& layout,
                       const Eigen::VectorXd& x, const std::vector<bool>& held,
                       std::vector<int>* begin, std::vector<int>* index, std::vector<int>* scatter,
                       CscMatrix* a, PatternScratch* scratch) {
  const int* items = fam.element_items(e);
  for (int k = 0; k < fam.element_num_items(e); ++k)
    for (int c = 0; c < layout.ItemDim(items[k]); ++c)
      index->push_back(layout.ItemOffset(items[k]) + c);
  begin->push_back(static_cast<int>(index->size()));
  const int first = (*begin)[e];
  const int local_dim = (*begin)[e + 1] - first;
  scratch->x_local.resize(local_dim);
  for (int l = 0; l < local_dim; ++l)
    scratch->x_local[l] = x.size() == layout.num_variables() ? x[(*index)[first + l]] : 0.0;
  const size_t pattern_size = static_cast<size_t>(fam.rows_per_element()) * local_dim;
  if (pattern_size > scratch->touches_capacity) {
    scratch->touches_capacity = pattern_size;
    scratch->touches = std::make_unique<bool[]>(pattern_size);
  }
  fam.RowPattern(e, scratch->x_local.data(), local_dim, scratch->touches.get());
  auto& used = scratch->used;
  for (int row = 0; row < fam.rows_per_element(); ++row) {
    used.clear();
    for (int l = 0; l < local_dim; ++l)
      if (scratch->touches[row * local_dim + l] && !held[(*index)[first + l]])
        used.emplace_back((*index)[first + l], l);
    std::sort(used.begin(), used.end());
    const size_t row_scatter = scatter->size();
    scatter->resize(row_scatter + local_dim, -1);
    int last = -1;
    for (const auto& [global, l] : used) {
      if (global != last) {
        a->row_index.push_back(global);
        last = global;
      }
      (*scatter)[row_scatter + l] = static_cast<int>(a->row_index.size()) - 1;
    }
    a->col_begin.push_back(static_cast<int>(a->row_index.size()));
  }
}

}  // namespace

LinearizedSystem::LinearizedSystem(Problem* problem) : problem_(problem) {
  const VariableLayout& layout = problem->layout();
  const int num_families = problem->num_families();
  a_.num_rows = layout.num_variables();
  family_row_begin_.assign(num_families + 1, 0);
  local_begin_.resize(num_families);
  local_index_.resize(num_families);
  scatter_.resize(num_families);
  int max_local = 0, max_rows = 0;

  // Pass 1: local indices and the column pattern (sorted, unique row indices per column).
  a_.col_begin.assign(1, 0);
  PatternScratch scratch;
  const std::vector<bool> held = HeldScalars(*problem);
  const Eigen::VectorXd& x = problem->x();
  for (int f = 0; f < num_families; ++f) {
    problem->family(f).Prepare();
    const ConstraintFamily& fam = problem->family(f);
    family_row_begin_[f + 1] = family_row_begin_[f] + fam.num_rows();
    auto& begin = local_begin_[f];
    begin.assign(1, 0);
    for (int e = 0; e < fam.num_elements(); ++e) {
      AddElementColumns(fam, e, layout, x, held, &begin, &local_index_[f], &scatter_[f], &a_,
                        &scratch);
      max_local = std::max(max_local, begin[e + 1] - begin[e]);
      max_rows = std::max(max_rows, fam.rows_per_element());
    }
  }
  // The arrays grew by appending: give back their slack (a third of their size on average).
  a_.row_index.shrink_to_fit();
  a_.col_begin.shrink_to_fit();
  for (int f = 0; f < num_families; ++f) {
    local_begin_[f].shrink_to_fit();
    local_index_[f].shrink_to_fit();
    scatter_[f].shrink_to_fit();
  }
  a_.num_cols = family_row_begin_.back();
  a_.values.assign(a_.row_index.size(), 0.0);
  r_.setZero(a_.num_cols);
  at_d_.setZero(a_.num_cols);
  phi_.setZero(a_.num_cols);
  row_scale_.assign(num_families, 0.0);
  x_local_.resize(max_local);
  phi_local_.resize(max_rows);
  jac_local_.resize(static_cast<size_t>(max_rows) * max_local);
}

bool LinearizedSystem::Assemble(const Eigen::VectorXd& x, double fairness_weight, double soft_scale,
                                std::string* message) {
  std::fill(a_.values.begin(), a_.values.end(), 0.0);
  for (int f = 0; f < problem_->num_families(); ++f) {
    ConstraintFamily& fam = problem_->family(f);
    fam.Update(problem_->layout(), x);
    const double s = std::sqrt(RowWeight(fam.role(), fam.weight(), fairness_weight, soft_scale));
    row_scale_[f] = s;
    const bool shifted = shift_.size() > 0 && fam.role() == FamilyRole::kConstraint;
    const int rows = fam.rows_per_element();
    const auto& begin = local_begin_[f];
    const auto& index = local_index_[f];
    const int* scatter = scatter_[f].data();
    int col = family_row_begin_[f];
    for (int e = 0; e < fam.num_elements(); ++e) {
      const int local_dim = begin[e + 1] - begin[e];
      for (int l = 0; l < local_dim; ++l) x_local_[l] = x[index[begin[e] + l]];
      fam.EvaluateElement(e, x_local_.data(), phi_local_.data(), jac_local_.data());
      for (int row = 0; row < rows; ++row, ++col, scatter += local_dim) {
        const double value = phi_local_[row];
        if (!std::isfinite(value)) {
          *message = "non-finite value in constraint family '" + fam.name() + "', element " +
                     std::to_string(e) + ", row " + std::to_string(row);
          return false;
        }
        phi_[col] = value;
        r_[col] = s * (shifted ? value - shift_[col] : value);
        const double* jac_row = jac_local_.data() + static_cast<size_t>(row) * local_dim;
        for (int l = 0; l < local_dim; ++l) {
          if (scatter[l] < 0) continue;
          if (!std::isfinite(jac_row[l])) {
            *message = "non-finite gradient in constraint family '" + fam.name() + "', element " +
                       std::to_string(e) + ", row " + std::to_string(row);
            return false;
          }
          a_.values[scatter[l]] += s * jac_row[l];
        }
      }
    }
  }
  for (int k : held_entries_) a_.values[k] = 0.0;
  return true;
}

void LinearizedSystem::ShiftConstraintTargets() {
  if (shift_.size() == 0) shift_.setZero(a_.num_cols);
  for (int f = 0; f < problem_->num_families(); ++f) {
    const ConstraintFamily& family = problem_->family(f);
    if (family.role() != FamilyRole::kConstraint || !family.ShiftsTargets()) continue;
    for (int col = family_row_begin_[f]; col < family_row_begin_[f + 1]; ++col) {
      shift_[col] -= phi_[col];
      r_[col] = row_scale_[f] * (phi_[col] - shift_[col]);
    }
  }
}

void LinearizedSystem::MultiplyAr(Eigen::VectorXd* out) const {
  out->setZero(a_.num_rows);
  for (int col = 0; col < a_.num_cols; ++col) {
    const double rc = r_[col];
    if (rc == 0.0) continue;
    for (int k = a_.col_begin[col]; k < a_.col_begin[col + 1]; ++k)
      (*out)[a_.row_index[k]] += a_.values[k] * rc;
  }
}

}  // namespace gproj

namespace gproj {

void LinearizedSystem::MultiplyNormal(const Eigen::VectorXd& d, double beta, Eigen::VectorXd* out) {
  for (int col = 0; col < a_.num_cols; ++col) {
    double sum = 0.0;
    for (int k = a_.col_begin[col]; k < a_.col_begin[col + 1]; ++k)
      sum += a_.values[k] * d[a_.row_index[k]];
    at_d_[col] = sum;
  }
  *out = beta * d;
  for (int col = 0; col < a_.num_cols; ++col) {
    const double v = at_d_[col];
    for (int k = a_.col_begin[col]; k < a_.col_begin[col + 1]; ++k)
      (*out)[a_.row_index[k]] += a_.values[k] * v;
  }
}

void LinearizedSystem::MultiplyAt(const Eigen::VectorXd& d, Eigen::VectorXd* out) const {
  out->resize(a_.num_cols);
  for (int col = 0; col < a_.num_cols; ++col) {
    double sum = 0.0;
    for (int k = a_.col_begin[col]; k < a_.col_begin[col + 1]; ++k)
      sum += a_.values[k] * d[a_.row_index[k]];
    (*out)[col] = sum;
  }
}

void LinearizedSystem::NormalDiagonal(Eigen::VectorXd* out) const {
  out->setZero(a_.num_rows);
  for (int k = 0; k < a_.col_begin[a_.num_cols]; ++k)
    (*out)[a_.row_index[k]] += a_.values[k] * a_.values[k];
}

void LinearizedSystem::SetHeld(const std::vector<int>& variables) {
  std::vector<bool> held(a_.num_rows, false);
  for (int i : variables) held[i] = true;
  held_entries_.clear();
  for (int k = 0; k < a_.nnz(); ++k)
    if (held[a_.row_index[k]]) held_entries_.push_back(k);
}

}  // namespace gproj
