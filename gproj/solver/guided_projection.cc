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

const char* StepControlName(StepControl control) {
  return control == StepControl::kDogleg ? "dogleg" : "damping";
}

bool ParseStepControl(const std::string& name, StepControl* control) {
  if (name == "dogleg")
    *control = StepControl::kDogleg;
  else if (name == "damping")
    *control = StepControl::kDamping;
  else
    return false;
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
  std::snprintf(line, sizeof(line), "%5s %13s %11s %11s %9s %9s %6s %9s %9s %9s\n", "iter",
                "energy", "max_constr", "step", "epsilon", "radius", "trials", "assembly", "factor",
                "solve");
  out << line;
  for (const IterationRecord& r : iterations) {
    std::snprintf(line, sizeof(line),
                  "%5d %13.6e %11.3e %11.3e %9.1e %9.2e %6d %9.4f %9.4f %9.4f\n", r.iteration,
                  r.energy, r.max_constraint, r.step_norm, r.epsilon, r.radius, r.trials,
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

// What a GuidedProjectionSolver keeps between solves: the linearised system, the step solver
// with its analysis, and what they were built for.
struct GuidedProjectionSolver::SetUp {
  std::unique_ptr<LinearizedSystem> system;
  std::unique_ptr<StepSolver> steps;
  std::vector<int> shape;  // variables, then per family its elements and rows
  std::vector<int> held;   // items constant when the pattern was built (left out of it)
  LinearSolverType linear_solver = LinearSolverType::kCholmod;
  int num_threads = 0;
  FillOrdering ordering = FillOrdering::kAuto;
  bool eliminate = true, block_ordering = true;
  int eliminated_variables = 0;
  std::string elimination_note;

  static std::vector<int> ShapeOf(const Problem& problem) {
    std::vector<int> shape = {problem.layout().num_variables(), problem.num_families()};
    for (int f = 0; f < problem.num_families(); ++f) {
      shape.push_back(problem.family(f).num_elements());
      shape.push_back(problem.family(f).num_rows());
    }
    return shape;
  }
  static std::vector<int> HeldOf(const Problem& problem) {
    std::vector<int> items;
    for (int item = 0; item < problem.layout().num_items(); ++item)
      if (problem.IsConstant(item)) items.push_back(item);
    return items;
  }
  // Whether the set-up serves a solve with these options: the same linear algebra, the same
  // rows, and every item left out of the pattern still held (a released one needs its
  // entries, so the pattern is rebuilt; newly held items are zeroed by SetHeld).
  bool Fits(const SolverOptions& o, const Problem& problem) const {
    if (!(system && steps && o.linear_solver == linear_solver && o.num_threads == num_threads &&
          o.ordering == ordering && o.eliminate_auxiliaries == eliminate &&
          o.block_ordering == block_ordering && ShapeOf(problem) == shape))
      return false;
    for (int item : held)
      if (!problem.IsConstant(item)) return false;
    return true;
  }
};

namespace {

// Guided projection as a minimizer (like Ceres' trust-region minimizer): evaluate the iterate,
// stop or step; a step solves the linearisation at ε, retries with a larger ε when the linear
// algebra fails, and with monotone steps damps ε until the energy falls (Nielsen's rule).
class Minimizer {
 public:
  // With `set_up`, the system and the analysis are taken from it when they fit, and left in
  // it otherwise.
  Minimizer(const SolverOptions& options, Problem* problem, const IterationCallback& callback,
            GuidedProjectionSolver::SetUp* set_up = nullptr)
      : options_(options),
        problem_(problem),
        callback_(callback),
        x_(problem->x()),
        set_up_(set_up) {}

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
                  iterate_constraint_, options_.residual_tolerance);
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
    if (set_up_ != nullptr && set_up_->Fits(options_, *problem_)) {
      system_ = set_up_->system.get();
      steps_ = set_up_->steps.get();
      summary_.analysis_reused = true;
      system_->ClearShifts();  // a new solve starts from the rows' own targets
      summary_.eliminated_variables = set_up_->eliminated_variables;
      summary_.elimination_note = set_up_->elimination_note;
    } else {
      owned_system_ = std::make_unique<LinearizedSystem>(problem_);
      system_ = owned_system_.get();
      owned_steps_ = std::make_unique<StepSolver>(options_, problem_->layout(), system_);
      steps_ = owned_steps_.get();
      if (!steps_->Analyze(&summary_, &why_)) return Finish(TerminationType::kFailure, why_);
      if (set_up_ != nullptr) {
        set_up_->steps = std::move(owned_steps_);  // the system it refers to goes with it
        set_up_->system = std::move(owned_system_);
        set_up_->shape = GuidedProjectionSolver::SetUp::ShapeOf(*problem_);
        set_up_->held = GuidedProjectionSolver::SetUp::HeldOf(*problem_);
        set_up_->linear_solver = options_.linear_solver;
        set_up_->num_threads = options_.num_threads;
        set_up_->ordering = options_.ordering;
        set_up_->eliminate = options_.eliminate_auxiliaries;
        set_up_->block_ordering = options_.block_ordering;
        set_up_->eliminated_variables = summary_.eliminated_variables;
        set_up_->elimination_note = summary_.elimination_note;
      }
    }
    summary_.num_rows = system_->num_rows();
    summary_.jacobian_nonzeros = system_->a().nnz();
    step_.resize(summary_.num_variables);
    trial_.resize(summary_.num_variables);
    const VariableLayout& layout = problem_->layout();
    for (int item = 0; item < layout.num_items(); ++item)
      if (problem_->IsConstant(item))
        for (int c = 0; c < layout.ItemDim(item); ++c) held_.push_back(layout.ItemOffset(item) + c);
    system_->SetHeld(held_);
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
    iterate_constraint_ = record_.max_constraint;
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
  bool SolveTrial(double epsilon) { return SolveStep(epsilon) && FormTrial(); }

  // Solves for the step at ε into step_ (held unknowns not moved); false (with why_) when the
  // linear algebra fails.
  bool SolveStep(double epsilon) {
    ++record_.factorizations;
    if (!steps_->Solve(epsilon, &step_, &schur_seconds_, &record_.factorization_seconds,
                       &record_.solve_seconds, &why_))
      return false;
    for (int i : held_) step_[i] = 0.0;
    return true;
  }

  // trial = x^k + step, projected; false (with why_) if not finite.
  bool FormTrial() {
    ++record_.trials;
    trial_ = x_ + step_;
    ProjectOwnedUnknowns(&trial_);
    if (options_.project_trial) options_.project_trial(&trial_);
    if (!trial_.allFinite()) {
      why_ = "the step is not finite";
      return false;
    }
    return true;
  }

  // The energy at the trial point (HUGE_VAL when it cannot be evaluated). When it exceeds
  // `energy` and `restore`, the system is assembled at x^k again; *failed when that fails.
  double TrialEnergy(double energy, bool restore, bool* failed) {
    const auto t = Clock::now();
    const bool assembled = system_->Assemble(trial_, options_.fairness_weight, soft_scale_, &why_);
    const double trial_energy = assembled ? system_->Energy() : HUGE_VAL;
    if (restore && trial_energy > energy &&
        !system_->Assemble(x_, options_.fairness_weight, soft_scale_, &why_))
      *failed = true;
    schur_seconds_ += SecondsSince(t);
    return trial_energy;
  }

  // With monotone steps: whether the trial lowers the energy. Updates the damping on success;
  // on failure the system is assembled at x^k again (same linearisation for the next solve).
  // Sets *failed when that re-assembly fails.
  bool Accepts(double energy, double epsilon, bool* failed) {
    const double trial_energy = TrialEnergy(energy, /*restore=*/true, failed);
    if (trial_energy > energy) return false;
    // Gain ratio against the linear model's reduction: with (A Aᵀ + ε² I) d = rhs it is
    // ½ dᵀ rhs + ½ ε² ‖d‖². With project_trial the actual reduction includes what the
    // projection gained, so the ratio is larger and ε falls faster: intended, the projected
    // point is the one kept.
    const double predicted =
        0.5 * (step_.dot(steps_->rhs()) + epsilon * epsilon * step_.squaredNorm());
    UpdateDamping(epsilon, predicted > 0.0 ? (energy - trial_energy) / predicted : -1.0);
    return true;
  }

  // Nielsen's update of the damping ε² from the gain ratio of a kept step taken at ε.
  void UpdateDamping(double epsilon, double gain) {
    const double factor = std::max(1.0 / 3.0, 1.0 - std::pow(2.0 * std::max(gain, 0.0) - 1.0, 3));
    damping_ = epsilon * std::sqrt(factor);
    growth_ = 2.0;
  }

  // The smallest ε of a step from x^k with constraint residual r_k: options_.epsilon, or with
  // epsilon_min > 0 the residual itself clamped to [epsilon_min, epsilon].
  double EpsilonFloor(double residual) const {
    if (!(options_.epsilon_min > 0.0)) return options_.epsilon;
    return std::clamp(residual, std::min(options_.epsilon_min, options_.epsilon), options_.epsilon);
  }

  // The dogleg path of this iteration in the coefficients of s = a c + b d (c the Cauchy
  // point, d the Gauss–Newton step): D-norms, the model's terms gᵀs and ‖Aᵀs‖², all from
  // inner products formed once, so a trial costs no product with A.
  struct DoglegPath {
    double cc = 0, cd = 0, dd = 0;     // (D c)·(D c), (D c)·(D d), (D d)·(D d)
    double gc = 0, gd = 0;             // gᵀc, gᵀd
    double acc = 0, acd = 0, add = 0;  // (Aᵀc)·(Aᵀc), (Aᵀc)·(Aᵀd), (Aᵀd)·(Aᵀd)
    bool has_cauchy = false;
    // The coefficients of the point of the path at D-norm ≤ radius.
    void At(double radius, double* a, double* b) const {
      const double norm_d = std::sqrt(dd);
      if (norm_d <= radius || !has_cauchy) {
        *a = 0.0;
        *b = norm_d <= radius ? 1.0 : radius / norm_d;
        return;
      }
      const double norm_c = std::sqrt(cc);
      if (norm_c >= radius) {
        *a = radius / norm_c;
        *b = 0.0;
        return;
      }
      // c + τ (d − c) with ‖D(c + τ (d − c))‖ = radius, τ in (0, 1).
      const double uw = cd - cc, ww = cc - 2.0 * cd + dd;
      const double tau =
          ww > 0.0 ? (-uw + std::sqrt(std::max(uw * uw + ww * (radius * radius - cc), 0.0))) / ww
                   : 1.0;
      *a = 1.0 - tau;
      *b = tau;
    }
    double ScaledNorm(double a, double b) const {
      return std::sqrt(std::max(a * a * cc + 2.0 * a * b * cd + b * b * dd, 0.0));
    }
    // m(0) − m(s) of the Gauss–Newton model: gᵀs − ½ ‖Aᵀs‖².
    double Predicted(double a, double b) const {
      return a * gc + b * gd - 0.5 * (a * a * acc + 2.0 * a * b * acd + b * b * add);
    }
  };

  // Forms the dogleg path from the Gauss–Newton step in step_ (ε the step's regularisation).
  void BuildDoglegPath(double epsilon) {
    gn_ = step_;
    gradient_ = steps_->rhs();
    for (int i : held_) gradient_[i] = 0.0;
    system_->NormalDiagonal(&scale_);
    scale_.array() += epsilon * epsilon;  // D², > 0
    cauchy_ = gradient_.cwiseQuotient(scale_);
    system_->MultiplyAt(cauchy_, &at_c_);
    system_->MultiplyAt(gn_, &at_d_);
    DoglegPath& p = path_;
    const double g_p = gradient_.dot(cauchy_), curvature = at_c_.squaredNorm();
    p.has_cauchy = g_p > 0.0 && curvature > 0.0 && std::isfinite(g_p / curvature);
    const double alpha = p.has_cauchy ? g_p / curvature : 0.0;
    cauchy_ *= alpha;
    at_c_ *= alpha;
    p.cc = cauchy_.dot(cauchy_.cwiseProduct(scale_));
    p.cd = cauchy_.dot(gn_.cwiseProduct(scale_));
    p.dd = gn_.dot(gn_.cwiseProduct(scale_));
    p.gc = gradient_.dot(cauchy_);
    p.gd = gradient_.dot(gn_);
    p.acc = at_c_.squaredNorm();
    p.acd = at_c_.dot(at_d_);
    p.add = at_d_.squaredNorm();
  }

  // A step with dogleg step control: one factorisation (more only when the linear algebra
  // fails), then trials along the dogleg path until one lowers the energy and is admissible.
  bool TakeDoglegStep(double energy, double epsilon, double residual_at_start) {
    int failures = 0;
    while (!SolveStep(epsilon)) {
      if (++failures > options_.max_retries) return FailAfterRetries(epsilon);
      epsilon *= options_.epsilon_growth;
    }
    BuildDoglegPath(epsilon);
    double a = 0.0, b = 1.0;
    path_.At(radius_, &a, &b);
    for (int rejections = 0;; ++rejections) {
      if (a != 0.0 || b != 1.0) step_ = a * cauchy_ + b * gn_;
      bool failed = false;
      const bool formed = FormTrial();
      const bool admissible =
          formed && (!options_.admissible_trial || options_.admissible_trial(trial_));
      const double trial_energy =
          admissible ? TrialEnergy(energy, /*restore=*/false, &failed) : HUGE_VAL;
      const double taken = path_.ScaledNorm(a, b);
      if (trial_energy <= energy) {
        const double predicted = path_.Predicted(a, b);
        const double gain = predicted > 0.0 ? (energy - trial_energy) / predicted : -1.0;
        if (gain > 0.75) radius_ = std::max(radius_, 3.0 * taken);
        if (gain < 0.25 && taken > 0.0) radius_ = 0.5 * std::min(radius_, taken);
        UpdateDamping(epsilon, gain);
        break;
      }
      radius_ = 0.5 * taken;
      if (rejections + 1 > options_.max_rejections || !(radius_ > 0.0)) {
        // Leave the system (and the families' frozen state) at x^k.
        if (!system_->Assemble(x_, options_.fairness_weight, soft_scale_, &why_))
          return Finish(TerminationType::kFailure, why_);
        char last[64];
        std::snprintf(last, sizeof(last), " (trust radius reduced to %.3g)", radius_);
        return Stop(std::string(admissible ? "no step lowers the energy"
                                           : "no admissible step (the last trial was refused)") +
                    last);
      }
      path_.At(radius_, &a, &b);
    }
    record_.retries = failures + record_.trials - 1;
    return Accept(epsilon, residual_at_start);
  }

  bool FailAfterRetries(double epsilon) {
    char last[32];
    std::snprintf(last, sizeof(last), "%g", epsilon);
    return Finish(TerminationType::kFailure, why_ + " (after " +
                                                 std::to_string(options_.max_retries) +
                                                 " increases of epsilon to " + last + ")");
  }

  // Keeps trial_ as x^{k+1} and moves the soft weights on.
  bool Accept(double epsilon, double residual_at_start) {
    summary_.factor_nonzeros = steps_->FactorNonZeros();
    summary_.factor_flops = steps_->FactorFlops();
    record_.epsilon = epsilon;
    record_.radius =
        options_.monotone && options_.step_control == StepControl::kDogleg ? radius_ : 0.0;
    record_.step_norm = (trial_ - x_).lpNorm<Eigen::Infinity>();
    x_.swap(trial_);
    double decay = options_.soft_weight_decay;
    if (options_.soft_weight_residual_factor > 0.0 && decay < 1.0 && has_constraint_rows_)
      decay = std::min(decay, options_.soft_weight_residual_factor * residual_at_start);
    soft_scale_ = std::max(soft_scale_ * decay, options_.soft_weight_floor);
    return true;
  }

  // Moves x to the next iterate; false when the run ends (failure, or no lower energy).
  bool TakeStep() {
    steps_->SetRhs();
    const double energy = step_energy_;
    const double residual_at_start = record_.max_constraint;
    const double floor = EpsilonFloor(residual_at_start);
    record_ = IterationRecord();
    double epsilon = options_.monotone ? std::max(floor, damping_) : floor;
    if (options_.monotone && options_.step_control == StepControl::kDogleg)
      return TakeDoglegStep(energy, epsilon, residual_at_start);
    growth_ = 2.0;
    int failures = 0, rejections = 0;
    for (;;) {
      if (!SolveTrial(epsilon)) {
        if (++failures > options_.max_retries) return FailAfterRetries(epsilon);
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
    return Accept(epsilon, residual_at_start);
  }

  const SolverOptions& options_;
  Problem* problem_;
  const IterationCallback& callback_;
  Eigen::VectorXd& x_;
  const Clock::time_point start_ = Clock::now();
  GuidedProjectionSolver::SetUp* set_up_;
  SolverSummary summary_;
  std::unique_ptr<LinearizedSystem> owned_system_;  // without a set-up that takes them
  std::unique_ptr<StepSolver> owned_steps_;
  LinearizedSystem* system_ = nullptr;
  StepSolver* steps_ = nullptr;
  Eigen::VectorXd step_, trial_;
  std::vector<int> held_;  // indices of x in constant items
  IterationRecord record_;
  std::string why_;
  double soft_scale_ = 1.0;
  double damping_ = 0.0;              // ε of the next step when options_.monotone
  bool has_constraint_rows_ = false;  // the residual-tied schedule needs some
  double growth_ = 2.0;               // growth of ε² on the next rejection
  double schur_seconds_ = 0.0;
  double step_energy_ = 0.0;         // energy at x^k that a monotone step must lower
  double iterate_constraint_ = 0.0;  // max |φ| of the constraint rows at x^k
  // Dogleg step control: the trust radius (∞ until a trial is rejected), this iteration's
  // Gauss–Newton step, gradient, D², Cauchy point, Aᵀ of both, and the path's products.
  double radius_ = HUGE_VAL;
  Eigen::VectorXd gn_, gradient_, scale_, cauchy_, at_c_, at_d_;
  DoglegPath path_;
};

}  // namespace

SolverSummary Solve(const SolverOptions& options, Problem* problem,
                    const IterationCallback& callback) {
  return Minimizer(options, problem, callback).Run();
}

GuidedProjectionSolver::GuidedProjectionSolver(Problem* problem)
    : problem_(problem), set_up_(std::make_unique<SetUp>()) {}

GuidedProjectionSolver::~GuidedProjectionSolver() = default;

SolverSummary GuidedProjectionSolver::Solve(const SolverOptions& options,
                                            const IterationCallback& callback) {
  return Minimizer(options, problem_, callback, set_up_.get()).Run();
}

double EvaluateObjective(Problem* problem, double fairness_weight, const Eigen::VectorXd& x) {
  LinearizedSystem system(problem);
  std::string why;
  if (!system.Assemble(x, fairness_weight, 1.0, &why)) return NAN;
  return system.Energy();
}

}  // namespace gproj
