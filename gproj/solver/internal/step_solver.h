#pragma once
// The linear algebra of one guided-projection step (003 eq. 11): with A and r from the
// LinearizedSystem at x^k, solves
//   (A Aᵀ + ε² I) d = −A r
// by sparse Cholesky, first eliminating per-element auxiliaries by a Schur complement when the
// layout allows it, and checks the solve. The pattern is analysed once (Analyze); each Solve
// refactorises numerically. Internal to the solver.

#include <Eigen/Core>
#include <memory>
#include <string>

#include "gproj/solver/internal/linearized_system.h"
#include "gproj/solver/internal/schur_complement.h"
#include "gproj/solver/sparse_cholesky.h"

namespace gproj {

struct SolverOptions;
struct SolverSummary;

class StepSolver {
 public:
  StepSolver(const SolverOptions& options, const VariableLayout& layout, LinearizedSystem* system);

  // Chooses elimination, analyses the pattern; fills the summary's elimination and analysis
  // fields. False (and `why`) on failure.
  bool Analyze(SolverSummary* summary, std::string* why);

  // Computes the right-hand side −A r of the current linearisation.
  void SetRhs();
  // Solves for the step d at this ε into *step. Adds the time of the Schur complement to
  // *schur_seconds, of the factorisation and the solve to the others. False (and `why`) when
  // the factorisation fails or the solve is inaccurate or not finite.
  bool Solve(double epsilon, Eigen::VectorXd* step, double* schur_seconds,
             double* factorization_seconds, double* solve_seconds, std::string* why);

  const Eigen::VectorXd& rhs() const { return rhs_; }
  int64_t FactorNonZeros() const { return cholesky_->FactorNonZeros(); }
  double FactorFlops() const { return cholesky_->FactorFlops(); }

 private:
  LinearizedSystem* system_;
  const VariableLayout& layout_;
  bool try_elimination_;
  bool block_ordering_;
  bool eliminate_ = false;
  std::unique_ptr<SparseCholesky> cholesky_;
  SchurComplement schur_;
  Eigen::VectorXd rhs_, check_, reduced_, step_kept_;
};

}  // namespace gproj
