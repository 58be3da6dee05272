#include "gproj/solver/internal/step_solver.h"

#include <chrono>
#include <cmath>
#include <vector>

#include "gproj/solver/guided_projection.h"

namespace gproj {
namespace {

using Clock = std::chrono::steady_clock;

double SecondsSince(Clock::time_point start) {
  return std::chrono::duration<double>(Clock::now() - start).count();
}

// Groups of consecutive variables (all of them, or the kept ones when `kept` is given) that
// belong to one item of the layout.
std::vector<int> ItemGroups(const VariableLayout& layout, const std::vector<int>* kept) {
  const int n = kept != nullptr ? static_cast<int>(kept->size()) : layout.num_variables();
  std::vector<int> begin;
  int item = 0, last_item = -1;
  for (int i = 0; i < n; ++i) {
    const int var = kept != nullptr ? (*kept)[i] : i;  // increasing
    while (layout.ItemOffset(item + 1) <= var) ++item;
    if (item != last_item) begin.push_back(i);
    last_item = item;
  }
  begin.push_back(n);
  return begin;
}

}  // namespace

StepSolver::StepSolver(const SolverOptions& options, const VariableLayout& layout,
                       LinearizedSystem* system)
    : system_(system),
      layout_(layout),
      try_elimination_(options.eliminate_auxiliaries),
      block_ordering_(options.block_ordering),
      cholesky_(
          CreateSparseCholesky(options.linear_solver, options.num_threads, options.ordering)) {}

bool StepSolver::Analyze(SolverSummary* summary, std::string* why) {
  const auto t = Clock::now();
  if (try_elimination_) {
    eliminate_ = schur_.Init(layout_, system_->a(), &summary->elimination_note);
    if (eliminate_) summary->eliminated_variables = schur_.num_eliminated();
  } else {
    summary->elimination_note = "disabled by options";
  }
  if (block_ordering_)
    cholesky_->SetGroups(ItemGroups(layout_, eliminate_ ? &schur_.kept_variables() : nullptr));
  const bool analysed = eliminate_ ? cholesky_->Analyze(schur_.s(), MatrixForm::kSymmetric, why)
                                   : cholesky_->Analyze(system_->a(), MatrixForm::kAAt, why);
  if (!analysed) return false;
  summary->analysis_seconds = SecondsSince(t);
  const int n = layout_.num_variables();
  rhs_.resize(n);
  check_.resize(n);
  reduced_.resize(eliminate_ ? schur_.num_kept() : n);
  step_kept_.resize(reduced_.size());
  return true;
}

void StepSolver::SetRhs() {
  system_->MultiplyAr(&rhs_);
  rhs_ = -rhs_;
}

bool StepSolver::Solve(double epsilon, Eigen::VectorXd* step, double* schur_seconds,
                       double* factorization_seconds, double* solve_seconds, std::string* why) {
  const double beta = epsilon * epsilon;
  auto t = Clock::now();
  if (eliminate_) {
    const bool formed = schur_.Form(system_->a(), beta, why);
    if (formed) schur_.ReduceRhs(system_->a(), rhs_, &reduced_);
    *schur_seconds += SecondsSince(t);
    if (!formed) return false;
  }
  t = Clock::now();
  const bool factored = eliminate_ ? cholesky_->Factorize(schur_.s(), beta, why)
                                   : cholesky_->Factorize(system_->a(), beta, why);
  *factorization_seconds += SecondsSince(t);
  if (!factored) return false;
  t = Clock::now();
  const bool solved = eliminate_ ? cholesky_->Solve(reduced_.data(), step_kept_.data(), why)
                                 : cholesky_->Solve(rhs_.data(), step->data(), why);
  if (solved && eliminate_) schur_.BackSubstitute(system_->a(), step_kept_, rhs_, step);
  *solve_seconds += SecondsSince(t);
  if (!solved) return false;
  // Check the solve: ‖(A Aᵀ + ε² I) d − rhs‖ small against the terms' sizes. Catches
  // factorisations that "succeed" on overflowing or non-finite values.
  system_->MultiplyNormal(*step, beta, &check_);
  const double scale = check_.norm() + rhs_.norm();
  const double residual = (check_ - rhs_).norm();
  if (!(residual <= 1e-6 * scale) || !std::isfinite(scale)) {
    *why = "the linear solve is inaccurate (residual " + std::to_string(residual) + " against " +
           std::to_string(scale) + ")";
    return false;
  }
  return true;
}

}  // namespace gproj
