#include "solver/guided_projection.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <sstream>

#include "solver/linearized_system.h"
#include "solver/schur_complement.h"

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

SolverSummary Solve(const SolverOptions& options, Problem* problem,
                    const IterationCallback& callback) {
  const auto start = Clock::now();
  SolverSummary summary;
  summary.linear_solver = options.linear_solver;
  summary.num_variables = problem->layout().num_variables();
  auto finish = [&](TerminationType type, const std::string& message) {
    summary.termination = type;
    summary.message = message;
    summary.total_seconds = SecondsSince(start);
    return summary;
  };
  std::string why;
  if (!options.IsValid(&why)) return finish(TerminationType::kFailure, "invalid options: " + why);
  Eigen::VectorXd& x = problem->x();
  if (x.size() != summary.num_variables)
    return finish(TerminationType::kFailure, "x does not match the variable layout");
  if (!x.allFinite()) return finish(TerminationType::kFailure, "the start x is not finite");
  summary.usable = true;

  LinearizedSystem system(problem);
  summary.num_rows = system.num_rows();
  summary.jacobian_nonzeros = system.a().nnz();
  auto cholesky = CreateSparseCholesky(options.linear_solver, options.num_threads);
  auto t = Clock::now();
  SchurComplement schur;
  bool eliminate = false;
  if (options.eliminate_auxiliaries) {
    eliminate = schur.Init(problem->layout(), system.a(), &summary.elimination_note);
    if (eliminate) summary.eliminated_variables = schur.num_eliminated();
  } else {
    summary.elimination_note = "disabled by options";
  }
  const bool analysed = eliminate ? cholesky->Analyze(schur.s(), MatrixForm::kSymmetric, &why)
                                  : cholesky->Analyze(system.a(), MatrixForm::kAAt, &why);
  if (!analysed) return finish(TerminationType::kFailure, why);
  summary.analysis_seconds = SecondsSince(t);

  const int n = summary.num_variables;
  const int n_kept = eliminate ? schur.num_kept() : n;
  Eigen::VectorXd rhs(n), step(n), trial(n), check(n), reduced(n_kept), step_kept(n_kept);
  IterationRecord record;
  double soft_scale = options.initial_soft_scale;
  double damping = options.epsilon;  // ε of the next step when options.monotone
  double growth = 2.0;               // growth of ε² on the next rejection
  double schur_seconds = 0.0;
  for (int k = 0;; ++k) {
    record.iteration = k;
    record.soft_scale = soft_scale;
    t = Clock::now();
    if (!system.Assemble(x, options.fairness_weight, soft_scale, &why))
      return finish(TerminationType::kFailure, why);
    record.energy = system.Energy();
    FillResiduals(*problem, system, &record);
    // The step's Schur complement counts as assembly of the iterate it led to.
    record.assembly_seconds = SecondsSince(t) + schur_seconds;
    schur_seconds = 0.0;
    summary.iterations.push_back(record);

    CallbackResult cb = callback ? callback(record, x) : CallbackResult::kContinue;
    if (cb == CallbackResult::kAbort)
      return finish(TerminationType::kUserAbort, "stopped by callback");
    if (cb == CallbackResult::kConverged)
      return finish(TerminationType::kConvergence, "the callback's tolerance was met");
    if (options.residual_tolerance > 0.0 && record.max_constraint <= options.residual_tolerance)
      return finish(TerminationType::kConvergence, "residual tolerance met");
    if (k > 0 && options.step_tolerance > 0.0 && record.step_norm <= options.step_tolerance)
      return finish(TerminationType::kConvergence, "step tolerance met");
    if (k == options.max_iterations)
      return finish(TerminationType::kNoConvergence, "maximum number of iterations reached");

    // Step: (A Aᵀ + ε² I) d = −A r.
    system.MultiplyAr(&rhs);
    rhs = -rhs;
    const double energy = record.energy;
    double epsilon = options.monotone ? damping : options.epsilon;
    record = IterationRecord();
    // Solves for the step at this ε into `trial`; false (with `why`) if it is unusable.
    auto solve_step = [&]() {
      const double beta = epsilon * epsilon;
      if (eliminate) {
        t = Clock::now();
        const bool formed = schur.Form(system.a(), beta, &why);
        if (formed) schur.ReduceRhs(rhs, &reduced);
        schur_seconds += SecondsSince(t);
        if (!formed) return false;
      }
      t = Clock::now();
      const bool factored = eliminate ? cholesky->Factorize(schur.s(), beta, &why)
                                      : cholesky->Factorize(system.a(), beta, &why);
      record.factorization_seconds += SecondsSince(t);
      if (!factored) return false;
      t = Clock::now();
      const bool solved = eliminate ? cholesky->Solve(reduced.data(), step_kept.data(), &why)
                                    : cholesky->Solve(rhs.data(), step.data(), &why);
      if (solved && eliminate) schur.BackSubstitute(step_kept, rhs, &step);
      record.solve_seconds += SecondsSince(t);
      if (!solved) return false;
      // Check the solve: ‖(A Aᵀ + ε² I) d − rhs‖ small against the terms' sizes. Catches
      // factorisations that "succeed" on overflowing or non-finite values.
      system.MultiplyNormal(step, beta, &check);
      const double scale = check.norm() + rhs.norm();
      const double residual = (check - rhs).norm();
      if (!(residual <= 1e-6 * scale) || !std::isfinite(scale)) {
        why = "the linear solve is inaccurate (residual " + std::to_string(residual) + " against " +
              std::to_string(scale) + ")";
        return false;
      }
      trial = x + step;
      if (options.project_trial) options.project_trial(&trial);
      if (!trial.allFinite()) {
        why = "the step is not finite";
        return false;
      }
      return true;
    };
    int failures = 0, rejections = 0;
    for (;;) {
      if (!solve_step()) {
        if (++failures > options.max_retries)
          return finish(TerminationType::kFailure,
                        why + " (after " + std::to_string(options.max_retries) +
                            " increases of epsilon to " + std::to_string(epsilon) + ")");
        epsilon *= options.epsilon_growth;
        continue;
      }
      if (!options.monotone) break;
      // Merit test at the trial point; on rejection the system (and the families' state) is
      // assembled at x^k again, so the next solve uses the same linearisation.
      t = Clock::now();
      const bool assembled = system.Assemble(trial, options.fairness_weight, soft_scale, &why);
      const double trial_energy = assembled ? system.Energy() : HUGE_VAL;
      if (trial_energy > energy && !system.Assemble(x, options.fairness_weight, soft_scale, &why))
        return finish(TerminationType::kFailure, why);
      schur_seconds += SecondsSince(t);
      // Gain ratio against the linear model's reduction: with (A Aᵀ + ε² I) d = rhs it is
      // ½ dᵀ rhs + ½ ε² ‖d‖². With project_trial the actual reduction includes what the
      // projection gained, so the ratio is larger and ε falls faster: intended, the projected
      // point is the one kept.
      const double predicted = 0.5 * (step.dot(rhs) + epsilon * epsilon * step.squaredNorm());
      const double gain = predicted > 0.0 ? (energy - trial_energy) / predicted : -1.0;
      if (trial_energy <= energy) {
        // Nielsen's update of the damping ε² from the gain ratio.
        const double factor =
            std::max(1.0 / 3.0, 1.0 - std::pow(2.0 * std::max(gain, 0.0) - 1.0, 3));
        damping = std::max(options.epsilon, epsilon * std::sqrt(factor));
        growth = 2.0;
        break;
      }
      if (++rejections > options.max_rejections)
        return finish(
            TerminationType::kConvergence,
            "no step lowers the energy (epsilon raised to " + std::to_string(epsilon) + ")");
      epsilon *= std::sqrt(growth);
      growth *= 2.0;
    }
    record.retries = failures + rejections;
    summary.factor_nonzeros = cholesky->FactorNonZeros();
    record.epsilon = epsilon;
    record.step_norm = (trial - x).lpNorm<Eigen::Infinity>();
    x.swap(trial);
    soft_scale = std::max(soft_scale * options.soft_weight_decay, options.soft_weight_floor);
  }
}

double EvaluateObjective(Problem* problem, double fairness_weight, const Eigen::VectorXd& x) {
  LinearizedSystem system(problem);
  std::string why;
  if (!system.Assemble(x, fairness_weight, 1.0, &why)) return NAN;
  return system.Energy();
}

}  // namespace gproj
