// gproj.bspline_curvature: H and K of a B-spline given as a dict (the JSON of docs/formats.md) at
// the samples `gproj weingarten` uses (gproj.weingarten comes from the registry).
#include <pybind11/stl.h>

#include <cstdint>
#include <optional>
#include <string>
#include <vector>

#include "gproj/problems/weingarten/weingarten.h"
#include "gproj/problems/weingarten/weingarten_options.h"
#include "python/extension/conversions.h"
#include "python/extension/module.h"
#include "python/extension/run_bridge.h"

namespace gproj::python {
namespace {

// H and K of a B-spline at the centres of an su × sv subdivision of its parameter domain.
py::dict BSplineCurvature(const py::object& surface, const std::vector<int>& samples) {
  const BSplineSurface s = ParseBSplineJson(PythonToJson(surface).dump(), "surface");
  if (!samples.empty() && samples.size() != 2)
    throw InputError("samples must be [NU, NV], got " + std::to_string(samples.size()) + " values");
  const std::int64_t per = weingarten::WeingartenOptions().samples_per_control;
  const std::int64_t su = samples.empty() ? per * s.nu : samples[0];
  const std::int64_t sv = samples.empty() ? per * s.nv : samples[1];
  if (su < 1 || sv < 1 || su * sv > weingarten::kMaxWeingartenSamples)
    throw InputError("samples must be positive with NU x NV <= " +
                     std::to_string(weingarten::kMaxWeingartenSamples) + ", got " +
                     std::to_string(su) + " x " + std::to_string(sv));
  const SampleMaps maps = MakeSampleMaps(s, static_cast<int>(su), static_cast<int>(sv));
  std::vector<double> h, k;
  weingarten::SampleCurvatures(s, maps, &h, &k);
  const std::vector<py::ssize_t> shape = {maps.su, maps.sv};
  py::dict result;
  result["u"] = py::array_t<double>(maps.su, maps.u.data());
  result["v"] = py::array_t<double>(maps.sv, maps.v.data());
  result["H"] = py::array_t<double>(shape, h.data());
  result["K"] = py::array_t<double>(shape, k.data());
  return result;
}

const char* const kCurvatureDoc =
    R"(Mean and Gaussian curvature of a B-spline (exact, from its derivatives) at the samples
`gproj weingarten` uses: the centres of a uniform NU x NV subdivision of the parameter domain.

    surface: the B-spline as a dict (as for weingarten).
    samples: [NU, NV] (default: 2 per control point and direction, weingarten's default).

Returns {"u": (NU,), "v": (NV,), "H": (NU, NV), "K": (NU, NV)} float64 arrays; H[a, b] and
K[a, b] are at (u[a], v[b]), in the surface's units (H = (k1 + k2) / 2, K = k1 k2).
)";

}  // namespace

void BindWeingarten(py::module_& m) {
  m.def("bspline_curvature", &BSplineCurvature, kCurvatureDoc, py::arg("surface"), py::kw_only(),
        py::arg("samples") = std::vector<int>());
}

}  // namespace gproj::python
