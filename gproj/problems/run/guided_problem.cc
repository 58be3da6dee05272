#include "gproj/problems/run/guided_problem.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <stdexcept>
#include <string>

namespace gproj {
namespace {

using Clock = std::chrono::steady_clock;

// Fills the fields every run shares once the solver has stopped.
void Conclude(const GuidedProblem& problem, Clock::time_point start, bool aborted,
              RunReport* report) {
  report->failed = report->failed || !problem.problem().x().allFinite();
  if (!report->failed) {
    report->final = problem.Measure();
    FailOnNonFiniteMeasures(report);
  }
  // A run stopped by its callback is not converged, even at an iterate that meets the tolerance
  // (guided projection asks the callback before the tolerance; Ceres' stop reads USER_SUCCESS).
  report->converged = !report->failed && !aborted &&
                      (!problem.HasTolerance() || problem.MeetsTolerance(report->final));
  // The iterations asked ran out (the solver's NO_CONVERGENCE) and the run counts as converged:
  // the tolerance is judged at the end, or none was asked.
  const size_t ran_out = report->termination.find("NO_CONVERGENCE");
  if (report->converged && ran_out != std::string::npos &&
      (ran_out == 0 || report->termination[ran_out - 1] == ' ')) {
    // The solver's name ("ceres ") before its words is kept, after the status.
    const std::string solver = report->termination.substr(0, ran_out);
    report->termination =
        std::string(problem.HasTolerance()
                        ? "CONVERGENCE: the problem's tolerance is met at the end of the run"
                        : "COMPLETED: no tolerance was asked (the measures are minimised, not "
                          "driven to a target)") +
        (solver.empty() ? "" : " (" + solver + "iterations ran out)");
  }
  // A solver stop short of the problem's tolerance (a step too small, no lower energy) is a
  // stall, whatever the solver calls it.
  const size_t at = report->termination.find("CONVERGENCE");
  if (!report->converged && !report->failed && at != std::string::npos &&
      (at == 0 || report->termination[at - 1] == ' '))
    report->termination.replace(at, 11, "STALLED short of the tolerance");
  // The solver's own stall (a row above its residual tolerance) when the problem's tolerance,
  // which decides, is met.
  if (report->converged && report->termination.rfind("STALLED", 0) == 0)
    report->termination =
        "CONVERGENCE: the problem's tolerance was met (the solver: " + report->termination + ")";
  ConcludeStatus(report);  // the same status as through RunProblem, for C++ callers of Run
  report->seconds = SecondsSince(start);
}

}  // namespace

void FailOnNonFiniteMeasures(RunReport* report) {
  for (const NamedValue& v : report->final)
    if (!std::isfinite(v.value)) {
      report->failed = true;
      report->converged = false;
      report->termination = "FAILURE: the result's " + v.name + " is not finite";
      return;
    }
}

namespace {

constexpr const char* kStatusNames[] = {"CONVERGENCE", "DIRECT",     "COMPLETED", "NO_CONVERGENCE",
                                        "STALLED",     "USER_ABORT", "FAILURE"};

// The status word `text` starts with ("WORD:" or "WORD " at the start), if any.
const char* LeadingStatus(const std::string& text) {
  for (const char* name : kStatusNames) {
    const size_t n = std::char_traits<char>::length(name);
    if (text.compare(0, n, name) == 0 && (text.size() == n || text[n] == ':' || text[n] == ' '))
      return name;
  }
  return nullptr;
}

bool Contains(const std::string& text, const char* word) {
  return text.find(word) != std::string::npos;
}

}  // namespace

const char* RunStatusName(RunStatus status) { return kStatusNames[static_cast<int>(status)]; }

RunStatus StatusOf(const RunReport& report) {
  const char* lead = LeadingStatus(report.termination);
  for (int i = 0; lead != nullptr && i < 7; ++i)
    if (lead == kStatusNames[i]) return static_cast<RunStatus>(i);
  return RunStatus::kFailure;
}

void ConcludeStatus(RunReport* report) {
  std::string& t = report->termination;
  const char* lead = LeadingStatus(t);
  const std::string words = lead != nullptr ? lead : "";
  auto prefix = [&t](const std::string& status, const std::string& how) {
    t = status + ": " + how + (t.empty() ? "" : " (" + t + ")");
  };
  if (report->failed) {
    report->converged = false;
    if (words != "FAILURE") prefix("FAILURE", "numerical failure");
    return;
  }
  // A Ceres run stopped by the callback says USER_FAILURE (SOLVER_ABORT) or, unconverged,
  // USER_SUCCESS (SOLVER_TERMINATE_SUCCESSFULLY is how the tolerance check stops it).
  const bool aborted = words == "USER_ABORT" || Contains(t, "USER_ABORT") ||
                       Contains(t, "USER_FAILURE") ||
                       (!report->converged && Contains(t, "USER_SUCCESS"));
  if (aborted) {
    report->converged = false;
    if (words != "USER_ABORT") prefix("USER_ABORT", "stopped on request");
    return;
  }
  if (report->converged) {
    if (words == "CONVERGENCE" || words == "DIRECT" || words == "COMPLETED") return;
    if (!report->method.empty() && report->solver == SolverKind::kDirect)
      prefix("DIRECT", "constructed without iterating");
    else
      prefix("CONVERGENCE", "the problem's tolerance is met");
    return;
  }
  if (words == "NO_CONVERGENCE" || words == "STALLED") return;
  // Not converged: a solver that calls its stop convergence stopped short of the tolerance.
  const size_t at = t.find("CONVERGENCE");
  const bool solver_converged = at != std::string::npos && (at == 0 || t[at - 1] != '_');
  if (solver_converged)
    prefix("STALLED", "the solver stopped short of the problem's tolerance");
  else
    prefix("NO_CONVERGENCE", "the problem's tolerance is not met");
}

RunRecord ToRunRecord(const IterationRecord& r) {
  RunRecord record;
  record.iteration = r.iteration;
  record.energy = r.energy;
  record.step = r.step_norm;
  record.epsilon = r.epsilon;
  record.soft_scale = r.soft_scale;
  record.factorizations = r.factorizations;
  record.trials = r.trials;
  record.radius = r.radius;
  record.max_constraint = r.max_constraint;
  record.assembly_seconds = r.assembly_seconds;
  record.factorization_seconds = r.factorization_seconds;
  record.solve_seconds = r.solve_seconds;
  record.seconds = r.assembly_seconds + r.factorization_seconds + r.solve_seconds;
  record.families = r.families;
  return record;
}

RunRecord ToRunRecord(const CeresIterationRecord& s) {
  RunRecord record;
  record.iteration = s.iteration;
  record.energy = s.cost;
  record.step = s.step_norm;
  record.max_constraint = NAN;  // Ceres reports no per-row maximum
  record.seconds = s.iteration_time_in_seconds;
  return record;
}

const char* SolverKindName(SolverKind kind) {
  switch (kind) {
    case SolverKind::kGuidedProjection:
      return "gp";
    case SolverKind::kCeres:
      return "ceres";
    case SolverKind::kDirect:
      return "direct";
  }
  return "?";
}

SolverKind SolverKindFromName(const std::string& name) {
  for (SolverKind kind : {SolverKind::kGuidedProjection, SolverKind::kCeres, SolverKind::kDirect})
    if (name == SolverKindName(kind)) return kind;
  throw std::invalid_argument("unknown solver '" + name + "' (gp, ceres or direct)");
}

double SecondsSince(std::chrono::steady_clock::time_point start) {
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
}

double ValueOf(const NamedValues& values, const std::string& name) {
  for (const NamedValue& v : values)
    if (v.name == name) return v.value;
  return NAN;
}

double StartSoftScale(double start_residual, double floor) {
  constexpr double kNear = 1e-2;
  if (!(start_residual < kNear)) return 1.0;
  return std::max(start_residual / kNear, floor);
}

RunReport GuidedProblem::RunWithOptions(const SolverOptions& options, const RunCallback& callback) {
  const auto start = Clock::now();
  RunReport report;
  report.solver = SolverKind::kGuidedProjection;
  report.variables = problem().layout().num_variables();
  report.initial = Measure();
  if (!solver_ || solver_->problem() != &problem())
    solver_ = std::make_shared<GuidedProjectionSolver>(&problem());
  report.summary = solver_->Solve(options, [&](const IterationRecord& r, const Eigen::VectorXd& x) {
    RunRecord record = ToRunRecord(r);
    record.measures = MeasureAt(x);
    report.history.push_back(record);
    if (callback && !callback(record)) return CallbackResult::kAbort;
    return HasTolerance() && StopsAtTolerance() && MeetsTolerance(record.measures)
               ? CallbackResult::kConverged
               : CallbackResult::kContinue;
  });
  report.termination =
      std::string(TerminationTypeName(report.summary.termination)) + ": " + report.summary.message;
  report.iterations = report.summary.num_steps();
  report.failed = report.summary.termination == TerminationType::kFailure;
  Conclude(*this, start, report.summary.termination == TerminationType::kUserAbort, &report);
  return report;
}

RunReport GuidedProblem::RunCeres(int max_iterations, const RunCallback& callback) {
  const auto start = Clock::now();
  RunReport report;
  report.solver = SolverKind::kCeres;
  report.variables = problem().layout().num_variables();
  report.initial = Measure();
  bool aborted = false;
  const CeresSummary summary = SolveWithCeres(
      ceres_options(max_iterations), &problem(),
      [&](const CeresIterationRecord& s, const Eigen::VectorXd& x) {
        RunRecord record = ToRunRecord(s);
        record.measures = MeasureAt(x);
        report.history.push_back(record);
        if (callback && !callback(record)) return !(aborted = true);
        return !HasTolerance() || !StopsAtTolerance() || !MeetsTolerance(record.measures);
      });
  report.termination = "ceres " + summary.ceres_termination + ": " + summary.message;
  report.iterations = summary.num_steps();
  report.failed = summary.termination == TerminationType::kFailure;
  Conclude(*this, start, aborted, &report);
  return report;
}

RunReport GuidedProblem::RunWith(SolverKind solver, const RunCallback& callback, bool soft_free) {
  if (solver == SolverKind::kGuidedProjection) {
    SolverOptions options = solver_options();
    if (soft_free) options.initial_soft_scale = 0.0;
    return RunWithOptions(options, callback);
  }
  if (solver == SolverKind::kCeres) return RunCeres(solver_options().max_iterations, callback);
  throw std::invalid_argument("RunWith: a direct solve needs the problem's own (RunDirect)");
}

RunReport GuidedProblem::RunDirect(const std::string& method, const std::string& termination,
                                   const std::function<void()>& solve) {
  const auto start = Clock::now();
  RunReport report;
  report.solver = SolverKind::kDirect;
  report.method = method;
  report.termination = termination;
  report.variables = problem().layout().num_variables();
  report.initial = Measure();
  solve();
  Conclude(*this, start, /*aborted=*/false, &report);
  return report;
}

}  // namespace gproj
