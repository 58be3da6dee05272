#include "solver/sparse_cholesky.h"

namespace gproj {

std::unique_ptr<SparseCholesky> CreateCholmodCholesky(int num_threads);
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

std::unique_ptr<SparseCholesky> CreateSparseCholesky(LinearSolverType type, int num_threads) {
  if (type == LinearSolverType::kEigen) return CreateEigenCholesky();
  return CreateCholmodCholesky(num_threads);
}

}  // namespace gproj
