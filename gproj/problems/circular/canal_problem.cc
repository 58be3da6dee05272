// `canal` in the registry: canal surfaces meshed by circular quads (000). Four constructions
// behind one command, chosen by what is given: a circular strip on a curve (§3.2–3.3, §4.1),
// optionally smoothed (eq. 5); the same closed around a closed curve (`closed`, §4.2); a C-canal
// surface (`section_scales`, §5.2); or the spheres equidistant from two curves (`second_curve`,
// §4.1, eq. 6). The strip's smooth cyclidic surface (§2.2) is an optional output.
#include <algorithm>
#include <chrono>
#include <cstdio>

#include "gproj/geometry/render/svg_render.h"
#include "gproj/problems/circular/c_canal.h"
#include "gproj/problems/circular/canal_from_curves.h"
#include "gproj/problems/circular/canal_surface.h"
#include "gproj/problems/circular/circular_mesh.h"
#include "gproj/problems/circular/closed_canal.h"
#include "gproj/problems/circular/cyclidic_surface.h"
#include "gproj/problems/mesh/mesh_outputs.h"
#include "gproj/problems/run/builtin_problems.h"
#include "gproj/problems/run/construction.h"
#include "gproj/problems/run/report_json.h"

namespace gproj::circular {
namespace {

struct CanalSettings {
  std::vector<double> first_point, lengths, normal, section_scales, reference_plane;
  double length = 0.0, psi = 0.0;
  bool closed = false, fixed_lengths = false;
  int surface_segments = 0;  // 0: not given (8)
  CanalSurfaceOptions options;
  ClosedCanalOptions closed_options;
};

void AddStripOptions(OptionSchema<CanalSettings>* s) {
  using S = CanalSettings;
  s->Optional<std::vector<double>>(
       "first_point", OptionType::kNumbers,
       "The point that fixes the first circle (with P_0 and P_1)",
       [](S & x) -> auto& { return x.first_point; })
      .Count(3, "X,Y,Z");
  s->Optional<std::vector<double>>(
       "lengths", OptionType::kNumbers, "|P_k Q_k| for every curve point",
       [](S & x) -> auto& { return x.lengths; })
      .Positive();
  s->Custom("length", OptionType::kNumber, "The same |P_k Q_k| for every curve point", nullptr,
            [](const nlohmann::json& v, S* x) { x->length = v.get<double>(); })
      .Positive();
  s->Optional<std::vector<double>>(
       "normal", OptionType::kNumbers,
       "Normal of the cyclidic net at P_0 (not given: in the first quad's plane, across the "
       "curve; with second_curve: the surface normal at P_0, required)",
       [](S & x) -> auto& { return x.normal; })
      .Count(3, "X,Y,Z");
  s->Custom("normal_angle", OptionType::kNumber,
            "The normal at P_0 at this angle to a reference plane (000 §3.3): the given or default "
            "normal is turned onto that cone (the nearest such normal), and smooth keeps it "
            "there, turning it about the plane's normal only",
            nullptr,
            [](const nlohmann::json& v, S* x) {
              x->options.smoothing.cone.enabled = true;
              x->options.smoothing.cone.angle_deg = v.get<double>();
            })
      .Range(-89, 89)
      .Unit("deg");
  s->Optional<std::vector<double>>(
       "reference_plane", OptionType::kNumbers,
       "With normal_angle: the reference plane's normal (not given: 0,0,1, a horizontal plane)",
       [](S & x) -> auto& { return x.reference_plane; })
      .Count(3, "X,Y,Z");
  s->Field<double>("psi", OptionType::kNumber,
                   "Rotation of the frame's first tangent about the normal",
                   [](S& x) -> double& { return x.psi; })
      .Range(-1e3, 1e3)
      .Unit("rad");
  s->Field<int>("segments", OptionType::kInt, "Quads across the strip in the canal mesh",
                [](S& x) -> int& { return x.options.segments; })
      .Range(1, 100000);
}

void AddModeOptions(OptionSchema<CanalSettings>* s) {
  using S = CanalSettings;
  s->Optional<std::vector<double>>(
       "section_scales", OptionType::kNumbers,
       "C-canal surface (000 §5.2): one factor per segment scaling the first arc's edges "
       "into a planar cross-section; the lengths are then the C-canal's",
       [](S & x) -> auto& { return x.section_scales; })
      .Positive();
  s->Field<bool>("closed", OptionType::kBool,
                 "Close the curve by the edge P_n -> P_0 (000 §4.2): the closing circle sets the "
                 "last length (case 1) or also moves Q_0 (case 2); the frame is closed around the "
                 "curve where it can be",
                 [](S& x) -> bool& { return x.closed; });
  s->Field<double>("cospherical_tolerance", OptionType::kNumber,
                   "With closed: the end circles count as co-spherical (case 1) within this "
                   "distance (per mean edge)",
                   [](S& x) -> double& { return x.closed_options.cospherical_tolerance; })
      .NonNegative();
  s->Field<double>("frame_tolerance", OptionType::kNumber,
                   "With closed: the frame closes around the curve when it misses itself by at "
                   "most this",
                   [](S& x) -> double& { return x.closed_options.frame_tolerance_deg; })
      .NonNegative()
      .Unit("deg");
  s->Field<bool>("smooth", OptionType::kBool, "Minimise the smoothness energy of 000 eq. 5",
                 [](S& x) -> bool& { return x.options.smooth; });
  s->Field<double>("length_weight", OptionType::kNumber,
                   "Weight keeping the lengths near the input during smooth",
                   [](S& x) -> double& { return x.options.smoothing.length_weight; })
      .NonNegative();
  s->Field<bool>("fixed_lengths", OptionType::kBool,
                 "With smooth: keep the lengths, smooth over the frame only",
                 [](S& x) -> bool& { return x.fixed_lengths; });
  s->Field<int>("max_iterations", OptionType::kInt, "BFGS iterations at most (smooth, C-canal)",
                [](S& x) -> int& { return x.options.smoothing.max_iterations; })
      .Range(1, 100000);
  s->Custom("surface_segments", OptionType::kInt,
            "Fine quads along every arc of the smooth surface (not given: 8)", nullptr,
            [](const nlohmann::json& v, S* x) { x->surface_segments = v.get<int>(); })
      .Range(1, 1000);
}

const OptionSchema<CanalSettings>& Schema() {
  static const OptionSchema<CanalSettings> schema = [] {
    OptionSchema<CanalSettings> s;
    AddStripOptions(&s);
    AddModeOptions(&s);
    return s;
  }();
  return schema;
}

Eigen::Vector3d Point(const std::vector<double>& p) { return {p[0], p[1], p[2]}; }

// The normal asked for, or `fallback` when none was given.
Eigen::Vector3d NormalOrDefault(const CanalSettings& s,
                                const std::function<Eigen::Vector3d()>& fallback) {
  if (s.normal.empty()) return fallback();
  const Eigen::Vector3d n = Point(s.normal);
  if (n.norm() == 0.0) throw InputError("`normal` must not be zero");
  return n;
}

CircularStripInput StripInput(const RunInputs& inputs, const CanalSettings& s) {
  return MakeCircularStripInput(inputs.Curve("curve"), Point(s.first_point), s.lengths, s.length);
}

void NeedPoints(const RunInputs& inputs, const std::string& name, size_t count) {
  const size_t n = inputs.Curve(name).size();
  if (n < count)
    throw InputError(inputs.Source(name) + ": needs at least " + std::to_string(count) +
                     " points, got " + std::to_string(n));
}

// Marks the run not converged, with the reason, when the canal mesh has crossed quads or the
// smooth surface (when made) is not usable.
void CheckCanalResult(const NamedValues& mesh_measures, const CyclidicSurface* surface,
                      RunReport* report, const char* hint = kCrossedQuadsHint) {
  std::string fault = CrossedQuadsFault(mesh_measures, hint);
  if (fault.empty() && surface != nullptr) fault = CyclidicSurfaceFault(surface->measures, 1e-4);
  if (fault.empty()) return;
  report->converged = false;
  report->termination = fault;
}

// The smooth cyclidic surface of the canal's net (000 §2.2) when `surface` or
// `surface_picture` asks for it; null otherwise.
std::unique_ptr<CyclidicSurface> SmoothSurface(const CanalSettings& s, const RunContext& context,
                                               const CyclidicStrip& net, bool closed) {
  if (!context.Wants("surface") && !context.Wants("surface_picture")) return nullptr;
  CyclidicSurfaceOptions options;
  options.segments = s.surface_segments > 0 ? s.surface_segments : 8;
  options.weld_closed = closed;
  return std::make_unique<CyclidicSurface>(MeshCyclidicSurface(CyclidicNetOfStrip(net), options));
}

// The smooth surface's line, report keys and outputs.
void AddSmoothSurface(const CyclidicSurface* surface, const RunContext& context,
                      RunResult* result) {
  if (surface == nullptr) return;
  const NamedValues& m = surface->measures;
  char line[256];
  std::snprintf(line, sizeof(line),
                "smooth cyclidic surface (000 §2.2): %g Dupin cyclide patches, %zu fine quads; "
                "tangent planes across the patches' shared arcs agree to %.1e deg",
                ValueOf(m, "patches"), surface->mesh.n_faces(),
                ValueOf(m, "max_tangent_angle_deg"));
  result->Info(line);
  for (const NamedValue& v : m) result->facts["surface"][v.name] = v.value;
  result->facts["surface"]["welded"] = surface->welded;
  if (context.Wants("surface")) result->meshes["surface"] = surface->mesh;
  std::snprintf(line, sizeof(line), "Smooth cyclidic surface (000 §2.2), %g Dupin cyclide patches",
                ValueOf(m, "patches"));
  AddMeshPicture(context, "surface_picture", surface->mesh, line, result);
}

// 000 §4.1 from two curves: spheres equidistant from the line of curvature and the second
// curve (eq. 6), their circles, the circular mesh between them.
RunResult RunFromCurves(const RunInputs& inputs, const CanalSettings& s,
                        const RunContext& context) {
  NeedPoints(inputs, "curve", 3);
  const std::vector<Eigen::Vector3d>& curve1 = inputs.Curve("curve");
  const std::vector<Eigen::Vector3d>& curve2 = inputs.Curve("second_curve");
  char line[512];
  std::snprintf(line, sizeof(line),
                "%s (line of curvature, %zu points) and %s (%zu points): spheres equidistant "
                "from both (000 eq. 6, Newton)",
                inputs.Source("curve").c_str(), curve1.size(),
                inputs.Source("second_curve").c_str(), curve2.size());
  context.Headline(line);
  CanalFromCurvesOptions options;
  options.segments = s.options.segments;
  const Construction construction(ConstructionMethod::kClosedForm, "spheres from two curves");
  const CanalFromCurves canal = FitCanalToCurves(curve1, curve2, Point(s.normal), options);
  RunResult result;
  result.report = construction.Finish({}, canal.measures, true);
  CheckCanalResult(canal.measures, nullptr, &result.report,
                   "the plane steps between the circles pass each other; fewer `segments` or a "
                   "finer line of curvature");
  const NamedValues& m = canal.measures;
  std::snprintf(line, sizeof(line),
                "%zu spheres: radius %.4g .. %.4g; max |R_k - dist(C_k, curve "
                "2)| %.3e",
                canal.radii.size(), *std::min_element(canal.radii.begin(), canal.radii.end()),
                *std::max_element(canal.radii.begin(), canal.radii.end()),
                ValueOf(m, "max_sphere_fit"));
  result.Info(line);
  std::snprintf(line, sizeof(line),
                "%zu circles S_k & S_k+1; they pass curve 1 within %.3g and curve 2's contact "
                "points within %.3g",
                canal.circles.size(), ValueOf(m, "max_curve1_distance"),
                ValueOf(m, "max_curve2_distance"));
  result.Info(line);
  result.Info(CircularMeasuresLine("canal mesh", m));
  result.facts = nlohmann::json::object();
  for (size_t k = 0; k < canal.radii.size(); ++k) {
    const Eigen::Vector3d& c = canal.centres[k];
    result.facts["spheres"].push_back({{"centre", {c.x(), c.y(), c.z()}},
                                       {"radius", canal.radii[k]},
                                       {"fit_residual", canal.fit_residuals[k]}});
  }
  result.facts["mesh"] = {{"circles", canal.circles.size()}, {"segments", s.options.segments}};
  result.meshes["output"] = canal.mesh;
  std::snprintf(line, sizeof(line), "Canal surface from two curves, %zu circular quads",
                canal.mesh.n_faces());
  AddMeshPicture(context, "picture", canal.mesh, line, &result);
  return result;
}

// 000 §5.2: the C-canal surface of the lengths, its cross-section the first arc scaled by
// `section_scales`; the canal's lengths found by BFGS (eq. 10).
RunResult RunCCanal(const RunInputs& inputs, const CanalSettings& s, const RunContext& context) {
  const CircularStripInput input = StripInput(inputs, s);
  FrameAngles angles = AnglesFromNormal(
      NormalOrDefault(s, [&] { return DefaultCanalNormal(BuildCircularStrip(input)); }));
  angles.psi = s.psi;
  char line[512];
  std::snprintf(line, sizeof(line),
                "%s: C-canal surface (000 §5.2): %zu curve points, cross-section of %d segments; "
                "BFGS on the canal's lengths until the C-canal's are the asked ones (eq. 10)",
                inputs.Source("curve").c_str(), input.curve.size(), s.options.segments);
  context.Headline(line);
  CCanalOptions options;
  options.segments = s.options.segments;
  options.section_scales = s.section_scales;
  options.max_iterations = s.options.smoothing.max_iterations;
  const Construction construction(ConstructionMethod::kBfgs, "C-canal lengths");
  const CCanalSurface c = BuildCCanalSurface(input, angles, options);
  NamedValues measures = MeasureCircularMesh(c.mesh);
  measures.push_back({"max_length_error", c.max_length_error});
  RunResult result;
  result.report =
      construction.Finish({{"max_length_error", c.initial_length_error}}, measures, c.converged);
  result.report.iterations = c.iterations;
  result.report.termination = "ceres-bfgs: " + c.message;
  CheckCanalResult(measures, nullptr, &result.report);
  result.tolerance_measure = "max_length_error";
  result.tolerance = options.length_tolerance;
  std::snprintf(line, sizeof(line),
                "|P_k Q'_k| against the asked lengths: %.3e -> %.3e (of the mean length) in %d "
                "iterations",
                c.initial_length_error, c.max_length_error, c.iterations);
  result.Info(line);
  result.Info(CircularMeasuresLine("C-canal mesh", result.report.final));
  result.facts = {{"lengths", c.lengths},
                  {"canal_lengths", c.canal_lengths},
                  {"section_scales", s.section_scales}};
  result.meshes["output"] = c.mesh;
  std::snprintf(line, sizeof(line), "C-canal surface (000 §5.2), %zu circular quads",
                c.mesh.n_faces());
  AddMeshPicture(context, "picture", c.mesh, line, &result);
  return result;
}

// The closing case and the frame's closure, as lines.
void DescribeClosedCanal(const ClosedCanalSurface& c, const CanalSettings& s, RunResult* result) {
  const NamedValues& m = c.measures;
  const int count = static_cast<int>(c.closed.strip.p.size());
  char line[512];
  if (c.closed.closing_case == 1)
    std::snprintf(line, sizeof(line),
                  "case 1: the circles of quads 0 and %d are co-spherical (to %.1e); the closing "
                  "circle passes Q_0 as asked and sets |P_%d Q_%d| = %.6g",
                  count - 2, c.closed.cosphericity, count - 1, count - 1,
                  ValueOf(m, "last_length"));
  else
    std::snprintf(line, sizeof(line),
                  "case 2: the circles of quads 0 and %d are not co-spherical (%.3g); the closing "
                  "circle (the spheres' intersection) moves Q_0 by %.6g and sets |P_%d Q_%d| = "
                  "%.6g",
                  count - 2, c.closed.cosphericity, c.closed.start_shift, count - 1, count - 1,
                  ValueOf(m, "last_length"));
  result->Info(line);
  result->Info(
      CircularMeasuresLine("closed strip", MeasureCircularMesh(ClosedStripMesh(c.closed.strip))));
  if (c.frame_closes)
    std::snprintf(line, sizeof(line),
                  "frame closes around the curve (%.1e deg; turned %.4g deg from the asked one)",
                  ValueOf(m, "frame_closure_deg"), ValueOf(m, "frame_rotation_deg"));
  else if (ValueOf(m, "frame_closure_deg") < 0.1)
    std::snprintf(line, sizeof(line),
                  "the frame comes back %.3g deg off after the loop, more than `frame_tolerance` "
                  "%.1e: is the curve a rounded pseudo-spherical one? A looser `frame_tolerance` "
                  "closes it; the canal mesh is left open at P_0",
                  ValueOf(m, "frame_closure_deg"), s.closed_options.frame_tolerance_deg);
  else
    std::snprintf(line, sizeof(line),
                  "the reflections along the curve turn every frame (%.4g deg for this one): no "
                  "smooth closed cyclidic net on this curve (000 §4.2 needs a pseudo-spherical "
                  "curve); the canal mesh is left open at P_0",
                  ValueOf(m, "frame_closure_deg"));
  result->Info(line);
  std::snprintf(line, sizeof(line), "canal mesh: %zu quads, %s (seam gap %.1e of the mean edge)",
                c.mesh.n_faces(), c.welded ? "a closed ring" : "open at P_0",
                ValueOf(m, "seam_gap"));
  result->Info(line);
  result->Info(CircularMeasuresLine("canal mesh", m));
}

// 000 §4.2: the strip closed by the closing circle (case 1 keeps the first point, case 2 moves
// Q_0), the frame closed around the loop where the curve allows, the canal mesh as a ring.
RunResult RunClosed(const RunInputs& inputs, const CanalSettings& s, const RunContext& context) {
  NeedPoints(inputs, "curve", 3);
  const CircularStripInput input = StripInput(inputs, s);
  char line[512];
  std::snprintf(line, sizeof(line),
                "%s: closed strip of %zu quads (000 §4.2); the closing circle sets Q_%zu (and Q_0 "
                "unless the end circles are co-spherical)",
                inputs.Source("curve").c_str(), input.curve.size(), input.curve.size() - 1);
  context.Headline(line);
  const Construction construction(ConstructionMethod::kClosedForm, "closing circle");
  FrameAngles angles =
      AnglesFromNormal(NormalOrDefault(s, [&] { return DefaultClosedCanalNormal(input); }));
  angles.psi = s.psi;
  ClosedCanalOptions options = s.closed_options;
  options.segments = s.options.segments;
  const ClosedCanalSurface c = BuildClosedCanalSurface(input, angles, options);
  const std::unique_ptr<CyclidicSurface> smooth = SmoothSurface(s, context, c.net, c.welded);
  RunResult result;
  result.report = ClosedCanalRunReport(c, options, construction);
  if (result.report.converged && smooth) CheckCanalResult(c.measures, smooth.get(), &result.report);
  DescribeClosedCanal(c, s, &result);
  result.facts = ClosedCanalJson(c, options);
  AddSmoothSurface(smooth.get(), context, &result);
  result.meshes["output"] = c.mesh;
  if (context.Wants("strip")) result.meshes["strip"] = ClosedStripMesh(c.closed.strip);
  std::snprintf(line, sizeof(line), "Closed canal surface (000 §4.2, case %d), %zu circular quads",
                c.closed.closing_case, c.mesh.n_faces());
  AddMeshPicture(context, "picture", c.mesh, line, &result);
  return result;
}

// 000 §3.2–3.3: the circular strip, its cyclidic net, the optional smoothing (eq. 5), the mesh.
RunResult RunStrip(const RunInputs& inputs, const CanalSettings& s, const RunContext& context) {
  const CircularStripInput input = StripInput(inputs, s);
  FrameAngles angles = AnglesFromNormal(
      NormalOrDefault(s, [&] { return DefaultCanalNormal(BuildCircularStrip(input)); }));
  angles.psi = s.psi;
  CanalSurfaceOptions options = s.options;
  options.smoothing.optimize_lengths = !s.fixed_lengths;
  NormalCone& cone = options.smoothing.cone;
  if (!s.reference_plane.empty()) {
    cone.axis = Point(s.reference_plane);
    const double largest = cone.axis.cwiseAbs().maxCoeff();
    if (!(largest > 0.0)) throw InputError("`reference_plane` must not be zero");
    cone.axis = (cone.axis / largest).normalized();
  }
  // No normal asked for: the smoothing on the cone starts from the free smoothing's normal
  // moved onto the cone (the default normal's nearest one on it may lie in a poor basin).
  const FrameAngles asked = angles;
  const bool scanned = cone.enabled && options.smooth && s.normal.empty();
  if (scanned) {
    CanalSmoothingOptions free = options.smoothing;
    free.cone.enabled = false;
    const CanalSmoothingSummary unconstrained = SmoothCanalStrip(input, angles, free);
    if (unconstrained.converged) angles = unconstrained.angles;
  }
  CanalSurface canal(input, angles, options);
  char line[512];
  std::snprintf(line, sizeof(line),
                "%s: %zu curve points, %zu strip quads; first point (%g, %g, %g)",
                inputs.Source("curve").c_str(), input.curve.size(), input.curve.size() - 1,
                input.first_point.x(), input.first_point.y(), input.first_point.z());
  context.Headline(line);
  if (cone.enabled) {
    std::snprintf(line, sizeof(line),
                  "the normal at P_0 at %g deg to the plane of normal (%g, %g, %g) (000 §3.3): "
                  "turned %.3g deg onto that cone%s",
                  cone.angle_deg, cone.axis.x(), cone.axis.y(), cone.axis.z(),
                  std::acos(std::clamp(NormalOf(asked).dot(NormalOf(canal.angles())), -1.0, 1.0)) *
                      180.0 / M_PI,
                  scanned ? "; the smoothing starts from the free smoothing's normal moved onto "
                            "the cone and turns it about the plane's normal only"
                  : options.smooth ? "; the smoothing turns it about the plane's normal only"
                                   : "");
    context.Info(line);
  }
  if (options.smooth) context.Info("shape smoothing (000 eq. 5), Ceres line-search BFGS");
  RunResult result;
  result.report = canal.Run([&context](const RunRecord& r) { return context.Record(r); });
  const PolyMesh mesh = canal.Mesh();
  const std::unique_ptr<CyclidicSurface> smooth = SmoothSurface(s, context, canal.Net(), false);
  if (result.report.converged) CheckCanalResult(result.report.final, smooth.get(), &result.report);
  const PolyMesh strip_mesh = StripMesh(canal.strip());
  const NamedValues strip = MeasureCircularMesh(strip_mesh);
  std::snprintf(line, sizeof(line), "F: %.6g -> %.6g",
                ValueOf(result.report.initial, "smoothness_energy"),
                ValueOf(result.report.final, "smoothness_energy"));
  result.Info(line);
  result.Info(CircularMeasuresLine("strip", strip));
  result.Info(CircularMeasuresLine("canal mesh", result.report.final));
  const FrameAngles& a = canal.angles();
  const Eigen::Vector3d n = NormalOf(a);
  result.facts = {{"lengths", canal.input().lengths}};
  result.facts["frame"] = {{"lambda", a.lambda}, {"theta", a.theta}, {"psi", a.psi}};
  result.facts["frame"]["normal"] = {n.x(), n.y(), n.z()};
  if (cone.enabled) {
    result.facts["frame"]["normal_angle_deg"] = cone.AngleOf(n);
    result.facts["frame"]["reference_plane"] = {cone.axis.x(), cone.axis.y(), cone.axis.z()};
  }
  result.facts["strip"] = MeasuresJson(strip);
  result.facts["mesh"] = {{"rows", canal.strip().p.size() - 1}, {"segments", options.segments}};
  AddSmoothSurface(smooth.get(), context, &result);
  result.meshes["output"] = mesh;
  if (context.Wants("strip")) result.meshes["strip"] = strip_mesh;
  std::snprintf(line, sizeof(line), "Canal surface, %zu circular quads, max concyclicity %.1e",
                mesh.n_faces(), ValueOf(result.report.final, "max_concyclicity"));
  AddMeshPicture(context, "picture", mesh, line, &result);
  return result;
}

// Options and outputs that do not belong to the construction asked for; empty when none.
std::string Misuse(const RunInputs& inputs, const CanalSettings& s, const RunContext& context) {
  const CanalSettings d;
  const bool surface = context.Wants("surface") || context.Wants("surface_picture");
  const bool cone = s.options.smoothing.cone.enabled;
  if (!s.reference_plane.empty() && !cone) return "`reference_plane` needs `normal_angle`";
  if (cone && (s.closed || !s.section_scales.empty() || inputs.Has("second_curve")))
    return "`normal_angle` constrains the frame of a circular strip (000 §3.3): `closed`, "
           "`section_scales` and `second_curve` do not apply";
  if (s.surface_segments > 0 && !surface)
    return "`surface_segments` needs `surface` or `surface_picture`";
  if (!s.closed &&
      (s.closed_options.cospherical_tolerance != d.closed_options.cospherical_tolerance ||
       s.closed_options.frame_tolerance_deg != d.closed_options.frame_tolerance_deg))
    return "`cospherical_tolerance` and `frame_tolerance` belong to `closed`";
  if (s.closed && (inputs.Has("second_curve") || !s.section_scales.empty() || s.options.smooth))
    return "`closed` builds a closed circular strip: `second_curve`, `section_scales` and "
           "`smooth` do not apply";
  if (!s.section_scales.empty() &&
      (inputs.Has("second_curve") || s.options.smooth || surface || context.Wants("strip")))
    return "`section_scales` builds a C-canal surface from a circular strip: `second_curve`, "
           "`smooth`, `strip`, `surface` and `surface_picture` do not apply";
  if (!inputs.Has("second_curve")) {
    if (s.fixed_lengths && !s.options.smooth)
      return "`fixed_lengths` needs `smooth` (it keeps the lengths while the frame is smoothed)";
    if (s.first_point.empty())
      return "`first_point` x,y,z is needed (or `second_curve` with `normal`)";
    return "";
  }
  const CanalSmoothingOptions& smoothing = s.options.smoothing;
  if (context.Wants("strip") || s.options.smooth || !s.first_point.empty() || !s.lengths.empty() ||
      s.length != 0.0 || s.psi != 0.0 || s.fixed_lengths ||
      smoothing.max_iterations != d.options.smoothing.max_iterations ||
      smoothing.length_weight != d.options.smoothing.length_weight)
    return "`second_curve` builds the spheres from the two curves: `strip`, `smooth`, "
           "`first_point`, `length`, `lengths`, `psi`, `fixed_lengths`, `max_iterations` and "
           "`length_weight` belong to the circular-strip construction";
  if (s.normal.empty()) return "`second_curve` needs `normal` x,y,z, the surface normal at P_0";
  if (surface)
    return "`surface` and `surface_picture` need a circular strip's cyclidic net, not "
           "`second_curve` (the cyclidic command makes the smooth surface of its mesh)";
  return "";
}

RunResult Run(const RunInputs& inputs, const nlohmann::json& values, const RunContext& context) {
  const CanalSettings s = Schema().Apply(values);
  if (const std::string misuse = Misuse(inputs, s, context); !misuse.empty())
    throw InputError(misuse);
  if (s.closed) return RunClosed(inputs, s, context);
  if (!s.section_scales.empty()) return RunCCanal(inputs, s, context);
  if (inputs.Has("second_curve")) return RunFromCurves(inputs, s, context);
  return RunStrip(inputs, s, context);
}

}  // namespace

ProblemSpec CanalSpec() {
  ProblemSpec spec;
  spec.name = "canal";
  spec.summary =
      "Canal surface from a circular strip (000 §3.2-3.3, §4.1): points P_k on a curve, a first "
      "point fixing the first circle and the lengths |P_k Q_k| give a strip of circular quads by "
      "propagation; a frame at P_0 makes it a cyclidic net whose crossing arcs are the canal "
      "surface's circles; the surface is meshed by circular quads between them. smooth "
      "minimises 000 eq. 5 (Ceres line-search BFGS); closed closes the strip around a closed "
      "curve (§4.2); section_scales makes a C-canal surface (§5.2). With second_curve and "
      "normal instead: spheres equidistant from the curve and a second curve (§4.1, eq. 6), "
      "meshed by circular quads between their circles.";
  spec.inputs = {
      {"curve", InputKind::kCurve, "Curve points P_0..P_n", true},
      {"second_curve", InputKind::kCurve,
       "Fit the canal surface to this second curve instead (000 §4.1): the curve is then a line "
       "of curvature and normal the surface normal at P_0"}};
  spec.outputs = {
      {"output", OutputKind::kMesh, "the canal mesh (circular quads)", true},
      {"strip", OutputKind::kMesh, "the circular strip (2 x (n+1) vertices)"},
      {"surface", OutputKind::kMesh,
       "the smooth cyclidic surface (000 §2.2): a Dupin cyclide patch on every quad of the "
       "strip's cyclidic net, meshed along its curvature lines"},
      {"surface_picture", OutputKind::kSvg, "a shaded picture of the smooth cyclidic surface"},
      {"picture", OutputKind::kSvg, "a shaded picture of the canal mesh"}};
  spec.options = Schema().specs();
  spec.log_measures = {"smoothness_energy"};
  spec.run = Run;
  return spec;
}

}  // namespace gproj::circular
