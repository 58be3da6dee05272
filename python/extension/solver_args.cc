#include "python/extension/solver_args.h"

#include "gproj/common/input_error.h"

namespace gproj::python {

void SolverArgs::ApplyTo(SolverOptions* options) const {
  if (max_iterations < 0 || max_iterations > 100000)
    throw InputError("max_iterations must be in [0, 100000], not " +
                     std::to_string(max_iterations));
  if (!ParseLinearSolverType(linear_solver, &options->linear_solver))
    throw InputError("linear_solver must be cholmod or eigen, not '" + linear_solver + "'");
  options->max_iterations = max_iterations;
  options->fairness_weight = fairness;
  options->epsilon = epsilon;
  options->soft_weight_decay = soft_decay;
  options->soft_weight_floor = soft_floor;
  options->soft_weight_residual_factor = soft_residual;
  options->epsilon_min = epsilon_min;
  options->num_threads = threads;
  std::string why;
  if (!options->IsValid(&why)) throw InputError("invalid option: " + why);
}

const char* const kSolverArgsDoc = R"(
Guided projection (defaults: the problem's, as on the command line):
    max_iterations: iterations at most (--max-iterations).
    fairness: omega_f, weight of the fairness rows (--fairness).
    epsilon: weight of the proximal term eps^2 |x - x^k|^2 (--epsilon).
    soft_decay: closeness and fairness weights are multiplied by this each iteration
        (--soft-decay) ...
    soft_floor: ... down to this fraction of their initial value (--soft-floor).
    soft_residual: ... and by this times the max constraint residual of the iteration
        (--soft-residual; 0: off).
    epsilon_min: when > 0, epsilon follows the constraint residual down to this
        (--epsilon-min).
    linear_solver: "cholmod" (supernodal) or "eigen" (--linear-solver).
    threads: threads for BLAS / Ceres, 0: the library default (--threads).
)";

}  // namespace gproj::python
