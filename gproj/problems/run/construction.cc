#include "gproj/problems/run/construction.h"

namespace gproj {

const char* ConstructionMethodName(ConstructionMethod method) {
  switch (method) {
    case ConstructionMethod::kClosedForm:
      return "closed form";
    case ConstructionMethod::kPropagation:
      return "propagation";
    case ConstructionMethod::kLinearSystem:
      return "linear system";
    case ConstructionMethod::kJetFit:
      return "jet fit";
    case ConstructionMethod::kIntegerGridMap:
      return "integer-grid map";
    case ConstructionMethod::kBfgs:
      return "BFGS";
  }
  return "?";
}

Construction::Construction(ConstructionMethod method, std::string detail)
    : method_(method), detail_(std::move(detail)), start_(std::chrono::steady_clock::now()) {}

RunReport Construction::Finish(const NamedValues& initial, const NamedValues& final,
                               bool met) const {
  RunReport report;
  report.solver = method_ == ConstructionMethod::kBfgs ? SolverKind::kCeres : SolverKind::kDirect;
  report.method = ConstructionMethodName(method_);
  report.converged = met;
  report.termination = "constructed directly (" + detail_ + ")";
  report.seconds = seconds();
  report.initial = initial;
  report.final = final;
  FailOnNonFiniteMeasures(&report);
  return report;
}

RunReport Construction::Stopped(const RunStopped& stop) const {
  RunReport report = Finish({}, {}, false);
  report.termination = std::string("USER_ABORT: ") + stop.what();
  return report;
}

}  // namespace gproj
