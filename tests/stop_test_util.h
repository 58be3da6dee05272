#pragma once
// Runs a registered problem by the run protocol with a callback that stops it: false at the
// record `stop_at` (1-based; 0: never), as `gproj.<problem>(..., callback=f)` and Ctrl-C do.

#include <set>
#include <string>

#include "gproj/problems/run/registry.h"

namespace gproj {

struct StopCount {
  int records = 0;     // records the callback was called with
  int after_stop = 0;  // of them, after the one it returned false for
};

inline RunResult RunStoppedAt(const std::string& problem, const RunInputs& inputs,
                              const nlohmann::json& options, int stop_at, StopCount* count,
                              const std::set<std::string>& outputs = {"output"}) {
  *count = StopCount();
  RunContext context;
  context.outputs = outputs;
  context.on_record = [stop_at, count](const RunRecord&) {
    const bool stopped = stop_at > 0 && count->records >= stop_at;
    ++count->records;
    if (stopped) ++count->after_stop;
    return stop_at <= 0 || count->records < stop_at;
  };
  return RunProblem(*Registry::Builtin().Find(problem), inputs, options, context);
}

}  // namespace gproj
