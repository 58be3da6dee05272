#include "python/extension/run_bridge.h"

#include "gproj/problems/run/report_json.h"
#include "python/extension/conversions.h"

namespace gproj::python {

py::dict RecordToPython(const RunRecord& record) {
  RunReport one;
  one.history.push_back(record);
  return JsonToPython(ReportJson("", one, nlohmann::json::object())["history"][0]);
}

py::dict ReportToPython(const std::string& command, const RunReport& report,
                        const nlohmann::json& extra) {
  return JsonToPython(ReportJson(command, report, extra));
}

bool RunBridge::OnRecord(const RunRecord& record) {
  py::gil_scoped_acquire acquire;
  if (error_) return false;
  try {
    if (PyErr_CheckSignals() != 0) throw py::error_already_set();
    if (callback_.is_none()) return true;
    const py::object result = callback_(RecordToPython(record));
    if (result.is_none()) return true;
    const int truth = PyObject_IsTrue(result.ptr());
    if (truth < 0) throw py::error_already_set();
    return truth == 1;
  } catch (py::error_already_set& e) {
    error_ = std::make_unique<py::error_already_set>(std::move(e));
  } catch (const std::exception& e) {
    PyErr_SetString(PyExc_RuntimeError, e.what());
    error_ = std::make_unique<py::error_already_set>();
  }
  return false;
}

bool RunBridge::StopRequested() {
  py::gil_scoped_acquire acquire;
  if (error_) return true;
  if (PyErr_CheckSignals() == 0) return false;
  error_ = std::make_unique<py::error_already_set>();
  return true;
}

void RunBridge::RethrowIfAny() {
  if (!error_) return;
  std::unique_ptr<py::error_already_set> error = std::move(error_);
  throw std::move(*error);
}

}  // namespace gproj::python
