#include "gproj/problems/run/report_json.h"

#include <cmath>
#include <cstdint>
#include <string>

namespace gproj {

// Non-finite numbers become null (JSON has no NaN).
nlohmann::json JsonNumber(double value) {
  return std::isfinite(value) ? nlohmann::json(value) : nlohmann::json(nullptr);
}

bool IsCountMeasure(const std::string& name) {
  auto ends = [&name](const char* suffix) {
    const std::string s = suffix;
    return name.size() >= s.size() && name.compare(name.size() - s.size(), s.size(), s) == 0;
  };
  return name == "quads" || name == "patches" || name == "round" || ends("_quads") ||
         ends("_vertices") || ends("_faces") || ends("_edges") || ends("iterations") ||
         name.rfind("worst_", 0) == 0;
}

nlohmann::json MeasureJson(const NamedValue& v) {
  if (IsCountMeasure(v.name) && std::isfinite(v.value) && v.value == std::floor(v.value) &&
      std::abs(v.value) < 9e15)
    return static_cast<int64_t>(v.value);
  return JsonNumber(v.value);
}

nlohmann::json MeasuresJson(const NamedValues& values) {
  nlohmann::json j = nlohmann::json::object();
  for (const NamedValue& v : values) j[v.name] = MeasureJson(v);
  return j;
}

nlohmann::json RecordJson(const RunRecord& r) {
  nlohmann::json j = {
      {"iteration", r.iteration},   {"energy", JsonNumber(r.energy)},
      {"step", JsonNumber(r.step)}, {"epsilon", r.epsilon},
      {"soft_scale", r.soft_scale}, {"max_constraint", JsonNumber(r.max_constraint)},
      {"seconds", r.seconds}};
  for (const NamedValue& v : r.measures) j[v.name] = MeasureJson(v);
  nlohmann::json families = nlohmann::json::object();
  for (const FamilyResidual& f : r.families)
    families[f.name] = {{"max", JsonNumber(f.max_abs)}, {"rms", JsonNumber(f.rms)}};
  j["families"] = families;
  j["factorizations"] = r.factorizations;
  j["trials"] = r.trials;
  j["radius"] = JsonNumber(r.radius);  // null: not yet bounded
  j["assembly_seconds"] = r.assembly_seconds;
  j["factorization_seconds"] = r.factorization_seconds;
  j["solve_seconds"] = r.solve_seconds;
  return j;
}

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
