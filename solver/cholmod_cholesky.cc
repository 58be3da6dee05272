// CHOLMOD backend: supernodal LLᵀ of A Aᵀ + β I, straight from A (no normal matrix formed).
#include <cholmod.h>

#include <cmath>
#include <cstdio>
#include <cstring>

#include "solver/sparse_cholesky.h"

extern "C" void openblas_set_num_threads(int num_threads);

namespace gproj {
namespace {

class CholmodCholesky : public SparseCholesky {
 public:
  CholmodCholesky(int num_threads, FillOrdering ordering) {
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
  }
  ~CholmodCholesky() override {
    if (factor_ != nullptr) cholmod_free_factor(&factor_, &common_);
    if (x_ != nullptr) cholmod_free_dense(&x_, &common_);
    if (y_ != nullptr) cholmod_free_dense(&y_, &common_);
    if (e_ != nullptr) cholmod_free_dense(&e_, &common_);
    if (b_ != nullptr) cholmod_free_dense(&b_, &common_);
    cholmod_finish(&common_);
  }

  bool Analyze(const CscMatrix& a, MatrixForm form, std::string* message) override {
    stype_ = form == MatrixForm::kSymmetric ? 1 : 0;
    cholmod_sparse view = View(a);
    if (factor_ != nullptr) cholmod_free_factor(&factor_, &common_);
    factor_ = cholmod_analyze(&view, &common_);
    flops_ = common_.fl;  // Cholesky flops of the chosen ordering
    if (factor_ == nullptr || common_.status != CHOLMOD_OK) {
      *message = "CHOLMOD analysis failed (status " + std::to_string(common_.status) + ")";
      return false;
    }
    n_ = a.num_rows;
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

  double FactorFlops() const override { return factor_ != nullptr ? flops_ : 0.0; }

  int64_t FactorNonZeros() const override {
    if (factor_ == nullptr) return 0;
    return factor_->is_super ? static_cast<int64_t>(factor_->xsize)
                             : static_cast<int64_t>(factor_->nzmax);
  }

 private:
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
