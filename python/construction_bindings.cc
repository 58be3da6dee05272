// gproj.canal: the canal surfaces of 000 (the command `gproj canal`) as calls on numpy arrays.
#include <pybind11/stl.h>

#include <chrono>
#include <cmath>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "geometry/mobius.h"
#include "geometry/quad_grid.h"
#include "problems/canal_surface.h"
#include "problems/circular_mesh.h"
#include "problems/closed_canal.h"
#include "problems/combescure.h"
#include "problems/cyclidic_surface.h"
#include "python/conversions.h"
#include "python/module.h"
#include "python/run_bridge.h"

namespace gproj::python {
namespace {

CircularStripInput StripInput(const py::object& curve, const py::object& first_point,
                              const std::optional<std::vector<double>>& lengths, double length) {
  if (lengths && lengths->empty()) throw InputError("lengths needs one value per curve point");
  return MakeCircularStripInput(PointsFromArray(curve, "curve"),
                                Vector3FromPython(first_point, "first_point"),
                                lengths ? *lengths : std::vector<double>{}, length);
}

nlohmann::json CanalExtra(const CanalSurface& canal, int segments) {
  const FrameAngles& a = canal.angles();
  const Eigen::Vector3d n = NormalOf(a);
  nlohmann::json extra = {
      {"curve", nullptr}, {"output", nullptr}, {"lengths", canal.input().lengths}};
  extra["frame"] = {{"lambda", a.lambda}, {"theta", a.theta}, {"psi", a.psi}};
  extra["frame"]["normal"] = {n.x(), n.y(), n.z()};
  for (const NamedValue& v : MeasureCircularMesh(StripMesh(canal.strip())))
    extra["strip"][v.name] = v.value;
  extra["mesh"] = {{"rows", canal.strip().p.size() - 1}, {"segments", segments}};
  return extra;
}

// 000 §4.2: the closed strip, as `gproj canal --closed`.
py::tuple RunClosedCanal(const CircularStripInput& input, const py::object& normal, double psi,
                         int segments, double cospherical_tolerance, double frame_tolerance) {
  ClosedCanalOptions options;
  options.segments = segments;
  options.cospherical_tolerance = cospherical_tolerance;
  options.frame_tolerance_deg = frame_tolerance;
  FrameAngles angles = AnglesFromNormal(normal.is_none() ? DefaultClosedCanalNormal(input)
                                                         : Vector3FromPython(normal, "normal"));
  angles.psi = psi;
  const auto start = std::chrono::steady_clock::now();
  const ClosedCanalSurface c = [&] {
    py::gil_scoped_release release;
    return BuildClosedCanalSurface(input, angles, options);
  }();
  const RunReport report = ClosedCanalRunReport(
      c, options, std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count());
  nlohmann::json extra = ClosedCanalJson(c, options);
  extra["curve"] = nullptr;
  extra["output"] = nullptr;
  return py::make_tuple(MeshToPython(c.mesh), ReportToPython("canal", report, extra));
}

py::tuple RunCanal(const py::object& curve, const py::object& first_point,
                   const std::optional<std::vector<double>>& lengths, double length,
                   const py::object& normal, double psi, int segments, bool smooth,
                   double length_weight, bool fixed_lengths, int max_iterations,
                   const py::object& callback, bool closed, double cospherical_tolerance,
                   double frame_tolerance) {
  if (closed) {
    if (smooth) throw InputError("closed builds a closed circular strip: smooth does not apply");
    if (!normal.is_none() && Vector3FromPython(normal, "normal").norm() == 0.0)
      throw InputError("normal must not be zero");
    return RunClosedCanal(StripInput(curve, first_point, lengths, length), normal, psi, segments,
                          cospherical_tolerance, frame_tolerance);
  }
  CanalSurfaceOptions options;
  options.segments = segments;
  options.smooth = smooth;
  options.smoothing.length_weight = length_weight;
  options.smoothing.optimize_lengths = !fixed_lengths;
  options.smoothing.max_iterations = max_iterations;
  const CircularStripInput input = StripInput(curve, first_point, lengths, length);
  FrameAngles angles =
      AnglesFromNormal(normal.is_none() ? DefaultCanalNormal(BuildCircularStrip(input))
                                        : Vector3FromPython(normal, "normal"));
  angles.psi = psi;
  CanalSurface canal(input, angles, options);
  RunBridge bridge(callback);
  const RunReport report = bridge.Call([&] { return canal.Run(bridge.callback()); });
  return py::make_tuple(MeshToPython(canal.Mesh()),
                        ReportToPython("canal", report, CanalExtra(canal, segments)));
}

const char* const kCanalDoc = R"(canal(curve, first_point, ...) -> ((V, F), report)

Canal surface from a circular strip (`gproj canal`, 000 §3.2-3.3, §4.1), optionally smoothed
(000 eq. 5, Ceres line-search BFGS).

    curve: (n, 3) float64 points P_0..P_{n-1}.
    first_point: (3,) the point fixing the first circle (with P_0 and P_1).
    lengths: |P_k Q_k| per curve point (n,), or length: the same for all.
    normal: (3,) normal of the cyclidic net at P_0 (default: in the first quad's plane, across
        the curve).
    psi: rotation (radians) of the frame's first tangent about the normal.
    segments: quads across the strip in the canal mesh.
    smooth: minimise the smoothness energy of 000 eq. 5 first; length_weight keeps the lengths
        near the input, fixed_lengths smooths over the frame only, max_iterations bounds BFGS.
    callback: as for planarize, with the smoothing's records.
    closed: close the curve by P_{n-1} -> P_0 (`--closed`, 000 §4.2): the closing circle sets
        the last length (and moves Q_0 unless the end circles are co-spherical); the frame is
        closed around the curve where it can be. The report's termination says why a ring
        stays open (then converged is False). cospherical_tolerance and frame_tolerance
        (degrees) as the options of the same names.

Returns the canal mesh (V: (N, 3) float64, F: (M, 4) int32) and the report dict.
)";

}  // namespace

void BindConstructions(py::module_& m) {
  const CanalSurfaceOptions ca;
  const ClosedCanalOptions cl;
  m.def("canal", &RunCanal, kCanalDoc, py::arg("curve"), py::arg("first_point"), py::kw_only(),
        py::arg("lengths") = py::none(), py::arg("length") = 0.0, py::arg("normal") = py::none(),
        py::arg("psi") = 0.0, py::arg("segments") = ca.segments, py::arg("smooth") = false,
        py::arg("length_weight") = ca.smoothing.length_weight, py::arg("fixed_lengths") = false,
        py::arg("max_iterations") = ca.smoothing.max_iterations, py::arg("callback") = py::none(),
        py::arg("closed") = false, py::arg("cospherical_tolerance") = cl.cospherical_tolerance,
        py::arg("frame_tolerance") = cl.frame_tolerance_deg);
}

}  // namespace gproj::python
