// gproj.combescure, gproj.invert, gproj.canal, gproj.cyclidic: the circular-mesh constructions
// of 000 (the commands `gproj combescure`, `gproj invert`, `gproj canal`, `gproj cyclidic`) as
// calls on numpy arrays.
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

py::tuple RunCombescure(const py::object& vertices, const py::object& faces,
                        const std::string& method, const std::optional<std::vector<double>>& row,
                        const std::optional<std::vector<double>>& column, double row_scale,
                        double column_scale, const py::object& origin, double tolerance) {
  if (method != "propagation" && method != "gp")
    throw InputError("method must be propagation or gp, not '" + method + "'");
  CombescureOptions options;
  options.reference_tolerance = tolerance;
  const PolyMesh reference = MeshFromArrays(vertices, faces, true);
  const GridShape shape = DetectGridShape(reference, "mesh");
  CombescureLengths lengths = ReferenceLengths(reference, shape);
  for (double& l : lengths.row) l *= row_scale;
  for (double& l : lengths.column) l *= column_scale;
  if (row) lengths.row = *row;
  if (column) lengths.column = *column;
  if (!origin.is_none()) lengths.origin = Vector3FromPython(origin, "origin");
  Combescure combescure(reference, shape, lengths, options);
  const RunReport report = [&] {
    py::gil_scoped_release release;
    return method == "gp" ? combescure.Run() : combescure.RunPropagation();
  }();
  const nlohmann::json extra = {{"input", nullptr},
                                {"output", nullptr},
                                {"method", method},
                                {"row_lengths", lengths.row},
                                {"column_lengths", lengths.column}};
  return py::make_tuple(VerticesToArray(combescure.Result()),
                        ReportToPython("combescure", report, extra));
}

py::tuple RunInvert(const py::object& vertices, const py::object& faces, const py::object& centre,
                    double ratio, const py::object& m_revolution, double t, int root) {
  const auto start = std::chrono::steady_clock::now();
  if (centre.is_none() == m_revolution.is_none())
    throw InputError("give either centre or m_revolution (4 concyclic points), not both");
  if (!std::isfinite(t) || t <= 0.0) throw InputError("t must be positive and finite");
  if (root != 0 && root != 1) throw InputError("root must be 0 or 1");
  const PolyMesh mesh = MeshFromArrays(vertices, faces, false);
  nlohmann::json extra = {{"input", nullptr}, {"output", nullptr}, {"ratio", ratio}};
  Eigen::Vector3d c;
  if (!centre.is_none()) {
    c = Vector3FromPython(centre, "centre");
  } else {
    const std::vector<Eigen::Vector3d> points = PointsFromArray(m_revolution, "m_revolution");
    if (points.size() != 4)
      throw InputError("m_revolution needs the 4 points P1, P2, P3, P4, got " +
                       std::to_string(points.size()));
    const MRevolutionChoice choice =
        ChooseMRevolutionCentre({points[0], points[1], points[2], points[3]}, t, root, ratio);
    c = choice.centre;
    extra["m_revolution"] = MRevolutionJson(choice, t, root);
  }
  extra["centre"] = {c.x(), c.y(), c.z()};
  const PolyMesh out = InvertMesh(mesh, c, ratio);
  const RunReport report = ConstructionReport(
      "none", MeasureCircularMesh(mesh), MeasureCircularMesh(out), true,
      std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count());
  return py::make_tuple(VerticesToArray(out), ReportToPython("invert", report, extra));
}

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

py::tuple RunCyclidic(const py::object& vertices, const py::object& faces, const py::object& normal,
                      double psi, int segments, int max_iterations, double closure_tolerance,
                      double tangent_tolerance) {
  CyclidicMeshOptions options;
  options.surface.segments = segments;
  options.max_iterations = max_iterations;
  options.closure_tolerance = closure_tolerance;
  if (!normal.is_none()) {
    const Eigen::Vector3d n = Vector3FromPython(normal, "normal");
    if (n.norm() == 0.0) throw InputError("normal must not be zero");
    options.given_frame = true;
    options.angles = AnglesFromNormal(n);
  }
  options.angles.psi = psi;
  const PolyMesh mesh = MeshFromArrays(vertices, faces, true);
  const auto start = std::chrono::steady_clock::now();
  const CyclidicMeshResult result = [&] {
    py::gil_scoped_release release;
    return CyclidicSurfaceOfMesh(mesh, options, "mesh");
  }();
  const RunReport report = CyclidicRunReport(
      result, tangent_tolerance,
      std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count());
  nlohmann::json extra = CyclidicJson(result);
  extra["input"] = nullptr;
  extra["output"] = nullptr;
  return py::make_tuple(MeshToPython(result.surface.mesh),
                        ReportToPython("cyclidic", report, extra));
}

const char* const kCombescureDoc = R"(combescure(V, F, ...) -> (V_out, report)

Combescure transformation (`gproj combescure`, 000 §2.4-2.5): a mesh with every edge parallel
to a planar quad grid's, from the edge lengths along row 0 and column 0.

    V: (n, 3) float64, F: (m, 4) integer quads of a planar grid in `grid` vertex order.
    method: "propagation" (linear time) or "gp" (guided projection, edge-parallelism rows).
    row_lengths: signed lengths of edges (0, j) -> (0, j+1) (default: the reference's times
        row_scale).
    column_lengths: signed lengths of edges (i, 0) -> (i+1, 0) (default: the reference's
        times column_scale).
    row_scale, column_scale: scales of the reference's lengths.
    origin: position (3,) of vertex (0, 0) (default: unchanged).
    tolerance: largest reference planarity accepted (diagonal distance / mean edge).

Returns V_out: (n, 3) float64 and the report dict (the keys of --report).
)";

const char* const kInvertDoc =
    R"(invert(V, F, centre=None, ratio=1.0, m_revolution=None, t=1.0, root=0) -> (V_out, report)

Inversion (Moebius transformation, `gproj invert`, 000 eq. 1): CM' = k / |CM|^2 CM. Circular
meshes stay circular.

    V: (n, 3) float64, F: (m, k) integer faces (or a list of faces).
    centre: (3,) centre of inversion; or
    m_revolution: (4, 3) float64, four concyclic points P1..P4: the centre is then the one
        (000 §5.1, eq. 9) that maps them to an isosceles trapezoid with P1'P2' = t P4'P3', for
        turning a surface of revolution into an M-revolution surface. The report's
        "m_revolution" gives both centres found and the image's side angle and diagonals.
    t: ratio of the trapezoid's parallel sides (> 0).
    root: which of the (up to) two centres to use, 0 or 1.
    ratio: k (non-zero).

Returns V_out: (n, 3) float64 and the report dict.
)";

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

const char* const kCyclidicDoc = R"(cyclidic(V, F, ...) -> ((V_fine, F_fine), report)

Smooth cyclidic surface of a circular quad mesh in grid order (`gproj cyclidic`, 000 §2.1-2.2):
a frame at vertex 0, carried to every vertex by mirror images across the edges, makes it a
cyclidic net; every quad carries a Dupin cyclide patch; the fine mesh follows the curvature
lines and the patches join with common tangent planes.

    V: (n, 3) float64, F: (m, 4) integer quads in `grid` vertex order, every quad circular.
    normal: (3,) normal of the frame at vertex 0 (default: the frame minimising 000 eq. 5).
    psi: turn (radians) of the frame's first tangent about the normal.
    segments: fine quads along every arc.
    max_iterations: BFGS iterations for the frame.
    closure_tolerance: degrees by which frames carried around a face may miss themselves.
    tangent_tolerance: degrees between tangent planes along shared arcs for "converged".

Returns the fine mesh (V: (N, 3) float64, F: (M, 4) int32) and the report dict (the keys of
--report: final has patches, max_tangent_angle_deg, smoothness_energy, ...).
)";

}  // namespace

void BindConstructions(py::module_& m) {
  const CombescureOptions co;
  m.def("combescure", &RunCombescure, kCombescureDoc, py::arg("V"), py::arg("F"), py::kw_only(),
        py::arg("method") = "propagation", py::arg("row_lengths") = py::none(),
        py::arg("column_lengths") = py::none(), py::arg("row_scale") = 1.0,
        py::arg("column_scale") = 1.0, py::arg("origin") = py::none(),
        py::arg("tolerance") = co.reference_tolerance);
  m.def("invert", &RunInvert, kInvertDoc, py::arg("V"), py::arg("F"), py::kw_only(),
        py::arg("centre") = py::none(), py::arg("ratio") = 1.0,
        py::arg("m_revolution") = py::none(), py::arg("t") = 1.0, py::arg("root") = 0);
  const CyclidicMeshOptions cy;
  m.def("cyclidic", &RunCyclidic, kCyclidicDoc, py::arg("V"), py::arg("F"), py::kw_only(),
        py::arg("normal") = py::none(), py::arg("psi") = 0.0,
        py::arg("segments") = cy.surface.segments, py::arg("max_iterations") = cy.max_iterations,
        py::arg("closure_tolerance") = cy.closure_tolerance, py::arg("tangent_tolerance") = 1e-4);
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
