#include "python/extension/problem_solve.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <stdexcept>
#include <string>
#include <vector>

#include "gproj/common/input_error.h"
#include "gproj/problems/run/guided_problem.h"
#include "python/extension/python_term.h"
#include "python/extension/run_bridge.h"

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

// max |φ| over the rows of the constraint families at the problem's x (their frozen
// coefficients as the solve left them).
double MaxConstraintResidual(const Problem& problem) {
  const VariableLayout& layout = problem.layout();
  double worst = 0.0;
  std::vector<double> local, phi, jac;
  for (int f = 0; f < problem.num_families(); ++f) {
    const ConstraintFamily& family = problem.family(f);
    if (family.role() != FamilyRole::kConstraint) continue;
    phi.resize(family.rows_per_element());
    for (int e = 0; e < family.num_elements(); ++e) {
      local.clear();
      for (int k = 0; k < family.element_num_items(e); ++k) {
        const int item = family.element_items(e)[k];
        const double* begin = problem.x().data() + layout.ItemOffset(item);
        local.insert(local.end(), begin, begin + layout.ItemDim(item));
      }
      jac.resize(phi.size() * local.size());
      family.EvaluateElement(e, local.data(), phi.data(), jac.data());
      for (double v : phi) worst = std::max(worst, std::abs(v));
    }
  }
  return worst;
}

}  // namespace

py::dict SolveProblem(Problem* problem, ErrorSlot* errors, const std::string& solver,
                      const py::object& callback, const GenericSolveArgs& args) {
  SolverKind kind = SolverKind::kDirect;
  try {
    kind = SolverKindFromName(solver);
  } catch (const std::invalid_argument&) {
  }
  if (kind == SolverKind::kDirect)
    throw InputError("`solver` must be gp or ceres, not '" + solver + "'");
  std::string why;
  if (!args.ceres.IsValid(&why)) throw InputError("invalid option: " + why);
  errors->error.reset();
  // Terms written in Python: derivatives probed and checked once, slacks at the start.
  for (int f = 0; f < problem->num_families(); ++f)
    if (auto* term = dynamic_cast<PythonTerm*>(&problem->family(f))) {
      term->PrepareDerivatives(*problem);
      term->Project(problem->layout(), &problem->x());
      errors->RethrowIfAny();
    }
  RunBridge bridge(callback);
  const auto go_on = [&](const RunRecord& record) {
    return bridge.OnRecord(record) && errors->empty();
  };
  py::dict summary;
  if (kind == SolverKind::kGuidedProjection) {
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
    // Ceres converges on the whole objective; the constraint rows decide, as they do for
    // guided projection (residual_tolerance).
    const double worst = MaxConstraintResidual(*problem);
    summary["max_constraint"] = worst;
    const double tolerance = args.gp.residual_tolerance;
    if (summary["converged"].cast<bool>() && tolerance > 0.0 && !(worst <= tolerance)) {
      char text[160];
      std::snprintf(text, sizeof(text),
                    "Ceres converged with a constraint row at |phi| = %.3g, above "
                    "residual_tolerance %.3g",
                    worst, tolerance);
      summary["converged"] = false;
      summary["termination"] = "STALLED";
      summary["message"] = text;
    }
  }
  summary["objective"] = EvaluateObjective(problem, args.gp.fairness_weight, problem->x());
  return summary;
}

}  // namespace gproj::python
