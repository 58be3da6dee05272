#pragma once
// Sparse Cholesky behind an interface: factors  N = A Aᵀ + β I  given A (n × m, CSC), the
// transposed, weighted Jacobian of guided projection, or  S + β I  given a symmetric S (the
// Schur complement once per-element auxiliaries are eliminated). The pattern is fixed per
// problem: Analyze once (ordering + symbolic factorisation), then Factorize per iteration.

#include <Eigen/SparseCore>
#include <cstdint>
#include <memory>
#include <string>
#include <vector>

namespace gproj {

// Compressed sparse columns, 0-based, row indices sorted and unique within each column.
struct CscMatrix {
  int num_rows = 0;
  int num_cols = 0;
  std::vector<int> col_begin;  // num_cols + 1
  std::vector<int> row_index;  // nnz
  std::vector<double> values;  // nnz
  int nnz() const { return static_cast<int>(row_index.size()); }
};

// The CSC form of a compressed Eigen matrix (makeCompressed()).
CscMatrix ToCsc(const Eigen::SparseMatrix<double>& a);

enum class LinearSolverType {
  kCholmod,  // CHOLMOD supernodal (default)
  kEigen,    // Eigen SimplicialLLT on the explicitly formed matrix (fallback, test oracle)
};

// The fill-reducing ordering of the symbolic analysis (CHOLMOD; the Eigen backend always uses
// its AMD).
enum class FillOrdering {
  kAuto,              // CHOLMOD's default: AMD, and METIS as well when AMD's fill is high
  kAmd,               // approximate minimum degree (on the pattern of A Aᵀ for kAAt)
  kMetis,             // METIS nested dissection
  kNestedDissection,  // CHOLMOD's own nested dissection (NESDIS, METIS's partitioner)
};
const char* FillOrderingName(FillOrdering ordering);
// Parses "auto" / "amd" / "metis" / "nesdis"; returns false for anything else.
bool ParseFillOrdering(const std::string& name, FillOrdering* ordering);

const char* LinearSolverTypeName(LinearSolverType type);
// Parses "cholmod" / "eigen"; returns false for anything else.
bool ParseLinearSolverType(const std::string& name, LinearSolverType* type);

// What the matrix handed to Analyze/Factorize stands for.
enum class MatrixForm {
  kAAt,        // a is A (n × m): factor A Aᵀ + β I without forming it
  kSymmetric,  // a is the upper triangle of a symmetric n × n matrix S: factor S + β I
};

class SparseCholesky {
 public:
  virtual ~SparseCholesky() = default;
  // Declares groups of consecutive variables that share their pattern (the 3 coordinates of a
  // vertex): group g is [group_begin[g], group_begin[g + 1]), from 0 to n. The ordering is then
  // computed on the graph of the groups, which is smaller by their size, and each group is kept
  // together. Call before Analyze; empty: order the scalars. Backends may ignore it.
  virtual void SetGroups(std::vector<int> group_begin) { (void)group_begin; }
  // Symbolic analysis (ordering, elimination tree) for the pattern of `a`. False (and
  // `message`) on failure.
  virtual bool Analyze(const CscMatrix& a, MatrixForm form, std::string* message) = 0;
  // Numeric factorisation; `a` must have the analysed pattern and form. False when the
  // matrix is not numerically positive definite or values are non-finite.
  virtual bool Factorize(const CscMatrix& a, double beta, std::string* message) = 0;
  // x = N⁻¹ rhs, both of length n. False on failure.
  virtual bool Solve(const double* rhs, double* x, std::string* message) = 0;
  // Stored entries of the factor L (0 before the first factorisation).
  virtual int64_t FactorNonZeros() const = 0;
  // The fill-reducing permutation of the analysis: entry k is the variable eliminated k-th
  // (empty when the backend does not expose it).
  virtual std::vector<int> FillPermutation() const { return {}; }
  // Floating-point operations of one numeric factorisation, as counted by the analysis (0 when
  // the backend does not count them).
  virtual double FactorFlops() const { return 0.0; }
};

std::unique_ptr<SparseCholesky> CreateSparseCholesky(LinearSolverType type, int num_threads,
                                                     FillOrdering ordering = FillOrdering::kAuto);

}  // namespace gproj
