#include "gproj/solver/sparse_cholesky.h"

namespace gproj {

std::unique_ptr<SparseCholesky> CreateCholmodCholesky(int num_threads, FillOrdering ordering);

namespace {
constexpr const char* kFillOrderingNames[] = {"auto", "amd", "metis", "nesdis"};
}  // namespace

const char* FillOrderingName(FillOrdering ordering) {
  return kFillOrderingNames[static_cast<int>(ordering)];
}

bool ParseFillOrdering(const std::string& name, FillOrdering* ordering) {
  for (int k = 0; k < 4; ++k)
    if (name == kFillOrderingNames[k]) {
      *ordering = static_cast<FillOrdering>(k);
      return true;
    }
  return false;
}
std::unique_ptr<SparseCholesky> CreateEigenCholesky();

const char* LinearSolverTypeName(LinearSolverType type) {
  return type == LinearSolverType::kCholmod ? "cholmod" : "eigen";
}

bool ParseLinearSolverType(const std::string& name, LinearSolverType* type) {
  if (name == "cholmod") {
    *type = LinearSolverType::kCholmod;
    return true;
  }
  if (name == "eigen") {
    *type = LinearSolverType::kEigen;
    return true;
  }
  return false;
}

CscMatrix ToCsc(const Eigen::SparseMatrix<double>& a) {
  CscMatrix out;
  out.num_rows = static_cast<int>(a.rows());
  out.num_cols = static_cast<int>(a.cols());
  out.col_begin.assign(a.outerIndexPtr(), a.outerIndexPtr() + a.cols() + 1);
  out.row_index.assign(a.innerIndexPtr(), a.innerIndexPtr() + a.nonZeros());
  out.values.assign(a.valuePtr(), a.valuePtr() + a.nonZeros());
  return out;
}

std::unique_ptr<SparseCholesky> CreateSparseCholesky(LinearSolverType type, int num_threads,
                                                     FillOrdering ordering) {
  if (type == LinearSolverType::kEigen) return CreateEigenCholesky();
  return CreateCholmodCholesky(num_threads, ordering);
}

}  // namespace gproj
