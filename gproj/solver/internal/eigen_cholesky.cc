// Eigen backend: forms A Aᵀ + β I explicitly and factors it with SimplicialLLT. Slower than
// CHOLMOD; kept as a fallback and as the oracle in the backend conformance tests.
#include <Eigen/SparseCholesky>
#include <Eigen/SparseCore>

#include "gproj/solver/sparse_cholesky.h"

namespace gproj {
namespace {

using SpMat = Eigen::SparseMatrix<double, Eigen::ColMajor, int>;

class EigenCholesky : public SparseCholesky {
 public:
  bool Analyze(const CscMatrix& a, MatrixForm form, std::string* message) override {
    form_ = form;
    Form(a, 1.0);
    llt_.analyzePattern(normal_);
    if (llt_.info() != Eigen::Success) {
      *message = "Eigen symbolic analysis failed";
      return false;
    }
    return true;
  }

  bool Factorize(const CscMatrix& a, double beta, std::string* message) override {
    Form(a, beta);
    llt_.factorize(normal_);
    if (llt_.info() != Eigen::Success) {
      *message = "Eigen factorisation failed: matrix not positive definite";
      return false;
    }
    return true;
  }

  bool Solve(const double* rhs, double* x, std::string* message) override {
    Eigen::Map<const Eigen::VectorXd> b(rhs, normal_.rows());
    Eigen::Map<Eigen::VectorXd>(x, normal_.rows()) = llt_.solve(b);
    if (llt_.info() != Eigen::Success) {
      *message = "Eigen solve failed";
      return false;
    }
    return true;
  }

  int64_t FactorNonZeros() const override { return llt_.matrixL().nestedExpression().nonZeros(); }

 private:
  void Form(const CscMatrix& a, double beta) {
    Eigen::Map<const SpMat> am(a.num_rows, a.num_cols, a.nnz(), a.col_begin.data(),
                               a.row_index.data(), a.values.data());
    SpMat identity(a.num_rows, a.num_rows);
    identity.setIdentity();
    if (form_ == MatrixForm::kAAt) {
      normal_ = am * am.transpose() + beta * identity;
    } else {
      normal_ = SpMat(am.selfadjointView<Eigen::Upper>()) + beta * identity;
    }
  }

  MatrixForm form_ = MatrixForm::kAAt;
  SpMat normal_;
  Eigen::SimplicialLLT<SpMat, Eigen::Lower, Eigen::AMDOrdering<int>> llt_;
};

}  // namespace

std::unique_ptr<SparseCholesky> CreateEigenCholesky() { return std::make_unique<EigenCholesky>(); }

}  // namespace gproj
