// CHOLMOD backend: supernodal LLᵀ of A Aᵀ + β I, straight from A (no normal matrix formed).
#include <cholmod.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <utility>
#include <vector>

#include "gproj/solver/sparse_cholesky.h"

extern "C" void openblas_set_num_threads(int num_threads);

namespace gproj {
namespace {

class CholmodCholesky : public SparseCholesky {
 public:
  CholmodCholesky(int num_threads, FillOrdering ordering) : ordering_(ordering) {
    cholmod_start(&common_);
    common_.supernodal = CHOLMOD_SUPERNODAL;
    common_.final_ll = 1;
    common_.print = 0;
    common_.error_handler = nullptr;
    if (ordering != FillOrdering::kAuto) {
      common_.nmethods = 1;
      common_.method[0].ordering = ordering == FillOrdering::kAmd     ? CHOLMOD_AMD
                                   : ordering == FillOrdering::kMetis ? CHOLMOD_METIS
                                                                      : CHOLMOD_NESDIS;
    }
    if (num_threads > 0) openblas_set_num_threads(num_threads);
    // Relaxed supernodal amalgamation: supernodes may take twice CHOLMOD's share of explicit
    // zeros (zrelax 0.9 / 0.2 / 0.1 instead of 0.8 / 0.1 / 0.05 for supernodes of up to 8 / 32 /
    // 128 columns instead of 4 / 16 / 48). Wider supernodes put more of the work in dense BLAS
    // calls: on the noisy planarisation grids the factor has 13–19% more entries and the
    // numeric factorisation takes 10–30% less time (201²: 1.6 s → 1.4 s; 101²: 0.35 s →
    // 0.25 s; bench BM_PlanarizationIteration).
    common_.nrelax[0] = 8;
    common_.nrelax[1] = 32;
    common_.nrelax[2] = 128;
    common_.zrelax[0] = 0.9;
    common_.zrelax[1] = 0.2;
    common_.zrelax[2] = 0.1;
  }
  ~CholmodCholesky() override {
    if (factor_ != nullptr) cholmod_free_factor(&factor_, &common_);
    if (x_ != nullptr) cholmod_free_dense(&x_, &common_);
    if (y_ != nullptr) cholmod_free_dense(&y_, &common_);
    if (e_ != nullptr) cholmod_free_dense(&e_, &common_);
    if (b_ != nullptr) cholmod_free_dense(&b_, &common_);
    cholmod_finish(&common_);
  }

  void SetGroups(std::vector<int> group_begin) override { group_begin_ = std::move(group_begin); }

  bool Analyze(const CscMatrix& a, MatrixForm form, std::string* message) override {
    stype_ = form == MatrixForm::kSymmetric ? 1 : 0;
    cholmod_sparse view = View(a);
    if (factor_ != nullptr) cholmod_free_factor(&factor_, &common_);
    const int num_groups = static_cast<int>(group_begin_.size()) - 1;
    if (num_groups > 0 && num_groups < a.num_rows && group_begin_.back() == a.num_rows) {
      factor_ = AnalyzeGroups(a, &view);
    } else {
      factor_ = cholmod_analyze(&view, &common_);
      flops_ = common_.fl;  // Cholesky flops of the chosen ordering
    }
    if (factor_ == nullptr || common_.status != CHOLMOD_OK) {
      *message = "CHOLMOD analysis failed (status " + std::to_string(common_.status) + ")";
      return false;
    }
    n_ = a.num_rows;
    // A second analysis (another pattern) replaces the right-hand side of the first.
    if (b_ != nullptr) cholmod_free_dense(&b_, &common_);
    b_ = cholmod_zeros(n_, 1, CHOLMOD_REAL, &common_);
    return true;
  }

  bool Factorize(const CscMatrix& a, double beta, std::string* message) override {
    cholmod_sparse view = View(a);
    double beta_pair[2] = {beta, 0.0};
    const int ok = cholmod_factorize_p(&view, beta_pair, nullptr, 0, factor_, &common_);
    if (!ok || common_.status == CHOLMOD_NOT_POSDEF || static_cast<int>(factor_->minor) < n_) {
      *message = "CHOLMOD factorisation failed: matrix not positive definite at column " +
                 std::to_string(factor_->minor);
      return false;
    }
    if (common_.status != CHOLMOD_OK) {
      *message = "CHOLMOD factorisation failed (status " + std::to_string(common_.status) + ")";
      return false;
    }
    return true;
  }

  bool Solve(const double* rhs, double* x, std::string* message) override {
    std::memcpy(b_->x, rhs, sizeof(double) * n_);
    // cholmod_solve2 reuses x_, y_, e_ across calls: no allocation after the first solve.
    if (!cholmod_solve2(CHOLMOD_A, factor_, b_, nullptr, &x_, nullptr, &y_, &e_, &common_)) {
      *message = "CHOLMOD solve failed (status " + std::to_string(common_.status) + ")";
      return false;
    }
    std::memcpy(x, x_->x, sizeof(double) * n_);
    return true;
  }

  std::vector<int> FillPermutation() const override {
    if (factor_ == nullptr) return {};
    const int* perm = static_cast<const int*>(factor_->Perm);
    return std::vector<int>(perm, perm + n_);
  }

  double FactorFlops() const override { return factor_ != nullptr ? flops_ : 0.0; }

  int64_t FactorNonZeros() const override {
    if (factor_ == nullptr) return 0;
    return factor_->is_super ? static_cast<int64_t>(factor_->xsize)
                             : static_cast<int64_t>(factor_->nzmax);
  }

 private:
  // The pattern of `a` with its rows (and, for a symmetric matrix, its columns) merged by
  // group: an upper triangle of the groups' graph, or the groups × m matrix whose C Cᵀ is it.
  CscMatrix GroupPattern(const CscMatrix& a) const {
    std::vector<int> group_of(a.num_rows);
    for (size_t g = 0; g + 1 < group_begin_.size(); ++g)
      for (int v = group_begin_[g]; v < group_begin_[g + 1]; ++v) group_of[v] = g;
    const int num_groups = static_cast<int>(group_begin_.size()) - 1;
    const int num_cols = stype_ == 1 ? num_groups : a.num_cols;
    CscMatrix c;
    c.num_rows = num_groups;
    c.num_cols = num_cols;
    c.col_begin.assign(1, 0);
    std::vector<int> seen(num_groups, -1);
    for (int j = 0; j < num_cols; ++j) {
      const int first_col = stype_ == 1 ? group_begin_[j] : j;
      const int end_col = stype_ == 1 ? group_begin_[j + 1] : j + 1;
      const size_t first = c.row_index.size();
      for (int col = first_col; col < end_col; ++col)
        for (int k = a.col_begin[col]; k < a.col_begin[col + 1]; ++k) {
          const int g = group_of[a.row_index[k]];
          if (seen[g] == j) continue;
          seen[g] = j;
          c.row_index.push_back(g);
        }
      std::sort(c.row_index.begin() + first, c.row_index.end());
      c.col_begin.push_back(static_cast<int>(c.row_index.size()));
    }
    return c;
  }

  // Orders the groups' graph, expands the order to the variables (each group kept together, in
  // its own order) and analyses with it. kAuto follows CHOLMOD's default on the groups: AMD,
  // and METIS as well when AMD's factor is dense (flops / nnz(L) ≥ 500 and nnz(L) ≥ 5 n),
  // keeping the one with fewer flops.
  cholmod_factor* AnalyzeGroups(const CscMatrix& a, cholmod_sparse* view) {
    const CscMatrix c = GroupPattern(a);
    cholmod_sparse graph = View(c);
    graph.xtype = CHOLMOD_PATTERN;
    graph.x = nullptr;
    const int num_groups = c.num_rows;
    std::vector<int> group_perm(num_groups), perm(a.num_rows);
    const int saved_nmethods = common_.nmethods;
    const int saved_ordering = common_.method[0].ordering;
    common_.nmethods = 1;
    common_.method[0].ordering = CHOLMOD_GIVEN;
    cholmod_factor* best = nullptr;
    double best_flops = 0.0, best_lnz = 0.0;
    auto try_ordering = [&](FillOrdering ordering) {
      bool ordered = false;
      if (ordering == FillOrdering::kMetis) {
        ordered = cholmod_metis(&graph, nullptr, 0, /*postorder=*/0, group_perm.data(), &common_);
      } else if (ordering == FillOrdering::kNestedDissection) {
        std::vector<int> parent(num_groups), member(num_groups);
        ordered = cholmod_nested_dissection(&graph, nullptr, 0, group_perm.data(), parent.data(),
                                            member.data(), &common_) > 0;
      } else {
        ordered = cholmod_amd(&graph, nullptr, 0, group_perm.data(), &common_);
      }
      if (!ordered) return;
      int k = 0;
      for (int g : group_perm)
        for (int v = group_begin_[g]; v < group_begin_[g + 1]; ++v) perm[k++] = v;
      cholmod_factor* factor = cholmod_analyze_p(view, perm.data(), nullptr, 0, &common_);
      if (factor == nullptr || common_.status != CHOLMOD_OK) return;
      if (best == nullptr || common_.fl < best_flops) {
        if (best != nullptr) cholmod_free_factor(&best, &common_);
        best = factor;
        best_flops = common_.fl;
        best_lnz = common_.lnz;
      } else {
        cholmod_free_factor(&factor, &common_);
      }
    };
    if (ordering_ == FillOrdering::kAuto) {
      try_ordering(FillOrdering::kAmd);
      if (best == nullptr || (best_flops / best_lnz >= 500.0 && best_lnz >= 5.0 * a.num_rows))
        try_ordering(FillOrdering::kMetis);
    } else {
      try_ordering(ordering_);
    }
    common_.nmethods = saved_nmethods;
    common_.method[0].ordering = saved_ordering;
    if (best != nullptr) {
      common_.status = CHOLMOD_OK;
      flops_ = best_flops;
    }
    return best;
  }

  // A non-owning CHOLMOD header over our arrays.
  cholmod_sparse View(const CscMatrix& a) const {
    cholmod_sparse s;
    std::memset(&s, 0, sizeof(s));
    s.nrow = a.num_rows;
    s.ncol = a.num_cols;
    s.nzmax = a.nnz();
    s.p = const_cast<int*>(a.col_begin.data());
    s.i = const_cast<int*>(a.row_index.data());
    s.x = const_cast<double*>(a.values.data());
    s.stype = stype_;  // 0: A (factor A Aᵀ + βI); 1: upper triangle of S (factor S + βI)
    s.itype = CHOLMOD_INT;
    s.xtype = CHOLMOD_REAL;
    s.dtype = CHOLMOD_DOUBLE;
    s.sorted = 1;
    s.packed = 1;
    return s;
  }

  cholmod_common common_;
  cholmod_factor* factor_ = nullptr;
  FillOrdering ordering_;
  std::vector<int> group_begin_;  // SetGroups
  double flops_ = 0.0;
  cholmod_dense* b_ = nullptr;
  cholmod_dense* x_ = nullptr;
  cholmod_dense* y_ = nullptr;
  cholmod_dense* e_ = nullptr;
  int n_ = 0;
  int stype_ = 0;
};

}  // namespace

std::unique_ptr<SparseCholesky> CreateCholmodCholesky(int num_threads, FillOrdering ordering) {
  return std::make_unique<CholmodCholesky>(num_threads, ordering);
}

}  // namespace gproj
