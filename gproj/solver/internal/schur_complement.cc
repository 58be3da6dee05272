#include "gproj/solver/internal/schur_complement.h"

#include <Eigen/Cholesky>
#include <algorithm>
#include <cstdint>

namespace gproj {
namespace {

using SmallMatrix = Eigen::Matrix<double, Eigen::Dynamic, Eigen::Dynamic, Eigen::ColMajor,
                                  SchurComplement::kMaxItemDim, SchurComplement::kMaxItemDim>;
using SmallVector =
    Eigen::Matrix<double, Eigen::Dynamic, 1, Eigen::ColMajor, SchurComplement::kMaxItemDim, 1>;

}  // namespace

bool SchurComplement::Init(const VariableLayout& layout, const CscMatrix& a, std::string* message) {
  std::vector<int> item_of_var;
  if (!CollectItems(layout, a.num_rows, &item_of_var, message)) return false;
  if (!SplitColumns(a, item_of_var, message)) return false;
  GroupColumnsByItem(a.num_cols);
  BuildPattern(a.num_cols);
  return true;
}

// The items of the eliminable blocks; item_of_var maps each variable to its item (or −1), and
// the kept variables are numbered in order.
bool SchurComplement::CollectItems(const VariableLayout& layout, int n,
                                   std::vector<int>* item_of_var_out, std::string* message) {
  std::vector<int>& item_of_var = *item_of_var_out;
  item_of_var.assign(n, -1);
  items_.clear();
  num_eliminated_ = 0;
  for (int b = 0; b < layout.num_blocks(); ++b) {
    const VariableBlock& block = layout.block(b);
    if (!block.eliminable) continue;
    if (block.item_dim > kMaxItemDim) {
      *message = "items of block '" + block.name + "' are larger than " +
                 std::to_string(kMaxItemDim) + " scalars";
      return false;
    }
    for (int i = 0; i < block.num_items; ++i) {
      Item item;
      item.first_var = block.offset + i * block.item_dim;
      item.dim = block.item_dim;
      for (int c = 0; c < item.dim; ++c) item_of_var[item.first_var + c] = items_.size();
      items_.push_back(item);
      num_eliminated_ += item.dim;
    }
  }
  if (items_.empty()) {
    *message = "no eliminable variable blocks";
    return false;
  }
  kept_of_var_.assign(n, -1);
  kept_var_.clear();
  for (int v = 0; v < n; ++v) {
    if (item_of_var[v] >= 0) continue;
    kept_of_var_[v] = static_cast<int>(kept_var_.size());
    kept_var_.push_back(v);
  }
  return true;
}

// Every column of A split into kept and eliminated entries; a column may touch one item only.
// The entries are counted first so that every array has its exact size (at a million faces
// the slack of growing vectors would be hundreds of megabytes).
bool SchurComplement::SplitColumns(const CscMatrix& a, const std::vector<int>& item_of_var,
                                   std::string* message) {
  const int m = a.num_cols;
  col_item_.assign(m, -1);
  col_kept_begin_.assign(m + 1, 0);
  col_elim_begin_.assign(m + 1, 0);
  for (int c = 0; c < m; ++c) {
    int kept = 0, elim = 0;
    for (int k = a.col_begin[c]; k < a.col_begin[c + 1]; ++k) {
      const int e = item_of_var[a.row_index[k]];
      if (e < 0) {
        ++kept;
        continue;
      }
      if (col_item_[c] >= 0 && col_item_[c] != e) {
        *message = "row " + std::to_string(c) + " touches two eliminated items";
        return false;
      }
      col_item_[c] = e;
      ++elim;
    }
    col_kept_begin_[c + 1] = col_kept_begin_[c] + kept;
    col_elim_begin_[c + 1] = col_elim_begin_[c] + elim;
  }
  kept_pos_.assign(col_kept_begin_[m], 0);
  kept_idx_.assign(col_kept_begin_[m], 0);
  elim_pos_.assign(col_elim_begin_[m], 0);
  elim_comp_.assign(col_elim_begin_[m], 0);
  for (int c = 0; c < m; ++c) {
    int kept = col_kept_begin_[c], elim = col_elim_begin_[c];
    for (int k = a.col_begin[c]; k < a.col_begin[c + 1]; ++k) {
      const int var = a.row_index[k];
      const int e = item_of_var[var];
      if (e < 0) {
        kept_pos_[kept] = k;
        kept_idx_[kept++] = kept_of_var_[var];
      } else {
        elim_pos_[elim] = k;
        elim_comp_[elim++] = var - items_[e].first_var;
      }
    }
  }
  return true;
}

// Columns of each item (counting sort), and K_e, the kept variables coupled to it.
void SchurComplement::GroupColumnsByItem(int m) {
  std::vector<int> count(items_.size() + 1, 0);
  for (int c = 0; c < m; ++c)
    if (col_item_[c] >= 0) ++count[col_item_[c] + 1];
  for (size_t e = 0; e < items_.size(); ++e) count[e + 1] += count[e];
  item_cols_.assign(count.back(), 0);
  for (size_t e = 0; e < items_.size(); ++e) {
    items_[e].col_begin = count[e];
    items_[e].col_end = count[e];
  }
  free_cols_.clear();
  for (int c = 0; c < m; ++c)
    if (col_item_[c] >= 0)
      item_cols_[items_[col_item_[c]].col_end++] = c;
    else
      free_cols_.push_back(c);
  kept_vars_.clear();
  int64_t v_size = 0;
  int dinv_size = 0, max_kept = 0, max_cols = 0;
  for (Item& item : items_) {
    item.kept_begin = static_cast<int>(kept_vars_.size());
    for (int j = item.col_begin; j < item.col_end; ++j) {
      const int c = item_cols_[j];
      for (int k = col_kept_begin_[c]; k < col_kept_begin_[c + 1]; ++k)
        kept_vars_.push_back(kept_idx_[k]);
    }
    std::sort(kept_vars_.begin() + item.kept_begin, kept_vars_.end());
    kept_vars_.erase(std::unique(kept_vars_.begin() + item.kept_begin, kept_vars_.end()),
                     kept_vars_.end());
    item.kept_end = static_cast<int>(kept_vars_.size());
    item.v_offset = v_size;
    v_size += static_cast<int64_t>(item.col_end - item.col_begin) * item.dim;
    item.dinv_offset = dinv_size;
    dinv_size += item.dim * item.dim;
    max_kept = std::max(max_kept, item.kept_end - item.kept_begin);
    max_cols = std::max(max_cols, item.col_end - item.col_begin);
  }
  ak_.resize(max_kept, max_cols);
  ae_.resize(kMaxItemDim, max_cols);
  p_.resize(max_cols, max_cols);
  w_.resize(max_kept, max_cols);
  clique_.resize(max_kept, max_kept);
  v_.assign(v_size, 0.0);
  dinv_.assign(dinv_size, 0.0);
  kept_local_.assign(kept_pos_.size(), -1);
  for (int c = 0; c < m; ++c) {
    if (col_item_[c] < 0) continue;
    const Item& item = items_[col_item_[c]];
    const auto begin = kept_vars_.begin() + item.kept_begin;
    const auto end = kept_vars_.begin() + item.kept_end;
    for (int k = col_kept_begin_[c]; k < col_kept_begin_[c + 1]; ++k)
      kept_local_[k] = static_cast<int>(std::lower_bound(begin, end, kept_idx_[k]) - begin);
  }
}

// Pattern of S (upper triangle): the diagonal, kept pairs of every column, item cliques; and the
// positions in S that each column pair and each clique entry adds to. Every entry S receives is
// bucketed by its column of S (a counting sort); each bucket is deduplicated and sorted into
// S's column, then overwritten with the positions of its entries, which a last pass in the
// same order hands out.
void SchurComplement::BuildPattern(int m) {
  const int num_kept = static_cast<int>(kept_var_.size());
  // Calls visit(row, col), row ≤ col, for every entry S receives (with repeats), in the order
  // of pair_pos_ and then clique_pos_ after the diagonal.
  auto for_each_entry = [&](auto&& diagonal, auto&& column_pair, auto&& clique_pair) {
    for (int j = 0; j < num_kept; ++j) diagonal(j);
    for (int c : free_cols_)  // A's row indices are sorted, so kept_idx_ is within a column
      for (int p = col_kept_begin_[c]; p < col_kept_begin_[c + 1]; ++p)
        for (int q = p; q < col_kept_begin_[c + 1]; ++q) column_pair(kept_idx_[p], kept_idx_[q]);
    for (const Item& item : items_)  // K_e is sorted
      for (int p = item.kept_begin; p < item.kept_end; ++p)
        for (int q = p; q < item.kept_end; ++q) clique_pair(kept_vars_[p], kept_vars_[q]);
  };
  auto pairs = [](int k) { return k * (k + 1) / 2; };
  col_pair_begin_.assign(m + 1, 0);  // a column of an item adds to its item's clique
  for (int c = 0; c < m; ++c)
    col_pair_begin_[c + 1] =
        col_pair_begin_[c] +
        (col_item_[c] < 0 ? pairs(col_kept_begin_[c + 1] - col_kept_begin_[c]) : 0);
  int num_clique_pairs = 0;
  for (Item& item : items_) {
    item.clique_begin = num_clique_pairs;
    num_clique_pairs += pairs(item.kept_end - item.kept_begin);
  }
  std::vector<int64_t> bucket(num_kept + 1, 0);
  auto count = [&](int, int col) { ++bucket[col + 1]; };
  for_each_entry([&](int j) { ++bucket[j + 1]; }, count, count);
  for (int j = 0; j < num_kept; ++j) bucket[j + 1] += bucket[j];
  std::vector<int> entries(bucket.back());  // rows, then positions in S
  std::vector<int64_t> next(bucket.begin(), bucket.end() - 1);
  auto place = [&](int row, int col) { entries[next[col]++] = row; };
  for_each_entry([&](int j) { entries[next[j]++] = j; }, place, place);

  s_ = CscMatrix();
  s_.num_rows = s_.num_cols = num_kept;
  s_.col_begin.assign(1, 0);
  std::vector<int> seen(num_kept, -1);  // the last column each row was added to
  std::vector<int> position(num_kept);  // of each row in the current column
  for (int j = 0; j < num_kept; ++j) {
    const int first = static_cast<int>(s_.row_index.size());
    for (int64_t k = bucket[j]; k < bucket[j + 1]; ++k) {
      const int row = entries[k];
      if (seen[row] == j) continue;
      seen[row] = j;
      s_.row_index.push_back(row);
    }
    std::sort(s_.row_index.begin() + first, s_.row_index.end());
    const int last = static_cast<int>(s_.row_index.size());
    for (int k = first; k < last; ++k) position[s_.row_index[k]] = k;
    for (int64_t k = bucket[j]; k < bucket[j + 1]; ++k) entries[k] = position[entries[k]];
    s_.col_begin.push_back(last);
  }
  s_.row_index.shrink_to_fit();
  s_.values.assign(s_.row_index.size(), 0.0);

  std::copy(bucket.begin(), bucket.end() - 1, next.begin());
  pair_pos_.clear();
  pair_pos_.reserve(col_pair_begin_.back());
  clique_pos_.clear();
  clique_pos_.reserve(num_clique_pairs);
  for_each_entry([&](int j) { ++next[j]; },
                 [&](int, int col) { pair_pos_.push_back(entries[next[col]++]); },
                 [&](int, int col) { clique_pos_.push_back(entries[next[col]++]); });
}

bool SchurComplement::Form(const CscMatrix& a, double beta, std::string* message) {
  std::fill(s_.values.begin(), s_.values.end(), 0.0);
  // Columns that touch no eliminated item: their kept pairs, one by one.
  for (int c : free_cols_) {
    const int* pos = pair_pos_.data() + col_pair_begin_[c];
    const int begin = col_kept_begin_[c], end = col_kept_begin_[c + 1];
    for (int p = begin; p < end; ++p) {
      const double vp = a.values[kept_pos_[p]];
      for (int q = p; q < end; ++q) s_.values[*pos++] += vp * a.values[kept_pos_[q]];
    }
  }
  // Per item, its columns as dense blocks A_K (|K_e| × cols) and A_e (dim × cols). With
  // D = A_e A_eᵀ + β I = L Lᵀ and T = L⁻¹ A_e,
  //   S_KK += A_K A_Kᵀ − A_K A_eᵀ D⁻¹ A_e A_Kᵀ = A_K P A_Kᵀ,  P = I − Tᵀ T (cols × cols),
  // added to S once per clique entry; fewer flops than forming B = A_K A_eᵀ when the item has
  // about as many columns as components.
  for (const Item& item : items_) {
    const int d = item.dim, kk = item.kept_end - item.kept_begin;
    const int nc = item.col_end - item.col_begin;
    auto ak = ak_.topLeftCorner(kk, nc);
    auto ae = ae_.topLeftCorner(d, nc);
    ak.setZero();
    ae.setZero();
    for (int j = 0; j < nc; ++j) {
      const int c = item_cols_[item.col_begin + j];
      for (int k = col_elim_begin_[c]; k < col_elim_begin_[c + 1]; ++k)
        ae(elim_comp_[k], j) = a.values[elim_pos_[k]];
      for (int k = col_kept_begin_[c]; k < col_kept_begin_[c + 1]; ++k)
        ak(kept_local_[k], j) = a.values[kept_pos_[k]];
    }
    SmallMatrix block = SmallMatrix::Identity(d, d) * beta;
    block.noalias() += ae * ae.transpose();
    Eigen::LLT<SmallMatrix> llt(block);
    if (llt.info() != Eigen::Success) {
      *message = "an eliminated block is not positive definite";
      return false;
    }
    Eigen::Map<SmallMatrix> dinv(dinv_.data() + item.dinv_offset, d, d);
    dinv = llt.solve(SmallMatrix::Identity(d, d));
    // V = A_eᵀ D⁻¹ for the right-hand side and the back substitution.
    Eigen::Map<Eigen::MatrixXd> v(v_.data() + item.v_offset, nc, d);
    v.noalias() = ae.transpose() * dinv;
    llt.matrixL().solveInPlace(ae);  // T
    auto p = p_.topLeftCorner(nc, nc);
    p.setIdentity();
    p.noalias() -= ae.transpose() * ae;
    auto w = w_.topLeftCorner(kk, nc);
    w.noalias() = ak * p;
    auto clique = clique_.topLeftCorner(kk, kk);
    clique.triangularView<Eigen::Upper>() = w * ak.transpose();
    const int* pos = clique_pos_.data() + item.clique_begin;
    for (int q = 0; q < kk; ++q)
      for (int r = q; r < kk; ++r) s_.values[*pos++] += clique(q, r);
  }
  return true;
}

// reduced = g_K − A_K A_eᵀ D⁻¹ g_e = g_K − A_K (V g_e) per item, A_K read from A's columns.
void SchurComplement::ReduceRhs(const CscMatrix& a, const Eigen::VectorXd& g,
                                Eigen::VectorXd* reduced) const {
  const int num_kept = static_cast<int>(kept_var_.size());
  for (int k = 0; k < num_kept; ++k) (*reduced)[k] = g[kept_var_[k]];
  for (const Item& item : items_) {
    const int d = item.dim, nc = item.col_end - item.col_begin;
    const Eigen::Map<const Eigen::MatrixXd> v(v_.data() + item.v_offset, nc, d);
    for (int j = 0; j < nc; ++j) {
      const int c = item_cols_[item.col_begin + j];
      const double t = v.row(j).dot(g.segment(item.first_var, d));
      for (int k = col_kept_begin_[c]; k < col_kept_begin_[c + 1]; ++k)
        (*reduced)[kept_idx_[k]] -= a.values[kept_pos_[k]] * t;
    }
  }
}

// d_e = D⁻¹ g_e − Vᵀ A_Kᵀ d_K per item.
void SchurComplement::BackSubstitute(const CscMatrix& a, const Eigen::VectorXd& d_kept,
                                     const Eigen::VectorXd& g, Eigen::VectorXd* d) const {
  const int num_kept = static_cast<int>(kept_var_.size());
  for (int k = 0; k < num_kept; ++k) (*d)[kept_var_[k]] = d_kept[k];
  for (const Item& item : items_) {
    const int dim = item.dim, nc = item.col_end - item.col_begin;
    const Eigen::Map<const Eigen::MatrixXd> v(v_.data() + item.v_offset, nc, dim);
    const Eigen::Map<const SmallMatrix> dinv(dinv_.data() + item.dinv_offset, dim, dim);
    SmallVector de = dinv * g.segment(item.first_var, dim);
    for (int j = 0; j < nc; ++j) {
      const int c = item_cols_[item.col_begin + j];
      double u = 0.0;  // (A_Kᵀ d_K)_j
      for (int k = col_kept_begin_[c]; k < col_kept_begin_[c + 1]; ++k)
        u += a.values[kept_pos_[k]] * d_kept[kept_idx_[k]];
      de -= u * v.row(j).transpose();
    }
    d->segment(item.first_var, dim) = de;
  }
}

}  // namespace gproj
