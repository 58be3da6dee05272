#include "python/problem_solve.h"

#include "gproj/common/input_error.h"
#include "gproj/problems/run/guided_problem.h"
#include "python/run_bridge.h"

namespace gproj::python {
namespace {

py::list Records(const std::vector<RunRecord>& records) {
  py::list list;
  for (const RunRecord& r : records) list.append(RecordToPython(r));
  return list;
}

py::dict GuidedProjectionSummary(const SolverSummary& s) {
  std::vector<RunRecord> records;
  for (const IterationRecord& r : s.iterations) records.push_back(ToRunRecord(r));
  py::dict d;
  d["solver"] = "gp";
  d["termination"] = TerminationTypeName(s.termination);
  d["message"] = s.message;
  d["converged"] = s.converged();
  d["usable"] = s.usable;
  d["iterations"] = Records(records);
  d["num_variables"] = s.num_variables;
  d["num_rows"] = s.num_rows;
  d["jacobian_nonzeros"] = s.jacobian_nonzeros;
  d["factor_nonzeros"] = s.factor_nonzeros;
  d["eliminated_variables"] = s.eliminated_variables;
  d["analysis_seconds"] = s.analysis_seconds;
  d["total_seconds"] = s.total_seconds;
  d["linear_solver"] = LinearSolverTypeName(s.linear_solver);
  d["brief_report"] = s.BriefReport();
  d["full_report"] = s.FullReport();
  return d;
}

py::dict CeresSummaryDict(const CeresSummary& s) {
  std::vector<RunRecord> records;
  for (const CeresIterationRecord& r : s.iterations) records.push_back(ToRunRecord(r));
  py::dict d;
  d["solver"] = "ceres";
  d["termination"] = TerminationTypeName(s.termination);
  d["ceres_termination"] = s.ceres_termination;
  d["message"] = s.message;
  d["converged"] = s.termination == TerminationType::kConvergence;
  d["usable"] = s.usable;
  d["iterations"] = Records(records);
  d["initial_cost"] = s.initial_cost;
  d["final_cost"] = s.final_cost;
  d["num_parameters"] = s.num_parameters;
  d["num_residuals"] = s.num_residuals;
  d["num_residual_blocks"] = s.num_residual_blocks;
  d["total_seconds"] = s.total_seconds;
  d["brief_report"] = s.BriefReport();
  d["full_report"] = s.FullReport();
  return d;
}

}  // namespace

py::dict SolveProblem(Problem* problem, ErrorSlot* errors, const std::string& solver,
                      const py::object& callback, const GenericSolveArgs& args) {
  if (solver != "gp" && solver != "ceres")
    throw InputError("solver must be gp or ceres, not '" + solver + "'");
  std::string why;
  if (!args.ceres.IsValid(&why)) throw InputError("invalid option: " + why);
  errors->error.reset();
  RunBridge bridge(callback);
  const auto go_on = [&](const RunRecord& record) {
    return bridge.OnRecord(record) && errors->empty();
  };
  py::dict summary;
  if (solver == "gp") {
    const SolverSummary s = bridge.Call([&] {
      return Solve(args.gp, problem, [&](const IterationRecord& r, const Eigen::VectorXd&) {
        return go_on(ToRunRecord(r)) ? CallbackResult::kContinue : CallbackResult::kAbort;
      });
    });
    errors->RethrowIfAny();
    summary = GuidedProjectionSummary(s);
  } else {
    const CeresSummary s = bridge.Call([&] {
      return SolveWithCeres(args.ceres, problem,
                            [&](const CeresIterationRecord& r, const Eigen::VectorXd&) {
                              return go_on(ToRunRecord(r));
                            });
    });
    errors->RethrowIfAny();
    summary = CeresSummaryDict(s);
  }
  summary["objective"] = EvaluateObjective(problem, args.gp.fairness_weight, problem->x());
  return summary;
}

}  // namespace gproj::python
