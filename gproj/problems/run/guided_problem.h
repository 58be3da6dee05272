#pragma once
// The shape every gproj problem has: Options that embed SolverOptions, a build step (the
// problem's constructor), named measures of an iterate, a tolerance on them, a run by guided
// projection with an iteration callback, and the Ceres cross-check from the same rows. Run and
// RunCeres return one report whose keys are the same for every problem, so the command line
// (and any other front end) logs, writes and maps exit codes in one place.

#include <Eigen/Core>
#include <chrono>
#include <functional>
#include <memory>
#include <string>
#include <utility>
#include <vector>

#include "gproj/common/run_stopped.h"
#include "gproj/solver/ceres_adapter.h"
#include "gproj/solver/guided_projection.h"
#include "gproj/solver/problem.h"

namespace gproj {

// The solver of a run: the report's "solver", and the values of the option "solver" where a
// problem offers a choice.
enum class SolverKind {
  kGuidedProjection,  // "gp": guided projection, gproj's own solver
  kCeres,             // "ceres": Ceres on the same definitions (Levenberg-Marquardt on the rows,
                      // or BFGS on a smooth energy; the report's "method" then says "BFGS")
  kDirect,            // "direct": no iteration on the constraints: a construction, one linear
                      // system or a propagation (the report's "method" says which)
};
// "gp", "ceres", "direct"
const char* SolverKindName(SolverKind kind);
// The kind named `name`; throws std::invalid_argument for any other name.
SolverKind SolverKindFromName(const std::string& name);

// A measure of an iterate: an identifier (a JSON key, a log column) and its value.
struct NamedValue {
  std::string name;
  double value = 0.0;
};
using NamedValues = std::vector<NamedValue>;
// The value named `name`; NaN when there is none.
double ValueOf(const NamedValues& values, const std::string& name);
// Seconds of wall time since `start` (the run's timer).
double SecondsSince(std::chrono::steady_clock::time_point start);

// One iterate of a run, the same for both solvers (fields a solver does not have stay 0).
struct RunRecord {
  int iteration = 0;
  double energy = 0.0;  // ½ Σ w φ² (+ fairness) with the iteration's weights
  double step = 0.0;  // ‖x^k − x^{k−1}‖ (∞-norm for guided projection, 2-norm for Ceres)
  double epsilon = 0.0;
  double soft_scale = 1.0;
  int factorizations = 0;       // numeric factorisations of the step that led here (Ceres: 0)
  int trials = 0;               // trial points assessed for it
  double radius = 0.0;          // dogleg trust radius after it (∞: unbounded; 0: no trust region)
  double max_constraint = 0.0;  // max |φ| over constraint rows (guided projection; NaN for Ceres)
  double seconds = 0.0;         // time of the step that led here
  NamedValues measures;         // the problem's measures at the iterate
  std::vector<FamilyResidual> families;  // per named term: max and RMS |φ| (guided projection)
  double assembly_seconds = 0.0, factorization_seconds = 0.0, solve_seconds = 0.0;
};

// The solvers' own records as RunRecords (measures left empty).
RunRecord ToRunRecord(const IterationRecord& record);
RunRecord ToRunRecord(const CeresIterationRecord& record);

// What a run did: the report every command writes (see docs/command-line.md, "Report JSON").
struct RunReport {
  SolverKind solver = SolverKind::kGuidedProjection;
  std::string method;       // a construction's method (ConstructionMethodName); empty otherwise
  bool converged = false;   // the problem's tolerance is met by the final iterate
  bool failed = false;      // numerical failure: the final iterate must not be used
  std::string termination;  // how the solver stopped, e.g. "CONVERGENCE: step tolerance met"
  int iterations = 0;
  double seconds = 0.0;
  int variables = 0;
  NamedValues initial, final;
  std::vector<RunRecord> history;
  SolverSummary summary;  // guided projection's own summary (empty for Ceres)
};

// Marks `report` failed ("FAILURE: the result's <name> is not finite") when a value of
// report->final is not finite: finite unknowns can still give measures that overflow
// (coordinates near 1e308), and such a result must not be written.
void FailOnNonFiniteMeasures(RunReport* report);

// How a run ended, one of a fixed set that every run's termination starts with ("STATUS: how"):
//   CONVERGENCE     the problem's tolerance is met (iterations)
//   DIRECT          constructed without iterating, and its tolerance is met
//   COMPLETED       the iterations asked ran; no tolerance was asked
//   NO_CONVERGENCE  the tolerance is not met (the iterations or rounds ran out)
//   STALLED         the solver stopped short of the tolerance (no step lowers the energy)
//   USER_ABORT      stopped by the callback or Ctrl-C
//   FAILURE         numerical failure: the result must not be used
// converged is true exactly for the first three.
enum class RunStatus {
  kConvergence,
  kDirect,
  kCompleted,
  kNoConvergence,
  kStalled,
  kUserAbort,
  kFailure
};
const char* RunStatusName(RunStatus status);  // "CONVERGENCE", ...
// The status a report's termination starts with (kFailure when it starts with none).
RunStatus StatusOf(const RunReport& report);
// Makes the termination start with the status that converged, failed and the solver's words
// say (a Ceres stop by the callback reads USER_ABORT, a direct construction DIRECT, a solver's
// CONVERGENCE short of the problem's tolerance STALLED, ...), keeping the solver's own words
// after it. The run protocol (RunProblem) calls it on every run.
void ConcludeStatus(RunReport* report);

// The factor on the fairness rows' weight (ω_f²) for a start whose target measure (e.g. max
// planarity, relative to the mean edge) is `start_residual`: 1 for a start far from the target,
// and start_residual / 1e-2 (not below `floor`) for one within 1e-2 of it. Fairness is there to
// guide a long way; against closeness it would smooth a mesh that is nearly there (an exact
// A-net or PQ mesh) away from where it is.
double StartSoftScale(double start_residual, double floor);

// Called with every record (the start and each step); returning false stops the run.
using RunCallback = std::function<bool(const RunRecord&)>;

// The callback of a run in stages (an A-net step and then rounds of updates, levels, a
// minimisation and then a mesh): passes the records of every stage on to `callback` until it
// returns false, and remembers that, so that the stage running stops at its next iterate, no
// later stage starts (each asks stopped() first) and `callback` sees no record after the stop.
class StopTracker {
 public:
  explicit StopTracker(RunCallback callback) : callback_(std::move(callback)) {}
  StopTracker(const StopTracker&) = delete;
  StopTracker& operator=(const StopTracker&) = delete;

  // Passes `record` on; false when the run must stop (then, and ever after, without calling
  // `callback`).
  bool Record(const RunRecord& record) {
    if (stopped_) return false;
    stopped_ = callback_ && !callback_(record);
    return !stopped_;
  }
  // Record() as a callback for a stage's solver; it refers to this tracker.
  RunCallback callback() {
    return [this](const RunRecord& record) { return Record(record); };
  }
  bool stopped() const { return stopped_; }
  // Whether anyone listens: without a callback a stage need not measure its iterates.
  bool listening() const { return static_cast<bool>(callback_); }

 private:
  RunCallback callback_;
  bool stopped_ = false;
};

class GuidedProblem {
 public:
  virtual ~GuidedProblem() = default;

  virtual Problem& problem() = 0;
  const Problem& problem() const { return const_cast<GuidedProblem*>(this)->problem(); }
  // Guided projection's options (the problem's Options embed them).
  virtual SolverOptions solver_options() const = 0;
  // The Ceres cross-check's options for at most `max_iterations` iterations.
  virtual CeresOptions ceres_options(int max_iterations) const = 0;
  // The problem's measures at x (same layout as problem().x()).
  virtual NamedValues MeasureAt(const Eigen::VectorXd& x) const = 0;
  // Whether measures meet the problem's tolerance.
  virtual bool MeetsTolerance(const NamedValues& measures) const = 0;
  // false for a run asked for a number of steps and no tolerance (e.g. the Weingarten presets
  // of 003, which minimise for a fixed number of iterations): the run then never stops early
  // and counts as converged when it ends without failure or abort.
  virtual bool HasTolerance() const { return true; }
  // false: guided projection stops by its own rules (residual and step tolerances, iterations)
  // and the tolerance only judges the final iterate, e.g. for problems whose start already
  // meets it or whose published runs take a fixed number of steps.
  virtual bool StopsAtTolerance() const { return true; }

  NamedValues Measure() const { return MeasureAt(problem().x()); }

  // Guided projection on problem().x() until the tolerance is met, the solver stops or the
  // callback says so. A later Run of the same problem (after an edit: moved or held vertices,
  // see MeshProblem::Resolve) reuses the first one's set-up and symbolic analysis.
  RunReport Run(const RunCallback& callback = nullptr) {
    return RunWithOptions(solver_options(), callback);
  }
  // Run with these options instead of solver_options().
  RunReport RunWithOptions(const SolverOptions& options, const RunCallback& callback = nullptr);
  // Ceres' Levenberg–Marquardt on the same rows, stopping when the tolerance is met.
  RunReport RunCeres(int max_iterations, const RunCallback& callback = nullptr);
  // Run (kGuidedProjection) or RunCeres for at most solver_options().max_iterations (kCeres);
  // throws std::invalid_argument for kDirect, which needs the problem's own solve (RunDirect).
  // `soft_free`: guided projection starts with the soft terms off (initial_soft_scale 0, as a
  // re-solve from an earlier result does; see RunContext::soft_free_start); Ceres ignores it.
  RunReport RunWith(SolverKind solver, const RunCallback& callback = nullptr,
                    bool soft_free = false);
  // A direct solve (closed form, linear system, propagation) as a run: `solve` sets
  // problem().x(); the report has solver "direct", `method` (ConstructionMethodName), no
  // iterations, the measures before and after, and is judged like the others (failed when x is
  // not finite).
  RunReport RunDirect(const std::string& method, const std::string& termination,
                      const std::function<void()>& solve);

 private:
  // Guided projection's set-up, kept between runs (shared by copies; rebuilt for another
  // Problem object).
  std::shared_ptr<GuidedProjectionSolver> solver_;
};

}  // namespace gproj
