#include "gproj/problems/run/report_json.h"

#include <cmath>

namespace gproj {

// Non-finite numbers become null (JSON has no NaN).
nlohmann::json JsonNumber(double value) {
  return std::isfinite(value) ? nlohmann::json(value) : nlohmann::json(nullptr);
}

namespace {

nlohmann::json MeasuresJson(const NamedValues& values) {
  nlohmann::json j = nlohmann::json::object();
  for (const NamedValue& v : values) j[v.name] = JsonNumber(v.value);
  return j;
}

nlohmann::json RecordJson(const RunRecord& r) {
  nlohmann::json j = {
      {"iteration", r.iteration},   {"energy", JsonNumber(r.energy)},
      {"step", JsonNumber(r.step)}, {"epsilon", r.epsilon},
      {"soft_scale", r.soft_scale}, {"max_constraint", JsonNumber(r.max_constraint)},
      {"seconds", r.seconds}};
  for (const NamedValue& v : r.measures) j[v.name] = JsonNumber(v.value);
  nlohmann::json families = nlohmann::json::object();
  for (const FamilyResidual& f : r.families)
    families[f.name] = {{"max", JsonNumber(f.max_abs)}, {"rms", JsonNumber(f.rms)}};
  j["families"] = families;
  j["assembly_seconds"] = r.assembly_seconds;
  j["factorization_seconds"] = r.factorization_seconds;
  j["solve_seconds"] = r.solve_seconds;
  return j;
}

}  // namespace

nlohmann::json ReportJson(const std::string& command, const RunReport& report,
                          const nlohmann::json& extra) {
  nlohmann::json history = nlohmann::json::array();
  for (const RunRecord& r : report.history) history.push_back(RecordJson(r));
  nlohmann::json j = {{"command", command},
                      {"solver", SolverKindName(report.solver)},
                      {"status", RunStatusName(StatusOf(report))},
                      {"converged", report.converged},
                      {"failed", report.failed},
                      {"termination", report.termination},
                      {"iterations", report.iterations},
                      {"seconds", report.seconds},
                      {"variables", report.variables},
                      {"initial", MeasuresJson(report.initial)},
                      {"final", MeasuresJson(report.final)},
                      {"history", history}};
  if (!report.method.empty()) j["method"] = report.method;
  for (auto it = extra.begin(); it != extra.end(); ++it) j[it.key()] = it.value();
  return j;
}

}  // namespace gproj
