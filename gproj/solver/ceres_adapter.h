#pragma once
// Cross-check path: turns any gproj Problem into a ceres::Problem whose residuals are
// √w_i φ_i(x), built from the same ConstraintFamily definitions (each element one residual
// block, each item one parameter block), and minimises ½ Σ w φ² + ½ ω_f² ‖P x‖² with
// Levenberg–Marquardt and SPARSE_NORMAL_CHOLESKY.

#include <Eigen/Core>
#include <functional>
#include <string>
#include <vector>

#include "gproj/solver/guided_projection.h"
#include "gproj/solver/problem.h"

namespace gproj {

struct CeresOptions {
  int max_iterations = 200;
  double function_tolerance = 1e-16;
  double gradient_tolerance = 1e-16;
  double parameter_tolerance = 1e-14;
  // ω_f as in SolverOptions; kSoft/kFairness weights are additionally multiplied by soft_scale.
  double fairness_weight = 0.1;
  double soft_scale = 1.0;
  int num_threads = 1;
  bool IsValid(std::string* why) const;
};

// Ceres' options for the same objective guided projection minimises with `solver`: its ω_f and
// threads, at most `max_iterations`, soft terms × `soft_scale`.
CeresOptions CeresOptionsFor(const SolverOptions& solver, int max_iterations,
                             double soft_scale = 1.0);

// One Ceres iteration (field names as in ceres::IterationSummary).
struct CeresIterationRecord {
  int iteration = 0;                       // 0: the start
  double cost = 0.0;                       // ½ Σ w φ² + ½ ω_f² ‖P x‖² at the iterate
  double step_norm = 0.0;                  // ‖Δx‖₂ of the step that led here
  double gradient_max_norm = 0.0;          // ‖∇‖∞ at the iterate
  bool step_is_successful = false;         // the trust region accepted the step
  double iteration_time_in_seconds = 0.0;  // of this iteration
  double cumulative_time_in_seconds = 0.0;
};

// What a Ceres run did, in gproj's terms (no Ceres type crosses this header).
struct CeresSummary {
  // kConvergence for Ceres' CONVERGENCE and USER_SUCCESS (the callback said stop: tolerance
  // met), kNoConvergence for NO_CONVERGENCE, kUserAbort for USER_FAILURE, kFailure otherwise.
  TerminationType termination = TerminationType::kFailure;
  std::string ceres_termination;  // Ceres' own name of it, e.g. "CONVERGENCE"
  std::string message;            // Ceres' message, or why the run did not start
  std::vector<CeresIterationRecord> iterations;
  double initial_cost = 0.0;
  double final_cost = 0.0;
  int num_parameters = 0;
  int num_residuals = 0;
  int num_residual_blocks = 0;
  double total_seconds = 0.0;
  bool usable = false;       // x holds a solution Ceres vouches for
  std::string brief_report;  // Ceres' BriefReport()
  std::string full_report;   // Ceres' FullReport()

  bool IsSolutionUsable() const { return usable; }
  // Steps taken (the last iteration's number).
  int num_steps() const { return iterations.empty() ? 0 : iterations.back().iteration; }
  const std::string& BriefReport() const { return brief_report; }
  const std::string& FullReport() const { return full_report; }
};

// Called after every Ceres iteration with its record and the current x (families' frozen
// coefficients have been updated at it). Return false to stop (counted as convergence: the
// caller's tolerance was met).
using CeresIterationCallback =
    std::function<bool(const CeresIterationRecord&, const Eigen::VectorXd& x)>;

// Solves in place on problem->x().
CeresSummary SolveWithCeres(const CeresOptions& options, Problem* problem,
                            const CeresIterationCallback& callback = nullptr);

}  // namespace gproj
