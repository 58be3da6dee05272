#pragma once
// Cross-check path: turns any gproj Problem into a ceres::Problem whose residuals are
// √w_i φ_i(x), built from the same ConstraintFamily definitions (each element one residual
// block, each item one parameter block), and minimises ½ Σ w φ² + ½ ω_f² ‖P x‖² with
// Levenberg–Marquardt and SPARSE_NORMAL_CHOLESKY.

#include <ceres/ceres.h>

#include <functional>
#include <string>

#include "solver/problem.h"

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

// Called after every Ceres iteration with its summary and the current x (families' frozen
// coefficients have been updated at it). Return false to stop.
using CeresIterationCallback =
    std::function<bool(const ceres::IterationSummary&, const Eigen::VectorXd& x)>;

// Solves in place on problem->x(). The returned summary is Ceres' own.
ceres::Solver::Summary SolveWithCeres(const CeresOptions& options, Problem* problem,
                                      const CeresIterationCallback& callback = nullptr);

}  // namespace gproj
