#pragma once
// The guided-projection solver (003 §3.3, eq. 11; Tang et al. 2014). Each iteration
// linearises every row at x^k and solves
//   ‖C x − r‖² + ω_f² ‖P x‖² + ε² ‖x − x^k‖² → min
// by sparse Cholesky of CᵀC + ω_f² PᵀP + ε² I (pattern analysed once per problem).

#include <Eigen/Core>
#include <cstdint>
#include <functional>
#include <memory>
#include <string>
#include <vector>

#include "gproj/solver/problem.h"
#include "gproj/solver/sparse_cholesky.h"

namespace gproj {

// See SolverOptions::step_control.
enum class StepControl { kDamping, kDogleg };
const char* StepControlName(StepControl control);  // "damping", "dogleg"
bool ParseStepControl(const std::string& name, StepControl* control);

struct SolverOptions {
  // Iterations (linear solves) at most.
  int max_iterations = 50;
  // Converged when every kConstraint row has |φ| ≤ this (0 disables the test).
  double residual_tolerance = 1e-10;
  // Converged when the step ‖x^{k+1} − x^k‖∞ ≤ this (a stationary point; 0 disables).
  double step_tolerance = 1e-14;
  // ω_f: kFairness families get row weight ω_f² × their own weight.
  double fairness_weight = 0.1;
  // ε: the proximal term ε²‖x − x^k‖² that keeps every normal matrix positive definite.
  double epsilon = 1e-3;
  // With epsilon_min > 0, ε follows the kConstraint residual r_k of the iterate:
  // ε_k = clamp(r_k, epsilon_min, epsilon) (Levenberg–Marquardt with μ = ‖φ‖², which
  // converges quadratically even where the constraint Jacobian is rank deficient; Yamashita &
  // Fukushima 2001). A fixed ε slows the last steps to a linear rate along the directions the
  // constraints barely constrain.
  double epsilon_min = 0.0;
  // Soft schedule: kSoft and kFairness weights are multiplied by max(decay^k, floor) at
  // iteration k (decay 1: fixed weights, a fixed point minimises the weighted objective).
  double soft_weight_decay = 1.0;
  double soft_weight_floor = 0.0;
  // Residual-tied schedule (0: off; no effect with decay 1, fixed weights, or without
  // kConstraint rows): the factor also falls with the constraints' own progress, by
  // min(decay, soft_weight_residual_factor · r_k) at iteration k, r_k the max |φ| of the
  // kConstraint rows at x^k. Once the constraints are nearly met the soft weights then vanish
  // superlinearly and the steps converge like Gauss–Newton on the constraints alone.
  double soft_weight_residual_factor = 0.0;
  // Soft-weight factor at iteration 0 (e.g. small when continuing from a converged state).
  double initial_soft_scale = 1.0;
  // On a failed factorisation or a non-finite step ε is multiplied by this and the iteration
  // retried, at most max_retries times, before the solver stops with kFailure.
  double epsilon_growth = 10.0;
  int max_retries = 4;
  // Monotone steps (Levenberg–Marquardt damping): a step is kept only if it lowers the energy
  // (with this iteration's weights, the families updated at the trial point); otherwise ε²
  // grows (×2, ×4, ×8, …) and the step is recomputed from the same linearisation. After a kept
  // step ε² follows the gain ratio (Nielsen's rule), never below `epsilon`². The solver stops
  // (converged) when max_rejections growths in a row find no lower energy. Costs one more
  // assembly per step.
  bool monotone = false;
  int max_rejections = 12;
  // How a monotone step that does not lower the energy (or is refused) is shortened.
  //  kDamping: ε² grows and the step is refactorised from the same linearisation, as above.
  //  kDogleg: ε follows the gain ratio as with kDamping, but a rejection keeps the factor of
  //    the iteration: the step moves along the dogleg path from the Gauss–Newton step d
  //    towards the Cauchy point (the model's minimiser along the gradient, both scaled by
  //    D = diag(A Aᵀ + ε² I)^½) inside a trust radius ‖D s‖ ≤ Δ. A rejection halves Δ below
  //    the trial's ‖D s‖; a kept step with gain ratio > 3/4 lets it grow to 3 ‖D s‖, one below
  //    1/4 halves it (Powell's dogleg, as Ceres' DOGLEG); Δ carries over to later iterations.
  //    A rejected trial then costs one evaluation, not a factorisation. Until the first
  //    rejection or kept step of gain ratio below 1/4 the steps are those of kDamping.
  StepControl step_control = StepControl::kDogleg;
  // Exact constraints by shifted targets (Bregman iteration; the method of multipliers for
  // non-linear rows): after each step every kConstraint row's target moves against its
  // residual, so the iterates converge to a point where the constraint rows hold exactly and
  // the soft rows are minimised subject to them, rather than to a balance set by the weights.
  // The energy is then that of the shifted rows; max_constraint stays the true residual.
  bool shifted_constraints = false;
  // Applied to every trial point x^k + d before it is assessed, e.g. to set auxiliary unknowns
  // to their exact values from the primary ones (null: none).
  std::function<void(Eigen::VectorXd*)> project_trial;
  // Whether a trial point (after project_trial) may be kept, e.g. a surface that does not fold
  // (null: every finite trial). A refused trial counts as a rejection: ε grows and the step is
  // recomputed from the same linearisation; after max_rejections refusals in a row the solver
  // stops (converged: no admissible step lowers the energy).
  std::function<bool(const Eigen::VectorXd&)> admissible_trial;
  LinearSolverType linear_solver = LinearSolverType::kCholmod;
  // Eliminate the items of eliminable blocks (per-element auxiliaries such as face normals)
  // with a Schur complement before factorising; the factor then covers the rest only.
  bool eliminate_auxiliaries = true;
  // Threads for the BLAS under CHOLMOD (0: leave the library default).
  int num_threads = 0;
  // The fill-reducing ordering of the one symbolic analysis.
  FillOrdering ordering = FillOrdering::kAuto;
  // Order the graph of the items (a vertex's 3 coordinates as one node) rather than of the
  // scalars: the same fill, a fraction of the ordering time.
  bool block_ordering = true;

  bool IsValid(std::string* why) const;
};

struct FamilyResidual {
  std::string name;
  double max_abs = 0.0;  // max |φ| over the family's rows (unweighted)
  double rms = 0.0;
};

struct IterationRecord {
  int iteration = 0;    // 0: the start, before any step
  double energy = 0.0;  // ½ Σ w φ² + ½ ω_f² ‖P x‖² with this iteration's weights
  double max_constraint = 0.0;  // max |φ| over kConstraint families
  std::vector<FamilyResidual> families;
  double step_norm = 0.0;         // ‖x^k − x^{k−1}‖∞ (0 at the start)
  double epsilon = 0.0;           // ε used for the step that led here
  double soft_scale = 1.0;        // soft-weight factor in effect for this iteration's energy
  int retries = 0;                // ε increases needed for that step
  int factorizations = 0;         // numeric factorisations for that step
  int trials = 0;                 // trial points assessed for it (1: the first one was kept)
  double radius = 0.0;            // dogleg: trust radius after it (∞: not yet bounded); else 0
  double assembly_seconds = 0.0;  // family updates + evaluation + assembly (+ Schur complement)
  double factorization_seconds = 0.0;  // numeric factorisation (of the step that led here)
  double solve_seconds = 0.0;          // triangular solves (of the step that led here)
};

enum class TerminationType {
  kConvergence,    // the residual tolerance met, or the callback said the problem's tolerance
                   // is; with residual_tolerance 0, also a vanished step or (monotone) no step
                   // that lowers the energy however large ε grows (a stationary point)
  kStalled,        // the step vanished, or no step lowers the energy, while a kConstraint row
                   // is still above residual_tolerance: not converged
  kNoConvergence,  // max_iterations reached
  kFailure,        // numerical failure (non-finite values, factorisation failed after retries)
  kUserAbort,      // the callback asked to stop
};
const char* TerminationTypeName(TerminationType type);

struct SolverSummary {
  TerminationType termination = TerminationType::kFailure;
  std::string message;
  std::vector<IterationRecord> iterations;  // iterations[0] is the start
  int num_variables = 0;
  int num_rows = 0;
  int64_t jacobian_nonzeros = 0;
  int64_t factor_nonzeros = 0;
  double factor_flops = 0.0;     // of one numeric factorisation (CHOLMOD's count; 0 if unknown)
  int eliminated_variables = 0;  // removed by the Schur complement before factorising
  std::string elimination_note;  // why no elimination happened, when it did not
  double analysis_seconds = 0.0;
  bool analysis_reused = false;  // a GuidedProjectionSolver's re-solve: no new analysis
  double total_seconds = 0.0;
  LinearSolverType linear_solver = LinearSolverType::kCholmod;

  int num_steps() const { return static_cast<int>(iterations.size()) - 1; }
  bool converged() const { return termination == TerminationType::kConvergence; }
  // x holds an iterate the solver vouches for: every outcome but kFailure (after a numerical
  // failure x holds the last accepted iterate, finite, but the run did not end by its rules).
  bool usable = false;
  std::string BriefReport() const;
  std::string FullReport() const;
};

enum class CallbackResult { kContinue, kConverged, kAbort };
// Called after every evaluation (the start and each step) with the record and the iterate.
using IterationCallback =
    std::function<CallbackResult(const IterationRecord&, const Eigen::VectorXd&)>;

// Runs guided projection on problem->x() in place. Never leaves non-finite values in x: a
// step that would is rejected (and retried with a larger ε).
SolverSummary Solve(const SolverOptions& options, Problem* problem,
                    const IterationCallback& callback = nullptr);

// Guided projection that keeps its set-up between solves of one problem: the pattern of the
// rows, the elimination and the symbolic analysis are built by the first Solve and reused by
// the next ones (their summaries have analysis_reused set and analysis_seconds 0), so a warm
// re-solve after an edit costs its iterations only. Between solves x, the held items and the
// rows' data may change; when the families, their elements or the linear-algebra options
// (linear_solver, num_threads, ordering, eliminate_auxiliaries, block_ordering) change, the
// set-up is rebuilt, and so it is when an item held at the set-up is released (the pattern
// leaves held items out). The problem must outlive the solver.
class GuidedProjectionSolver {
 public:
  explicit GuidedProjectionSolver(Problem* problem);
  ~GuidedProjectionSolver();
  GuidedProjectionSolver(const GuidedProjectionSolver&) = delete;
  GuidedProjectionSolver& operator=(const GuidedProjectionSolver&) = delete;

  SolverSummary Solve(const SolverOptions& options, const IterationCallback& callback = nullptr);
  Problem* problem() const { return problem_; }

  struct SetUp;  // internal

 private:
  Problem* problem_;
  std::unique_ptr<SetUp> set_up_;
};

// Weighted objective ½ Σ w φ² + ½ ω_f² ‖P x‖² at x with fixed weights (soft scale 1).
double EvaluateObjective(Problem* problem, double fairness_weight, const Eigen::VectorXd& x);

}  // namespace gproj
