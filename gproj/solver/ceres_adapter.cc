#include "gproj/solver/ceres_adapter.h"

#include <ceres/ceres.h>

#include <algorithm>
#include <cmath>
#include <memory>
#include <vector>

namespace gproj {
namespace {

// One element of a family as a Ceres residual block: residuals √w φ, Jacobians √w ∇φ.
class ElementCost : public ceres::CostFunction {
 public:
  ElementCost(const ConstraintFamily* family, int element, const std::vector<int>& dims,
              double sqrt_weight)
      : family_(family), element_(element), dims_(dims), sqrt_weight_(sqrt_weight) {
    set_num_residuals(family->rows_per_element());
    for (int d : dims) mutable_parameter_block_sizes()->push_back(d);
    local_dim_ = 0;
    for (int d : dims) local_dim_ += d;
  }

  bool Evaluate(double const* const* parameters, double* residuals,
                double** jacobians) const override {
    const int rows = num_residuals();
    // Per-thread buffers that only grow: Ceres calls this for every element in every iteration.
    thread_local std::vector<double> x_local, jac;
    if (x_local.size() < static_cast<size_t>(local_dim_)) x_local.resize(local_dim_);
    if (jac.size() < static_cast<size_t>(rows * local_dim_)) jac.resize(rows * local_dim_);
    for (size_t b = 0, l = 0; b < dims_.size(); ++b)
      for (int c = 0; c < dims_[b]; ++c) x_local[l++] = parameters[b][c];
    family_->EvaluateElement(element_, x_local.data(), residuals, jac.data());
    for (int r = 0; r < rows; ++r) {
      residuals[r] *= sqrt_weight_;
      if (!std::isfinite(residuals[r])) return false;
    }
    if (jacobians == nullptr) return true;
    for (size_t b = 0, first = 0; b < dims_.size(); first += dims_[b], ++b) {
      if (jacobians[b] == nullptr) continue;
      for (int r = 0; r < rows; ++r)
        for (int c = 0; c < dims_[b]; ++c)
          jacobians[b][r * dims_[b] + c] = sqrt_weight_ * jac[r * local_dim_ + first + c];
    }
    return true;
  }

 private:
  const ConstraintFamily* family_;
  int element_;
  std::vector<int> dims_;
  double sqrt_weight_;
  int local_dim_;
};

class UpdateCallback : public ceres::IterationCallback {
 public:
  UpdateCallback(Problem* problem, const CeresIterationCallback& user)
      : problem_(problem), user_(user) {}
  ceres::CallbackReturnType operator()(const ceres::IterationSummary& summary) override {
    for (int f = 0; f < problem_->num_families(); ++f)
      problem_->family(f).Update(problem_->layout(), problem_->x());
    if (user_ && !user_(Record(summary), problem_->x()))
      return ceres::SOLVER_TERMINATE_SUCCESSFULLY;
    return ceres::SOLVER_CONTINUE;
  }

  static CeresIterationRecord Record(const ceres::IterationSummary& s) {
    CeresIterationRecord r;
    r.iteration = s.iteration;
    r.cost = s.cost;
    r.step_norm = s.step_norm;
    r.gradient_max_norm = s.gradient_max_norm;
    r.step_is_successful = s.step_is_successful;
    r.iteration_time_in_seconds = s.iteration_time_in_seconds;
    r.cumulative_time_in_seconds = s.cumulative_time_in_seconds;
    return r;
  }

 private:
  Problem* problem_;
  const CeresIterationCallback& user_;
};

TerminationType FromCeres(ceres::TerminationType type) {
  switch (type) {
    case ceres::CONVERGENCE:
    case ceres::USER_SUCCESS:
      return TerminationType::kConvergence;
    case ceres::NO_CONVERGENCE:
      return TerminationType::kNoConvergence;
    case ceres::USER_FAILURE:
      return TerminationType::kUserAbort;
    case ceres::FAILURE:
      return TerminationType::kFailure;
  }
  return TerminationType::kFailure;
}

CeresSummary FromCeres(const ceres::Solver::Summary& s) {
  CeresSummary out;
  out.termination = FromCeres(s.termination_type);
  out.ceres_termination = ceres::TerminationTypeToString(s.termination_type);
  out.message = s.message;
  for (const ceres::IterationSummary& it : s.iterations)
    out.iterations.push_back(UpdateCallback::Record(it));
  out.initial_cost = s.initial_cost;
  out.final_cost = s.final_cost;
  out.num_parameters = s.num_parameters;
  out.num_residuals = s.num_residuals;
  out.num_residual_blocks = s.num_residual_blocks;
  out.total_seconds = s.total_time_in_seconds;
  out.usable = s.IsSolutionUsable();
  out.brief_report = s.BriefReport();
  out.full_report = s.FullReport();
  return out;
}

}  // namespace

CeresOptions CeresOptionsFor(const SolverOptions& solver, int max_iterations, double soft_scale) {
  CeresOptions options;
  options.max_iterations = max_iterations;
  options.fairness_weight = solver.fairness_weight;
  options.soft_scale = soft_scale;
  options.num_threads = std::max(1, solver.num_threads);
  return options;
}

bool CeresOptions::IsValid(std::string* why) const {
  if (max_iterations < 0) {
    *why = "max_iterations must be ≥ 0";
    return false;
  }
  if (!(fairness_weight >= 0.0) || !(soft_scale >= 0.0) || num_threads < 1) {
    *why = "fairness_weight and soft_scale must be ≥ 0, num_threads ≥ 1";
    return false;
  }
  return true;
}

CeresSummary SolveWithCeres(const CeresOptions& options, Problem* problem,
                            const CeresIterationCallback& callback) {
  ceres::Solver::Summary summary;
  std::string why;
  if (!options.IsValid(&why)) {
    CeresSummary out;
    out.message = "invalid options: " + why;
    out.ceres_termination = "FAILURE";
    return out;
  }
  const VariableLayout& layout = problem->layout();
  Eigen::VectorXd& x = problem->x();
  for (int f = 0; f < problem->num_families(); ++f) {
    problem->family(f).Prepare();
    problem->family(f).Update(layout, x);
  }

  ceres::Problem ceres_problem;
  std::vector<int> dims;
  std::vector<double*> blocks;
  for (int f = 0; f < problem->num_families(); ++f) {
    const ConstraintFamily& fam = problem->family(f);
    const double w =
        RowWeight(fam.role(), fam.weight(), options.fairness_weight, options.soft_scale);
    if (w == 0.0) continue;
    for (int e = 0; e < fam.num_elements(); ++e) {
      dims.clear();
      blocks.clear();
      const int* items = fam.element_items(e);
      for (int k = 0; k < fam.element_num_items(e); ++k) {
        dims.push_back(layout.ItemDim(items[k]));
        blocks.push_back(x.data() + layout.ItemOffset(items[k]));
      }
      ceres_problem.AddResidualBlock(new ElementCost(&fam, e, dims, std::sqrt(w)), nullptr, blocks);
    }
  }

  for (int item = 0; item < layout.num_items(); ++item) {
    double* block = x.data() + layout.ItemOffset(item);
    if (problem->IsConstant(item) && ceres_problem.HasParameterBlock(block))
      ceres_problem.SetParameterBlockConstant(block);
  }

  ceres::Solver::Options solver_options;
  solver_options.minimizer_type = ceres::TRUST_REGION;
  solver_options.trust_region_strategy_type = ceres::LEVENBERG_MARQUARDT;
  solver_options.linear_solver_type = ceres::SPARSE_NORMAL_CHOLESKY;
  solver_options.sparse_linear_algebra_library_type = ceres::SUITE_SPARSE;
  solver_options.max_num_iterations = options.max_iterations;
  solver_options.function_tolerance = options.function_tolerance;
  solver_options.gradient_tolerance = options.gradient_tolerance;
  solver_options.parameter_tolerance = options.parameter_tolerance;
  solver_options.num_threads = options.num_threads;
  solver_options.logging_type = ceres::SILENT;
  solver_options.update_state_every_iteration = true;
  UpdateCallback update(problem, callback);
  solver_options.callbacks.push_back(&update);
  ceres::Solve(solver_options, &ceres_problem, &summary);
  return FromCeres(summary);
}

}  // namespace gproj
