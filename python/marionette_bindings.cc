// gproj.marionette_lift and gproj.marionette_fit: `gproj marionette` (002) on numpy arrays,
// through the library's Marionette front end (MakeMarionetteRun) with its inputs in memory.
#include <pybind11/stl.h>

#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "problems/marionette_run.h"
#include "python/conversions.h"
#include "python/module.h"
#include "python/run_bridge.h"

namespace gproj::python {
namespace {

struct MarionetteInputs {
  py::object vertices, faces, fit;
  std::optional<std::string> guides;
};

py::tuple RunMarionette(const MarionetteInputs& in, MarionetteRunOptions options,
                        const py::object& callback) {
  // The argument names stand for the file names in messages; the report has None for them.
  options.plan = "plan";
  options.plan_mesh = MeshFromArrays(in.vertices, in.faces, true);
  if (!in.fit.is_none()) {
    options.fit = "target";
    options.fit_mesh = MeshFromArrays(in.fit, in.faces, true);
  }
  if (in.guides) {
    options.guides = "guides";
    options.guides_text = *in.guides;
  }
  const std::unique_ptr<MarionetteRun> run = MakeMarionetteRun(options);
  RunBridge bridge(callback);
  const RunReport report = bridge.Call([&] { return run->Run(bridge.callback()); });
  nlohmann::json extra = run->Facts();
  extra.update({{"output", nullptr}, {"tolerance", options.lift.tolerance}, {"input", nullptr}});
  if (options.fit_mesh) extra["fit"] = nullptr;
  if (options.guides_text) extra["guides"] = nullptr;
  return py::make_tuple(report.failed ? py::object(py::none()) : VerticesToArray(run->Result()),
                        ReportToPython("marionette", report, extra));
}

py::tuple Lift(const py::object& vertices, const py::object& faces, const std::vector<double>& row,
               const std::vector<double>& column, const std::optional<std::string>& guides,
               const std::string& projection, const std::vector<double>& axis,
               const std::vector<double>& centre, const std::string& solver, double tolerance,
               int max_iterations, const py::object& callback) {
  MarionetteRunOptions options;
  options.row = row;
  options.column = column;
  options.projection = projection;
  options.axis = axis;
  options.centre = centre;
  options.solver = solver;
  options.lift.tolerance = tolerance;
  options.lift.solver.max_iterations = max_iterations;
  return RunMarionette({vertices, faces, py::none(), guides}, options, callback);
}

py::tuple Fit(const py::object& vertices, const py::object& faces, const py::object& target,
              const std::string& solver, double tolerance) {
  MarionetteRunOptions options;
  options.solver = solver;
  options.lift.tolerance = tolerance;
  return RunMarionette({vertices, faces, target, std::nullopt}, options, py::none());
}

const char* const kLiftDoc = R"(marionette_lift(V, F, ...) -> (V_out, report)

Marionette mesh (`gproj marionette`, 002): planar quads over a fixed plan view, every vertex
moving on its own line.

    V: (n, 3) float64 plan view, F: (m, 4) integer quads: a regular grid in `grid` order (with
        row and column) or any disk-like quad mesh (with guides).
    row: guide values of vertices (0, j), j = 0..cols of a grid plan.
    column: guide values of vertices (i, 0), i = 0..rows; column[0] must equal row[0].
    guides: the text of a guide file (see `gproj marionette --help`): 'guide START NEXT V0 V1
        ...' and 'vertex ID VALUE' lines.
    projection: "vertical" (values are heights), "cylindrical" (perpendicular to axis, values
        are distances from it) or "central" (through centre, values are distances from it).
    axis: cylindrical axis [px, py, pz, dx, dy, dz].
    centre: centre of the central projection [x, y, z].
    solver: "direct" (propagation) or "gp" (guided projection).
    tolerance: the planarity to reach (report["converged"]).
    max_iterations: gp with a non-vertical projection: iterations at most.
    callback: as for planarize (guided projection only).

Returns V_out: (n, 3) float64 (None when the run failed) and the report dict.
)";

const char* const kFitDoc = R"(marionette_fit(V, F, target, ...) -> (V_out, report)

Marionette fit (002 eq. 14): the planar-quad mesh over the grid plan (V, F) whose heights fit
those of `target` best in the least-squares sense.

    V: (n, 3) float64 grid plan in `grid` order, F: (m, 4) integer quads.
    target: (n, 3) float64 target mesh with the plan's vertex order (and F).
    solver: "direct" (normal equations) or "gp".
    tolerance: the planarity to reach.

Returns V_out: (n, 3) float64 (None when the run failed) and the report dict.
)";

}  // namespace

void BindMarionette(py::module_& m) {
  const MarionetteRunOptions o;
  m.def("marionette_lift", &Lift, kLiftDoc, py::arg("V"), py::arg("F"), py::kw_only(),
        py::arg("row") = std::vector<double>(), py::arg("column") = std::vector<double>(),
        py::arg("guides") = py::none(), py::arg("projection") = o.projection,
        py::arg("axis") = o.axis, py::arg("centre") = o.centre, py::arg("solver") = o.solver,
        py::arg("tolerance") = o.lift.tolerance,
        py::arg("max_iterations") = o.lift.solver.max_iterations, py::arg("callback") = py::none());
  m.def("marionette_fit", &Fit, kFitDoc, py::arg("V"), py::arg("F"), py::arg("target"),
        py::kw_only(), py::arg("solver") = o.solver, py::arg("tolerance") = o.lift.tolerance);
}

}  // namespace gproj::python
