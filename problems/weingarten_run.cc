// The multiresolution Weingarten run (003 §4.1.1): optimise, insert a knot in every span,
// optimise again, for every level.
#include <cmath>

#include "problems/weingarten.h"

namespace gproj {

WeingartenRun RunWeingarten(const BSplineSurface& input, const WeingartenOptions& options,
                            bool use_ceres, const RunCallback& on_iteration,
                            const std::function<void(int, const WeingartenProblem&)>& on_level) {
  WeingartenRun run;
  BSplineSurface current = input;
  for (int level = 0; level <= options.refine_levels; ++level) {
    if (level > 0) current = InsertKnotsUniform(current, 1);
    WeingartenProblem problem(current, options);
    run.su = problem.maps().su;
    run.sv = problem.maps().sv;
    run.variables = problem.num_variables();
    if (level == 0) run.before = MeasureWeingarten(input, input, run.su, run.sv);
    if (on_level) on_level(level, problem);
    auto record = [&](RunRecord r) {
      run.history.push_back(r);
      run.history_level.push_back(level);
      return on_iteration ? on_iteration(r) : true;
    };
    int iterations = 0;
    if (!use_ceres) {
      const SolverSummary summary = problem.Solve([&](const IterationRecord& r) {
        return record(ToRunRecord(r)) ? CallbackResult::kContinue : CallbackResult::kAbort;
      });
      iterations = summary.num_steps();
      run.termination = summary.message;
      run.failed = summary.termination == TerminationType::kFailure;
      run.converged = run.converged && summary.termination == TerminationType::kConvergence;
    } else {
      const CeresSummary summary = problem.SolveWithCeres(
          options.max_iterations,
          [&](const CeresIterationRecord& s) { return record(ToRunRecord(s)); });
      iterations = summary.num_steps();
      run.termination = "ceres " + summary.ceres_termination + ": " + summary.message;
      run.failed = summary.termination == TerminationType::kFailure;
      run.converged = run.converged && summary.ceres_termination == "CONVERGENCE";
    }
    run.iterations += iterations;
    if (run.failed || !problem.problem().x().allFinite()) {
      run.failed = true;
      return run;
    }
    current = problem.Result();
    run.relation = problem.LinearRelation();
    run.levels.push_back({level, current.nu, current.nv, run.su, run.sv, run.variables, iterations,
                          problem.Measures().misalignment});
  }
  run.result = current;
  run.after = MeasureWeingarten(current, input, run.su, run.sv);
  return run;
}

}  // namespace gproj
