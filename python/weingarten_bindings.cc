// gproj.weingarten: `gproj weingarten` (003) on a B-spline given as a dict (the JSON of SPEC §4).
#include <pybind11/stl.h>

#include <cstdint>
#include <optional>
#include <string>
#include <vector>

#include "problems/weingarten.h"
#include "python/conversions.h"
#include "python/module.h"
#include "python/run_bridge.h"

namespace gproj::python {
namespace {

// The overrides of a preset, each None for the preset's value (the command line's options).
struct Overrides {
  std::optional<double> alignment, closeness, shape, geodesic_parallel, epsilon, soft_start,
      fairness, definitions, boundary, tolerance;
};

WeingartenSettings Settings(const std::string& preset, const std::string& relation,
                            const std::vector<double>& linear, const std::string& relation_on,
                            const std::string& steps, bool no_auxiliaries, bool allow_folds,
                            const std::vector<int>& samples, std::optional<int> max_iterations,
                            int refine, int molds, const Overrides& o) {
  WeingartenSettings s;
  s.preset = preset;
  s.relation = relation;
  s.linear = linear;
  s.relation_on = relation_on;
  s.steps = steps;
  s.no_auxiliaries = no_auxiliaries;
  s.allow_folds = allow_folds;
  s.samples = samples;
  s.max_iterations = max_iterations;
  s.refine_levels = refine;
  s.molds = molds;
  s.alignment = o.alignment;
  s.closeness = o.closeness;
  s.shape = o.shape;
  s.geodesic_parallel = o.geodesic_parallel;
  s.epsilon = o.epsilon;
  s.soft_start = o.soft_start;
  s.fairness = o.fairness;
  s.definitions = o.definitions;
  s.boundary = o.boundary;
  s.tolerance = o.tolerance;
  return s;
}

py::tuple RunWeingartenFromPython(
    const py::object& surface, const std::string& preset, const std::string& relation,
    const std::vector<double>& linear, const std::string& relation_on, const std::string& steps,
    bool no_auxiliaries, bool allow_folds, const std::vector<int>& samples,
    std::optional<int> max_iterations, int refine, int molds, const std::string& solver,
    const py::object& callback, std::optional<double> alignment, std::optional<double> closeness,
    std::optional<double> shape, std::optional<double> geodesic_parallel,
    std::optional<double> epsilon, std::optional<double> soft_start, std::optional<double> fairness,
    std::optional<double> definitions, std::optional<double> boundary,
    std::optional<double> tolerance) {
  if (solver != "gp" && solver != "ceres")
    throw InputError("solver must be gp or ceres, not '" + solver + "'");
  if (refine < 0 || refine > 4) throw InputError("refine must be in [0, 4]");
  const WeingartenSettings settings =
      Settings(preset, relation, linear, relation_on, steps, no_auxiliaries, allow_folds, samples,
               max_iterations, refine, molds,
               {alignment, closeness, shape, geodesic_parallel, epsilon, soft_start, fairness,
                definitions, boundary, tolerance});
  const WeingartenOptions options = settings.ToOptions();
  const BSplineSurface input = ParseBSplineJson(PythonToJson(surface).dump(), "surface");
  RunBridge bridge(callback);
  const WeingartenRun run = bridge.Call(
      [&] { return RunWeingarten(input, options, solver != "gp", molds, bridge.callback()); });
  nlohmann::json report = WeingartenReportJson(options, run);
  report.update({{"input", nullptr}, {"output", nullptr}, {"preset", preset}});
  const py::object result = run.report.failed
                                ? py::object(py::none())
                                : JsonToPython(nlohmann::json::parse(BSplineToJson(run.result)));
  return py::make_tuple(result, JsonToPython(report));
}

// H and K of a B-spline at the centres of an su × sv subdivision of its parameter domain.
py::dict BSplineCurvature(const py::object& surface, const std::vector<int>& samples) {
  const BSplineSurface s = ParseBSplineJson(PythonToJson(surface).dump(), "surface");
  if (!samples.empty() && samples.size() != 2)
    throw InputError("samples must be [NU, NV], got " + std::to_string(samples.size()) + " values");
  const std::int64_t per = WeingartenOptions().samples_per_control;
  const std::int64_t su = samples.empty() ? per * s.nu : samples[0];
  const std::int64_t sv = samples.empty() ? per * s.nv : samples[1];
  if (su < 1 || sv < 1 || su * sv > kMaxWeingartenSamples)
    throw InputError(
        "samples must be positive with NU x NV <= " + std::to_string(kMaxWeingartenSamples) +
        ", got " + std::to_string(su) + " x " + std::to_string(sv));
  const SampleMaps maps = MakeSampleMaps(s, static_cast<int>(su), static_cast<int>(sv));
  std::vector<double> h, k;
  SampleCurvatures(s, maps, &h, &k);
  const std::vector<py::ssize_t> shape = {maps.su, maps.sv};
  py::dict result;
  result["u"] = py::array_t<double>(maps.su, maps.u.data());
  result["v"] = py::array_t<double>(maps.sv, maps.v.data());
  result["H"] = py::array_t<double>(shape, h.data());
  result["K"] = py::array_t<double>(shape, k.data());
  return result;
}

const char* const kCurvatureDoc = R"(bspline_curvature(surface, samples=None) -> dict

Mean and Gaussian curvature of a B-spline (exact, from its derivatives) at the samples
`gproj weingarten` uses: the centres of a uniform NU x NV subdivision of the parameter domain.

    surface: the B-spline as a dict (as for weingarten).
    samples: [NU, NV] (default: 2 per control point and direction, weingarten's default).

Returns {"u": (NU,), "v": (NV,), "H": (NU, NV), "K": (NU, NV)} float64 arrays; H[a, b] and
K[a, b] are at (u[a], v[b]), in the surface's units (H = (k1 + k2) / 2, K = k1 k2).
)";

const char* const kWeingartenDoc =
    R"(weingarten(surface, preset="fig1", ...) -> (surface_out, report)

Weingarten surface (`gproj weingarten`, 003): moves the control points of a B-spline so that the
isolines of H and K align, keeping it close to the input.

    surface: the B-spline as a dict, the JSON of SPEC §4 (json.load of a `gproj weingarten`
        input): degrees, knot vectors and the control points (numpy arrays are accepted).
    preset: the weights of 003 Table 1 (fig1, fig2b, fig2c, fig2d, fig3, fig4b, fig4c, fig9b,
        fig9c, fig10).
    relation: "" (the preset's), "none", "linear" (fitted each iteration) or "bspline".
    linear: a fixed linear relation [a, b, c]: a H + b K + c = 0 in input units.
    relation_on: "" (the preset's), "surface" or "auxiliaries".
    steps: "" (the preset's), "plain", "monotone" or "projected".
    no_auxiliaries: control points are the only unknowns (only with linear on the surface).
    allow_folds: keep steps that fold the surface (by default refused: neighbouring normals on
        a grid 4x as dense as the samples may not turn by more than 60 degrees).
    samples: [NU, NV] samples (default: 2 per control point and direction).
    max_iterations: guided-projection iterations per level (None: the preset's).
    refine: multiresolution levels (a knot inserted in every span, re-optimised), 0..4.
    molds: cluster the samples into at most this many molds in the (H, sqrt K) plane.
    solver: "gp" or "ceres" (Levenberg-Marquardt on the same rows).
    callback: as for planarize, with every level's records.
    alignment, closeness, shape, geodesic_parallel, epsilon, soft_start, fairness,
        definitions, boundary: override the preset's weights (None: the preset's), as the
        command line's --alignment ... --boundary.
    tolerance: stop when the misalignment (with linear: the max relation residual) <= this
        (None: run the preset's iterations).

Returns the optimised B-spline as a dict (None when the run failed) and the report dict (the
keys of --report).
)";

}  // namespace

void BindWeingarten(py::module_& m) {
  m.def("weingarten", &RunWeingartenFromPython, kWeingartenDoc, py::arg("surface"), py::kw_only(),
        py::arg("preset") = "fig1", py::arg("relation") = "",
        py::arg("linear") = std::vector<double>(), py::arg("relation_on") = "",
        py::arg("steps") = "", py::arg("no_auxiliaries") = false, py::arg("allow_folds") = false,
        py::arg("samples") = std::vector<int>(), py::arg("max_iterations") = py::none(),
        py::arg("refine") = 0, py::arg("molds") = 0, py::arg("solver") = "gp",
        py::arg("callback") = py::none(), py::arg("alignment") = py::none(),
        py::arg("closeness") = py::none(), py::arg("shape") = py::none(),
        py::arg("geodesic_parallel") = py::none(), py::arg("epsilon") = py::none(),
        py::arg("soft_start") = py::none(), py::arg("fairness") = py::none(),
        py::arg("definitions") = py::none(), py::arg("boundary") = py::none(),
        py::arg("tolerance") = py::none());
  m.def("bspline_curvature", &BSplineCurvature, kCurvatureDoc, py::arg("surface"), py::kw_only(),
        py::arg("samples") = std::vector<int>());
}

}  // namespace gproj::python
