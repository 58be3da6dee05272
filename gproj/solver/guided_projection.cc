#include "gproj/solver/guided_projection.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <memory>
#include <sstream>

#include "gproj/solver/internal/linearized_system.h"
#include "gproj/solver/internal/step_solver.h"

namespace gproj {
namespace {

using Clock = std::chrono::steady_clock;

double SecondsSince(Clock::time_point start) {
  return std::chrono::duration<double>(Clock::now() - start).count();
}

void FillResiduals(const Problem& problem, const LinearizedSystem& system,
                   IterationRecord* record) {
  record->families.resize(problem.num_families());
  record->max_constraint = 0.0;
  for (int f = 0; f < problem.num_families(); ++f) {
    const int begin = system.family_row_begin(f);
    const int rows = problem.family(f).num_rows();
    FamilyResidual& out = record->families[f];
    out.name = problem.family(f).name();
    if (rows == 0) {
      out.max_abs = out.rms = 0.0;
      continue;
    }
    const auto phi = system.phi().segment(begin, rows);
    out.max_abs = phi.cwiseAbs().maxCoeff();
    out.rms = std::sqrt(phi.squaredNorm() / rows);
    if (problem.family(f).role() == FamilyRole::kConstraint)
      record->max_constraint = std::max(record->max_constraint, out.max_abs);
  }
}

}  // namespace

bool SolverOptions::IsValid(std::string* why) const {
  auto fail = [why](const std::string& text) {
    if (why != nullptr) *why = text;
    return false;
  };
  if (max_iterations < 0) return fail("max_iterations must be ≥ 0");
  if (!(residual_tolerance >= 0.0)) return fail("residual_tolerance must be ≥ 0");
  if (!(step_tolerance >= 0.0)) return fail("step_tolerance must be ≥ 0");
  if (!(fairness_weight >= 0.0) || !std::isfinite(fairness_weight))
    return fail("fairness_weight must be finite and ≥ 0");
  if (!(epsilon > 0.0) || !std::isfinite(epsilon)) return fail("epsilon must be finite and > 0");
  if (!(soft_weight_decay > 0.0 && soft_weight_decay <= 1.0))
    return fail("soft_weight_decay must be in (0, 1]");
  if (!(soft_weight_floor >= 0.0 && soft_weight_floor <= 1.0))
    return fail("soft_weight_floor must be in [0, 1]");
  if (!(epsilon_min >= 0.0) || !std::isfinite(epsilon_min))
    return fail("epsilon_min must be finite and >= 0");
  if (!(soft_weight_residual_factor >= 0.0) || !std::isfinite(soft_weight_residual_factor))
    return fail("soft_weight_residual_factor must be finite and >= 0");
  if (!(initial_soft_scale >= 0.0 && initial_soft_scale <= 1.0))
    return fail("initial_soft_scale must be in [0, 1]");
  if (!(epsilon_growth > 1.0) || !std::isfinite(epsilon_growth))
    return fail("epsilon_growth must be finite and > 1");
  if (max_retries < 0) return fail("max_retries must be ≥ 0");
  if (max_rejections < 0) return fail("max_rejections must be ≥ 0");
  if (num_threads < 0) return fail("num_threads must be ≥ 0");
  return true;
}

const char* TerminationTypeName(TerminationType type) {
  switch (type) {
    case TerminationType::kConvergence:
      return "CONVERGENCE";
    case TerminationType::kStalled:
      return "STALLED";
    case TerminationType::kNoConvergence:
      return "NO_CONVERGENCE";
    case TerminationType::kFailure:
      return "FAILURE";
    case TerminationType::kUserAbort:
      return "USER_ABORT";
  }
  return "UNKNOWN";
}

std::string SolverSummary::BriefReport() const {
  std::ostringstream out;
  const double final_residual = iterations.empty() ? 0.0 : iterations.back().max_constraint;
  out << "gproj guided projection: " << TerminationTypeName(termination) << ", " << num_steps()
      << " iterations, max constraint residual " << final_residual << ", " << total_seconds
      << " s (" << message << ")";
  return out.str();
}

std::string SolverSummary::FullReport() const {
  std::ostringstream out;
  out << "variables " << num_variables << ", rows " << num_rows << ", nnz(J) " << jacobian_nonzeros
      << ", nnz(L) " << factor_nonzeros << ", linear solver " << LinearSolverTypeName(linear_solver)
      << ", analysis " << analysis_seconds << " s\n";
  char line[256];
  std::snprintf(line, sizeof(line), "%5s %13s %11s %11s %9s %9s %9s %9s\n", "iter", "energy",
                "max_constr", "step", "epsilon", "assembly", "factor", "solve");
  out << line;
  for (const IterationRecord& r : iterations) {
    std::snprintf(line, sizeof(line), "%5d %13.6e %11.3e %11.3e %9.1e %9.4f %9.4f %9.4f\n",
                  r.iteration, r.energy, r.max_constraint, r.step_norm, r.epsilon,
                  r.assembly_seconds, r.factorization_seconds, r.solve_seconds);
    out << line;
  }
  if (!iterations.empty()) {
    for (const FamilyResidual& f : iterations.back().families)
      out << "  " << f.name << ": max " << f.max_abs << ", rms " << f.rms << "\n";
  }
  out << BriefReport() << "\n";
  return out.str();
}

namespace {

// Guided projection as a minimizer (like Ceres' trust-region minimizer): evaluate the iterate,
// stop or step; a step solves the linearisation at ε, retries with a larger ε when the linear
// algebra fails, and with monotone steps damps ε until the energy falls (Nielsen's rule).
class Minimizer {
 public:
  Minimizer(const SolverOptions& options, Problem* problem, const IterationCallback& callback)
      : options_(options), problem_(problem), callback_(callback), x_(problem->x()) {}

  SolverSummary Run() {
    summary_.linear_solver = options_.linear_solver;
    summary_.num_variables = problem_->layout().num_variables();
    if (!Start()) return summary_;
    for (int k = 0;; ++k)
      if (EvaluateIterate(k) || !TakeStep()) return summary_;
  }

 private:
  // Ends the run with this outcome; returns false so callers can `return Finish(…)`.
  // A stop at a stationary point: converged when no residual tolerance is asked, else a stall
  // short of it (the rows' maximum named).
  bool Stop(const std::string& why) {
    if (options_.residual_tolerance <= 0.0) return Finish(TerminationType::kConvergence, why);
    char residual[96];
    std::snprintf(residual, sizeof(residual),
                  " with the max constraint residual %.3e above the residual tolerance %.1e",
                  record_.max_constraint, options_.residual_tolerance);
    return Finish(TerminationType::kStalled, why + residual);
  }

  bool Finish(TerminationType type, const std::string& message) {
    summary_.termination = type;
    if (type == TerminationType::kFailure) summary_.usable = false;
    summary_.message = message;
    summary_.total_seconds = SecondsSince(start_);
    return false;
  }

  void ProjectOwnedUnknowns(Eigen::VectorXd* x) const {
    for (int f = 0; f < problem_->num_families(); ++f)
      problem_->family(f).Project(problem_->layout(), x);
  }

  // Checks the options and the start, builds the system, analyses its pattern.
  bool Start() {
    if (!options_.IsValid(&why_))
      return Finish(TerminationType::kFailure, "invalid options: " + why_);
    if (x_.size() != summary_.num_variables)
      return Finish(TerminationType::kFailure, "x does not match the variable layout");
    if (!x_.allFinite()) return Finish(TerminationType::kFailure, "the start x is not finite");
    summary_.usable = true;
    ProjectOwnedUnknowns(&x_);
    system_ = std::make_unique<LinearizedSystem>(problem_);
    summary_.num_rows = system_->num_rows();
    summary_.jacobian_nonzeros = system_->a().nnz();
    steps_ = std::make_unique<StepSolver>(options_, problem_->layout(), system_.get());
    if (!steps_->Analyze(&summary_, &why_)) return Finish(TerminationType::kFailure, why_);
    step_.resize(summary_.num_variables);
    trial_.resize(summary_.num_variables);
    const VariableLayout& layout = problem_->layout();
    for (int item = 0; item < layout.num_items(); ++item)
      if (problem_->IsConstant(item))
        for (int c = 0; c < layout.ItemDim(item); ++c) held_.push_back(layout.ItemOffset(item) + c);
    soft_scale_ = options_.initial_soft_scale;
    damping_ = options_.epsilon;
    for (int f = 0; f < problem_->num_families(); ++f)
      if (problem_->family(f).role() == FamilyRole::kConstraint &&
          problem_->family(f).num_elements() > 0)
        has_constraint_rows_ = true;
    return true;
  }

  // Assembles at x^k and records it; true when the run ends here (tolerance, callback,
  // iteration limit or failure).
  bool EvaluateIterate(int k) {
    record_.iteration = k;
    record_.soft_scale = soft_scale_;
    const auto t = Clock::now();
    if (!system_->Assemble(x_, options_.fairness_weight, soft_scale_, &why_))
      return !Finish(TerminationType::kFailure, why_);
    record_.energy = system_->Energy();
    FillResiduals(*problem_, *system_, &record_);
    // The step's Schur complement counts as assembly of the iterate it led to.
    record_.assembly_seconds = SecondsSince(t) + schur_seconds_;
    schur_seconds_ = 0.0;
    summary_.iterations.push_back(record_);

    const CallbackResult cb = callback_ ? callback_(record_, x_) : CallbackResult::kContinue;
    if (cb == CallbackResult::kAbort)
      return !Finish(TerminationType::kUserAbort, "stopped by callback");
    if (cb == CallbackResult::kConverged)
      return !Finish(TerminationType::kConvergence, "the problem's tolerance was met");
    if (options_.residual_tolerance > 0.0 && record_.max_constraint <= options_.residual_tolerance)
      return !Finish(TerminationType::kConvergence, "residual tolerance met");
    if (k > 0 && options_.step_tolerance > 0.0 && record_.step_norm <= options_.step_tolerance)
      return !Stop("step tolerance met");
    if (k == options_.max_iterations)
      return !Finish(TerminationType::kNoConvergence, "maximum number of iterations reached");
    // The targets move after a step (Bregman: the first solve has none), and the step's
    // energy is that of the shifted rows.
    if (options_.shifted_constraints && k > 0) system_->ShiftConstraintTargets();
    step_energy_ = system_->Energy();
    return false;
  }

  // Solves for the step at ε and forms the trial point; false (with why_) if unusable.
  bool SolveTrial(double epsilon) {
    if (!steps_->Solve(epsilon, &step_, &schur_seconds_, &record_.factorization_seconds,
                       &record_.solve_seconds, &why_))
      return false;
    for (int i : held_) step_[i] = 0.0;
    trial_ = x_ + step_;
    ProjectOwnedUnknowns(&trial_);
    if (options_.project_trial) options_.project_trial(&trial_);
    if (!trial_.allFinite()) {
      why_ = "the step is not finite";
      return false;
    }
    return true;
  }

  // With monotone steps: whether the trial lowers the energy. Updates the damping on success;
  // on failure the system is assembled at x^k again (same linearisation for the next solve).
  // Sets *failed when that re-assembly fails.
  bool Accepts(double energy, double epsilon, bool* failed) {
    const auto t = Clock::now();
    const bool assembled = system_->Assemble(trial_, options_.fairness_weight, soft_scale_, &why_);
    const double trial_energy = assembled ? system_->Energy() : HUGE_VAL;
    if (trial_energy > energy &&
        !system_->Assemble(x_, options_.fairness_weight, soft_scale_, &why_))
      *failed = true;
    schur_seconds_ += SecondsSince(t);
    if (trial_energy > energy) return false;
    // Gain ratio against the linear model's reduction: with (A Aᵀ + ε² I) d = rhs it is
    // ½ dᵀ rhs + ½ ε² ‖d‖². With project_trial the actual reduction includes what the
    // projection gained, so the ratio is larger and ε falls faster: intended, the projected
    // point is the one kept.
    const double predicted =
        0.5 * (step_.dot(steps_->rhs()) + epsilon * epsilon * step_.squaredNorm());
    const double gain = predicted > 0.0 ? (energy - trial_energy) / predicted : -1.0;
    // Nielsen's update of the damping ε² from the gain ratio.
    const double factor = std::max(1.0 / 3.0, 1.0 - std::pow(2.0 * std::max(gain, 0.0) - 1.0, 3));
    damping_ = epsilon * std::sqrt(factor);
    growth_ = 2.0;
    return true;
  }

  // The smallest ε of a step from x^k with constraint residual r_k: options_.epsilon, or with
  // epsilon_min > 0 the residual itself clamped to [epsilon_min, epsilon].
  double EpsilonFloor(double residual) const {
    if (!(options_.epsilon_min > 0.0)) return options_.epsilon;
    return std::clamp(residual, std::min(options_.epsilon_min, options_.epsilon), options_.epsilon);
  }

  // Moves x to the next iterate; false when the run ends (failure, or no lower energy).
  bool TakeStep() {
    steps_->SetRhs();
    const double energy = step_energy_;
    const double residual_at_start = record_.max_constraint;
    const double floor = EpsilonFloor(residual_at_start);
    double epsilon = options_.monotone ? std::max(floor, damping_) : floor;
    record_ = IterationRecord();
    growth_ = 2.0;
    int failures = 0, rejections = 0;
    for (;;) {
      if (!SolveTrial(epsilon)) {
        if (++failures > options_.max_retries) {
          char last[32];
          std::snprintf(last, sizeof(last), "%g", epsilon);
          return Finish(TerminationType::kFailure, why_ + " (after " +
                                                       std::to_string(options_.max_retries) +
                                                       " increases of epsilon to " + last + ")");
        }
        epsilon *= options_.epsilon_growth;
        continue;
      }
      const bool admissible = !options_.admissible_trial || options_.admissible_trial(trial_);
      if (admissible && !options_.monotone) break;
      bool failed = false;
      if (admissible && Accepts(energy, epsilon, &failed)) break;
      if (failed) return Finish(TerminationType::kFailure, why_);
      if (++rejections > options_.max_rejections)
        return Stop(std::string(admissible ? "no step lowers the energy"
                                           : "no admissible step (the last trial was refused)") +
                    " (epsilon raised to " + std::to_string(epsilon) + ")");
      epsilon *= std::sqrt(growth_);
      growth_ *= 2.0;
    }
    record_.retries = failures + rejections;
    summary_.factor_nonzeros = steps_->FactorNonZeros();
    summary_.factor_flops = steps_->FactorFlops();
    record_.epsilon = epsilon;
    record_.step_norm = (trial_ - x_).lpNorm<Eigen::Infinity>();
    x_.swap(trial_);
    double decay = options_.soft_weight_decay;
    if (options_.soft_weight_residual_factor > 0.0 && decay < 1.0 && has_constraint_rows_)
      decay = std::min(decay, options_.soft_weight_residual_factor * residual_at_start);
    soft_scale_ = std::max(soft_scale_ * decay, options_.soft_weight_floor);
    return true;
  }

  const SolverOptions& options_;
  Problem* problem_;
  const IterationCallback& callback_;
  Eigen::VectorXd& x_;
  const Clock::time_point start_ = Clock::now();
  SolverSummary summary_;
  std::unique_ptr<LinearizedSystem> system_;
  std::unique_ptr<StepSolver> steps_;
  Eigen::VectorXd step_, trial_;
  std::vector<int> held_;  // indices of x in constant items
  IterationRecord record_;
  std::string why_;
  double soft_scale_ = 1.0;
  double damping_ = 0.0;              // ε of the next step when options_.monotone
  bool has_constraint_rows_ = false;  // the residual-tied schedule needs some
  double growth_ = 2.0;               // growth of ε² on the next rejection
  double schur_seconds_ = 0.0;
  double step_energy_ = 0.0;  // energy at x^k that a monotone step must lower
};

}  // namespace

SolverSummary Solve(const SolverOptions& options, Problem* problem,
                    const IterationCallback& callback) {
  return Minimizer(options, problem, callback).Run();
}

double EvaluateObjective(Problem* problem, double fairness_weight, const Eigen::VectorXd& x) {
  LinearizedSystem system(problem);
  std::string why;
  if (!system.Assemble(x, fairness_weight, 1.0, &why)) return NAN;
  return system.Energy();
}

}  // namespace gproj
