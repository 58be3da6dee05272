#pragma once
// Runs a library solve from Python: the GIL is released while the solver works and taken back
// for every iteration record, which goes to the Python callback as a dict (the keys of the
// report's history entries). Returning False from the callback stops the run cleanly; an
// exception in the callback, or Ctrl-C (checked at every record and at every poll of a stage
// without records), stops it and is raised again when the run has returned.

#include <pybind11/pybind11.h>

#include <functional>
#include <memory>
#include <nlohmann/json.hpp>
#include <string>

#include "gproj/problems/run/guided_problem.h"

namespace gproj::python {

namespace py = pybind11;

// A record as the report's history entry (gproj/problems/run/report_json.h), as a dict.
py::dict RecordToPython(const RunRecord& record);
// ReportJson(command, report, extra) as a dict.
py::dict ReportToPython(const std::string& command, const RunReport& report,
                        const nlohmann::json& extra);

class RunBridge {
 public:
  // `callback`: None or callable(record: dict) -> bool | None.
  explicit RunBridge(py::object callback) : callback_(std::move(callback)) {}

  // The callback to hand to the library (called while the GIL is released).
  RunCallback callback() {
    return [this](const RunRecord& record) { return OnRecord(record); };
  }

  // The poll for the stages that send no records (RunContext::stop_requested): true after
  // Ctrl-C or an error in the callback.
  std::function<bool()> stop_poll() {
    return [this] { return StopRequested(); };
  }

  // run() with the GIL released; then raises what the callback raised, or KeyboardInterrupt.
  template <typename Run>
  auto Call(Run run) {
    using Result = decltype(run());
    std::unique_ptr<Result> result;
    {
      py::gil_scoped_release release;
      result = std::make_unique<Result>(run());
    }
    RethrowIfAny();
    return std::move(*result);
  }

  // Takes the GIL; false when the run must stop.
  bool OnRecord(const RunRecord& record);
  // Takes the GIL; true when a signal handler raised (Ctrl-C) or the callback failed.
  bool StopRequested();
  void RethrowIfAny();

 private:
  py::object callback_;
  std::unique_ptr<py::error_already_set> error_;
};

}  // namespace gproj::python
