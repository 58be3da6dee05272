#pragma once
// The run report as JSON: one schema for every problem and front end (the command line's
// --report, the Python module's report dict). See docs/command-line.md, "Report JSON".

#include <nlohmann/json.hpp>
#include <string>

#include "gproj/problems/run/guided_problem.h"

namespace gproj {

// Whether a measure is a count or an element id, written as an integer: "quads", "patches",
// "round", names ending in _quads, _vertices, _faces or iterations, and worst_<element> ids.
bool IsCountMeasure(const std::string& name);
// A measure as JSON: an integer for a count or an element id, else JsonNumber.
nlohmann::json MeasureJson(const NamedValue& value);
// Named measures as a JSON object (MeasureJson each), as the report's "initial" and "final".
nlohmann::json MeasuresJson(const NamedValues& values);

// A number for JSON: non-finite values become null (JSON has no NaN).
nlohmann::json JsonNumber(double value);

// One record as the report's history has it (and the HTTP service streams it): iteration,
// energy, step, epsilon, soft_scale, max_constraint, seconds, the measures, per-term residuals,
// factorizations, trials, radius and the time split.
nlohmann::json RecordJson(const RunRecord& record);

// The report: command, solver, converged, failed, termination, iterations, seconds,
// variables, initial and final measures, and the history (per record: iteration, energy, step,
// epsilon, soft_scale, max_constraint, seconds, the measures, per-term residuals and the time
// split); `extra` adds the problem's or command's own keys (input, output, options, ...).
nlohmann::json ReportJson(const std::string& command, const RunReport& report,
                          const nlohmann::json& extra);

}  // namespace gproj
