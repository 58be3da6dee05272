// `gproj canal`: a canal surface meshed by circular quads from a circular strip on a curve
// (000 §3.2–3.3, §4.1), optionally smoothed (000 eq. 5).
#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <iostream>
#include <memory>
#include <string>
#include <vector>

#include "apps/super_canal_commands.h"
#include "geometry/text_input.h"
#include "problems/c_canal.h"
#include "problems/canal_from_curves.h"
#include "problems/canal_surface.h"
#include "problems/circular_mesh.h"
#include "problems/closed_canal.h"
#include "problems/cyclidic_surface.h"

namespace gproj {
namespace {

struct CanalArgs {
  std::string curve, strip, second_curve, surface, surface_picture;
  int surface_segments = 0;  // 0: 8
  ClosedCanalOptions closed_options;
  MeshOutputs outputs;
  std::vector<double> first_point, lengths, normal, section_scales;
  double length = 0.0, psi = 0.0;
  bool closed = false;
  CanalSurfaceOptions options;
};

// The canal surface of the options; its frame's normal is --normal or the default.
std::unique_ptr<CanalSurface> CanalFromArgs(const CanalArgs& args) {
  args.outputs.Check({{"curve", args.curve}},
                     {{"--strip", args.strip, true},
                      {"--surface", args.surface, true},
                      {"--surface-picture", args.surface_picture, false, ".svg"}});
  if (args.first_point.empty())
    throw InputError("--first-point x,y,z is needed (or --second-curve with --normal)");
  const CircularStripInput input =
      MakeCircularStripInput(ReadPoints(args.curve), Vector3(args.first_point, "--first-point"),
                             args.lengths, args.length);
  const Eigen::Vector3d normal = args.normal.empty() ? DefaultCanalNormal(BuildCircularStrip(input))
                                                     : Vector3(args.normal, "--normal");
  if (normal.norm() == 0.0) throw InputError("--normal must not be zero");
  FrameAngles angles = AnglesFromNormal(normal);
  angles.psi = args.psi;
  return std::make_unique<CanalSurface>(input, angles, args.options);
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

ExtraMeshes Joined(ExtraMeshes a, const ExtraMeshes& b) {
  a.insert(a.end(), b.begin(), b.end());
  return a;
}

// The smooth cyclidic surface of the canal's net (000 §2.2) when --surface asks for it; its
// measures go to the report's "surface".
struct SmoothSurface {
  CyclidicSurface surface;
  bool made = false;
  // Its outputs: the fine mesh (--surface) and its picture (--surface-picture).
  ExtraMeshes Outputs(const CanalArgs& args) const {
    char title[160];
    std::snprintf(title, sizeof(title),
                  "Smooth cyclidic surface (000 §2.2), %g Dupin cyclide patches",
                  made ? ValueOf(surface.measures, "patches") : 0.0);
    return {{args.surface, &surface.mesh}, {args.surface_picture, &surface.mesh, title}};
  }
};
SmoothSurface MakeSmoothSurface(const CanalArgs& args, const CyclidicStrip& net, bool closed) {
  SmoothSurface s;
  if (args.surface.empty() && args.surface_picture.empty()) return s;
  CyclidicSurfaceOptions options;
  options.segments = args.surface_segments > 0 ? args.surface_segments : 8;
  options.weld_closed = closed;
  s.surface = MeshCyclidicSurface(CyclidicNetOfStrip(net), options);
  s.made = true;
  return s;
}
void PrintSmoothSurface(const SmoothSurface& s, nlohmann::json* extra) {
  if (!s.made) return;
  const NamedValues& m = s.surface.measures;
  std::printf(
      "smooth cyclidic surface (000 §2.2): %g Dupin cyclide patches, %zu fine quads; tangent "
      "planes across the patches' shared arcs agree to %.1e deg\n",
      ValueOf(m, "patches"), s.surface.mesh.n_faces(), ValueOf(m, "max_tangent_angle_deg"));
  for (const NamedValue& v : m) (*extra)["surface"][v.name] = v.value;
  (*extra)["surface"]["welded"] = s.surface.welded;
}

// 000 §4.1 from two curves: spheres equidistant from the line of curvature and the second
// curve (eq. 6), their circles, the circular mesh between them.
int RunCanalFromCurves(const CanalArgs& args) {
  CanalFromCurves canal;
  RunReport report;
  try {
    args.outputs.Check({{"curve", args.curve}, {"--second-curve", args.second_curve}});
    const CanalSmoothingOptions defaults;
    const CanalSmoothingOptions& smoothing = args.options.smoothing;
    if (!args.strip.empty() || args.options.smooth || !args.first_point.empty() ||
        !args.lengths.empty() || args.length != 0.0 || args.psi != 0.0 ||
        smoothing.optimize_lengths != defaults.optimize_lengths ||
        smoothing.max_iterations != defaults.max_iterations ||
        smoothing.length_weight != defaults.length_weight)
      throw InputError(
          "--second-curve builds the spheres from the two curves: --strip, --smooth, "
          "--first-point, --length(s), --psi, --fixed-lengths, --max-iterations and "
          "--length-weight belong to the circular-strip construction");
    if (args.normal.empty())
      throw InputError("--second-curve needs --normal x,y,z, the surface normal at P_0");
    if (!args.surface.empty() || !args.surface_picture.empty())
      throw InputError(
          "--surface and --surface-picture need a circular strip's cyclidic net, not "
          "--second-curve (gproj cyclidic makes the smooth surface of its mesh)");
    const std::vector<Eigen::Vector3d> curve1 = ReadPoints(args.curve, 3);
    const std::vector<Eigen::Vector3d> curve2 = ReadPoints(args.second_curve, 2);
    std::printf(
        "gproj canal: %s (line of curvature, %zu points) and %s (%zu points): spheres "
        "equidistant from both (000 eq. 6, Newton)\n",
        args.curve.c_str(), curve1.size(), args.second_curve.c_str(), curve2.size());
    CanalFromCurvesOptions options;
    options.segments = args.options.segments;
    const auto start = std::chrono::steady_clock::now();
    canal = FitCanalToCurves(curve1, curve2, Vector3(args.normal, "--normal"), options);
    const double seconds =
        std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    report = ConstructionReport("spheres from two curves", {}, canal.measures, true, seconds);
    CheckCanalResult(canal.measures, nullptr, &report,
                     "the plane steps between the circles pass each other; fewer --segments or a "
                     "finer line of curvature");
  } catch (const InputError& e) {
    std::cerr << "gproj canal: " << e.what() << "\n";
    return kExitInputError;
  }
  const NamedValues& m = canal.measures;
  std::printf("%zu spheres: radius %.4g .. %.4g; max |R_k - dist(C_k, curve 2)| %.3e\n",
              canal.radii.size(), *std::min_element(canal.radii.begin(), canal.radii.end()),
              *std::max_element(canal.radii.begin(), canal.radii.end()),
              ValueOf(m, "max_sphere_fit"));
  std::printf(
      "%zu circles S_k & S_k+1; they pass curve 1 within %.3g and curve 2's contact "
      "points within %.3g\n",
      canal.circles.size(), ValueOf(m, "max_curve1_distance"), ValueOf(m, "max_curve2_distance"));
  PrintMeasures("canal mesh", m);
  nlohmann::json extra = {{"curve", args.curve}, {"second_curve", args.second_curve}};
  for (size_t k = 0; k < canal.radii.size(); ++k) {
    extra["spheres"].push_back(
        {{"centre", {canal.centres[k].x(), canal.centres[k].y(), canal.centres[k].z()}},
         {"radius", canal.radii[k]},
         {"fit_residual", canal.fit_residuals[k]}});
  }
  extra["mesh"] = {{"circles", canal.circles.size()}, {"segments", args.options.segments}};
  char title[160];
  std::snprintf(title, sizeof(title), "Canal surface from two curves, %zu circular quads",
                canal.mesh.n_faces());
  return WriteAndConclude("canal", report, canal.mesh, title, args.outputs, extra, "", 0.0);
}

// 000 §5.2: the C-canal surface of the lengths, its cross-section the first arc scaled by
// --section-scales; the canal's lengths found by BFGS (eq. 10).
int RunCCanal(const CanalArgs& args) {
  CCanalSurface c;
  RunReport report;
  try {
    if (!args.second_curve.empty() || args.options.smooth || !args.surface.empty() ||
        !args.surface_picture.empty())
      throw InputError(
          "--section-scales builds a C-canal surface from a circular strip: "
          "--second-curve, --smooth, --surface and --surface-picture do not apply");
    const std::unique_ptr<CanalSurface> canal = CanalFromArgs(args);
    std::printf(
        "gproj canal: %s: C-canal surface (000 §5.2): %zu curve points, cross-section of %d "
        "segments; BFGS on the canal's lengths until the C-canal's are the asked ones (eq. 10)\n",
        args.curve.c_str(), canal->input().curve.size(), args.options.segments);
    CCanalOptions options;
    options.segments = args.options.segments;
    options.section_scales = args.section_scales;
    options.max_iterations = args.options.smoothing.max_iterations;
    const auto start = std::chrono::steady_clock::now();
    c = BuildCCanalSurface(canal->input(), canal->angles(), options);
    NamedValues measures = MeasureCircularMesh(c.mesh);
    measures.push_back({"max_length_error", c.max_length_error});
    report = ConstructionReport(
        "ceres-bfgs", {{"max_length_error", c.initial_length_error}}, measures, c.converged,
        std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count());
    report.iterations = c.iterations;
    report.termination = "ceres-bfgs: " + c.message;
    CheckCanalResult(measures, nullptr, &report);
  } catch (const InputError& e) {
    std::cerr << "gproj canal: " << e.what() << "\n";
    return kExitInputError;
  }
  std::printf(
      "|P_k Q'_k| against the asked lengths: %.3e -> %.3e (of the mean length) in %d "
      "iterations\n",
      c.initial_length_error, c.max_length_error, c.iterations);
  PrintMeasures("C-canal mesh", report.final);
  nlohmann::json extra = {{"curve", args.curve},
                          {"lengths", c.lengths},
                          {"canal_lengths", c.canal_lengths},
                          {"section_scales", args.section_scales}};
  char title[160];
  std::snprintf(title, sizeof(title), "C-canal surface (000 §5.2), %zu circular quads",
                c.mesh.n_faces());
  return WriteAndConclude("canal", report, c.mesh, title, args.outputs, extra, "max_length_error",
                          1e-9);
}

// 000 §4.2: the strip closed by the closing circle (case 1 keeps the first point, case 2 moves
// Q_0), the frame closed around the loop where the curve allows, the canal mesh as a ring.
int RunClosedCanal(const CanalArgs& args) {
  ClosedCanalSurface c;
  ClosedCanalOptions options;
  RunReport report;
  PolyMesh strip_mesh;
  SmoothSurface smooth;
  try {
    args.outputs.Check({{"curve", args.curve}},
                       {{"--strip", args.strip, true},
                        {"--surface", args.surface, true},
                        {"--surface-picture", args.surface_picture, false, ".svg"}});
    if (!args.second_curve.empty() || !args.section_scales.empty() || args.options.smooth)
      throw InputError(
          "--closed builds a closed circular strip: --second-curve, --section-scales and --smooth "
          "do not apply");
    if (args.first_point.empty()) throw InputError("--closed needs --first-point x,y,z");
    const CircularStripInput input = MakeCircularStripInput(
        ReadPoints(args.curve, 3), Vector3(args.first_point, "--first-point"), args.lengths,
        args.length);
    std::printf(
        "gproj canal: %s: closed strip of %zu quads (000 §4.2); the closing circle sets Q_%zu%s\n",
        args.curve.c_str(), input.curve.size(), input.curve.size() - 1,
        " (and Q_0 unless the end circles are co-spherical)");
    const auto start = std::chrono::steady_clock::now();
    Eigen::Vector3d normal;
    if (args.normal.empty()) {
      normal = DefaultClosedCanalNormal(input);
    } else {
      normal = Vector3(args.normal, "--normal");
      if (normal.norm() == 0.0) throw InputError("--normal must not be zero");
    }
    FrameAngles angles = AnglesFromNormal(normal);
    angles.psi = args.psi;
    options = args.closed_options;
    options.segments = args.options.segments;
    c = BuildClosedCanalSurface(input, angles, options);
    strip_mesh = ClosedStripMesh(c.closed.strip);
    smooth = MakeSmoothSurface(args, c.net, c.welded);
    report = ClosedCanalRunReport(
        c, options,
        std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count());
    if (report.converged && smooth.made) CheckCanalResult(c.measures, &smooth.surface, &report);
  } catch (const InputError& e) {
    std::cerr << "gproj canal: " << e.what() << "\n";
    return kExitInputError;
  }
  const NamedValues& m = c.measures;
  const int count = static_cast<int>(c.closed.strip.p.size());
  if (c.closed.closing_case == 1)
    std::printf(
        "case 1: the circles of quads 0 and %d are co-spherical (to %.1e); the closing circle "
        "passes Q_0 as asked and sets |P_%d Q_%d| = %.6g\n",
        count - 2, c.closed.cosphericity, count - 1, count - 1, ValueOf(m, "last_length"));
  else
    std::printf(
        "case 2: the circles of quads 0 and %d are not co-spherical (%.3g); the closing circle "
        "(the spheres' intersection) moves Q_0 by %.6g and sets |P_%d Q_%d| = %.6g\n",
        count - 2, c.closed.cosphericity, c.closed.start_shift, count - 1, count - 1,
        ValueOf(m, "last_length"));
  PrintMeasures("closed strip", MeasureCircularMesh(strip_mesh));
  if (c.frame_closes)
    std::printf("frame closes around the curve (%.1e deg; turned %.4g deg from the asked one)\n",
                ValueOf(m, "frame_closure_deg"), ValueOf(m, "frame_rotation_deg"));
  else if (ValueOf(m, "frame_closure_deg") < 0.1)
    std::printf(
        "the frame comes back %.3g deg off after the loop, more than --frame-tolerance %.1e: is "
        "the curve a rounded pseudo-spherical one? A looser --frame-tolerance closes it; the "
        "canal mesh is left open at P_0\n",
        ValueOf(m, "frame_closure_deg"), args.closed_options.frame_tolerance_deg);
  else
    std::printf(
        "the reflections along the curve turn every frame (%.4g deg for this one): no smooth "
        "closed cyclidic net on this curve (000 §4.2 needs a pseudo-spherical curve); the canal "
        "mesh is left open at P_0\n",
        ValueOf(m, "frame_closure_deg"));
  std::printf("canal mesh: %zu quads, %s (seam gap %.1e of the mean edge)\n", c.mesh.n_faces(),
              c.welded ? "a closed ring" : "open at P_0", ValueOf(m, "seam_gap"));
  PrintMeasures("canal mesh", m);
  nlohmann::json extra = ClosedCanalJson(c, options);
  extra["curve"] = args.curve;
  PrintSmoothSurface(smooth, &extra);
  char title[160];
  std::snprintf(title, sizeof(title),
                "Closed canal surface (000 §4.2, case %d), %zu circular quads",
                c.closed.closing_case, c.mesh.n_faces());
  return WriteAndConclude("canal", report, c.mesh, title, args.outputs, extra, "", 0.0,
                          Joined({{args.strip, &strip_mesh}}, smooth.Outputs(args)));
}

int RunCanal(const CanalArgs& args) {
  const ClosedCanalOptions closed_defaults;
  std::string misuse;
  if (args.surface_segments > 0 && args.surface.empty() && args.surface_picture.empty())
    misuse = "--surface-segments needs --surface or --surface-picture";
  else if (!args.closed &&
           (args.closed_options.cospherical_tolerance != closed_defaults.cospherical_tolerance ||
            args.closed_options.frame_tolerance_deg != closed_defaults.frame_tolerance_deg))
    misuse = "--cospherical-tolerance and --frame-tolerance belong to --closed";
  if (!misuse.empty()) {
    std::cerr << "gproj canal: " << misuse << "\n";
    return kExitInputError;
  }
  if (args.closed) return RunClosedCanal(args);
  if (!args.section_scales.empty()) return RunCCanal(args);
  if (!args.second_curve.empty()) return RunCanalFromCurves(args);
  std::unique_ptr<CanalSurface> canal;
  RunReport report;
  PolyMesh mesh;
  SmoothSurface smooth;
  try {
    canal = CanalFromArgs(args);
    const CircularStripInput& input = canal->input();
    std::printf("gproj canal: %s: %zu curve points, %zu strip quads; first point (%g, %g, %g)\n",
                args.curve.c_str(), input.curve.size(), input.curve.size() - 1,
                input.first_point.x(), input.first_point.y(), input.first_point.z());
    const IterationLog log({"smoothness_energy"});  // F = sum of 1/R^2 over the strip's arcs
    if (args.options.smooth) std::printf("shape smoothing (000 eq. 5), Ceres line-search BFGS\n");
    if (args.options.smooth) log.PrintHeader();
    report = canal->Run([&log](const RunRecord& r) { return log.Print(r), true; });
    mesh = canal->Mesh();
    smooth = MakeSmoothSurface(args, canal->Net(), false);
    if (report.converged)
      CheckCanalResult(report.final, smooth.made ? &smooth.surface : nullptr, &report);
  } catch (const InputError& e) {
    std::cerr << "gproj canal: " << e.what() << "\n";
    return kExitInputError;
  }
  const PolyMesh strip_mesh = StripMesh(canal->strip());
  const NamedValues strip = MeasureCircularMesh(strip_mesh);
  std::printf("F: %.6g -> %.6g\n", ValueOf(report.initial, "smoothness_energy"),
              ValueOf(report.final, "smoothness_energy"));
  PrintMeasures("strip", strip);
  PrintMeasures("canal mesh", report.final);
  const FrameAngles& a = canal->angles();
  const Eigen::Vector3d n = NormalOf(a);
  nlohmann::json extra = {{"curve", args.curve}, {"lengths", canal->input().lengths}};
  extra["frame"] = {{"lambda", a.lambda}, {"theta", a.theta}, {"psi", a.psi}};
  extra["frame"]["normal"] = {n.x(), n.y(), n.z()};
  for (const NamedValue& v : strip) extra["strip"][v.name] = v.value;
  extra["mesh"] = {{"rows", canal->strip().p.size() - 1}, {"segments", args.options.segments}};
  PrintSmoothSurface(smooth, &extra);
  char title[160];
  std::snprintf(title, sizeof(title), "Canal surface, %zu circular quads, max concyclicity %.1e",
                mesh.n_faces(), ValueOf(report.final, "max_concyclicity"));
  // The smoothing's tolerance is Ceres' relative function decrease, not a bound on a measure.
  return WriteAndConclude("canal", report, mesh, title, args.outputs, extra, "", 0.0,
                          Joined({{args.strip, &strip_mesh}}, smooth.Outputs(args)));
}

}  // namespace

void RegisterCanalCommand(CLI::App* app, int* exit_code) {
  auto args = std::make_shared<CanalArgs>();
  CLI::App* cmd = app->add_subcommand(
      "canal",
      "Canal surface from a circular strip (000 §3.2-3.3, §4.1): points P_k on a curve, a first "
      "point fixing the first circle and the lengths |P_k Q_k| give a strip of circular quads "
      "by propagation; a frame at P_0 makes it a cyclidic net whose crossing arcs are the "
      "canal surface's circles; the surface is meshed by circular quads between them. "
      "--smooth minimises 000 eq. 5 (Ceres line-search BFGS). With --second-curve and --normal "
      "instead: spheres equidistant from the curve and a second curve (000 §4.1, eq. 6), meshed "
      "by circular quads between their circles. Exit codes as for planarize.");
  cmd->add_option("curve", args->curve,
                  "Curve points P_0..P_n: one 'x y z' per line ('#' comments)")
      ->required();
  cmd->add_option("-o,--output", args->outputs.mesh, "Canal mesh to write (circular quads)")
      ->required();
  cmd->add_option("--first-point", args->first_point,
                  "x,y,z of the point that fixes the first circle (with P_0 and P_1)")
      ->check(Finite())
      ->delimiter(',');
  cmd->add_option("--second-curve", args->second_curve,
                  "Fit the canal surface to a second curve instead (000 §4.1): the curve is "
                  "then a line of curvature and --normal the surface normal at P_0");
  cmd->add_option("--lengths", args->lengths, "|P_k Q_k| for every curve point (comma separated)")
      ->check(Finite())
      ->delimiter(',');
  cmd->add_option("--length", args->length, "The same |P_k Q_k| for every curve point")
      ->check(Finite())
      ->check(Positive());
  cmd->add_option(
         "--normal", args->normal,
         "Normal of the cyclidic net at P_0 (default: in the first quad's plane, across the "
         "curve; not zero)")
      ->check(Finite())
      ->delimiter(',');
  cmd->add_option("--psi", args->psi,
                  "Rotation (radians) of the frame's first tangent about the normal")
      ->check(Finite())
      ->capture_default_str();
  cmd->add_option("--segments", args->options.segments, "Quads across the strip in the canal mesh")
      ->check(Within(1, 100000))
      ->capture_default_str();
  cmd->add_option("--section-scales", args->section_scales,
                  "C-canal surface (000 §5.2): one factor > 0 per segment scaling the first "
                  "arc's edges into a planar cross-section; the lengths are then the C-canal's")
      ->check(Positive())
      ->delimiter(',');
  cmd->add_flag("--closed", args->closed,
                "Close the curve by the edge P_n -> P_0 (000 §4.2): the closing circle sets the "
                "last length (case 1) or also moves Q_0 (case 2); the frame is closed around the "
                "curve where it can be");
  cmd->add_option("--cospherical-tolerance", args->closed_options.cospherical_tolerance,
                  "With --closed: the end circles count as co-spherical (case 1) within this "
                  "distance (per mean edge)")
      ->check(NonNegative())
      ->capture_default_str();
  cmd->add_option("--frame-tolerance", args->closed_options.frame_tolerance_deg,
                  "With --closed: the frame closes around the curve when it misses itself by at "
                  "most this many degrees")
      ->check(NonNegative())
      ->capture_default_str();
  cmd->add_flag("--smooth", args->options.smooth, "Minimise the smoothness energy of 000 eq. 5");
  cmd->add_option("--length-weight", args->options.smoothing.length_weight,
                  "Weight keeping the lengths near the input during --smooth")
      ->check(NonNegative())
      ->capture_default_str();
  cmd->add_flag("!--fixed-lengths", args->options.smoothing.optimize_lengths,
                "Keep the lengths; smooth over the frame only");
  cmd->add_option("--max-iterations", args->options.smoothing.max_iterations,
                  "BFGS iterations at most")
      ->check(Within(1, 100000))
      ->capture_default_str();
  cmd->add_option("--strip", args->strip, "Also write the circular strip (2 x (n+1) vertices)");
  cmd->add_option("--surface", args->surface,
                  "Also write the smooth cyclidic surface (000 §2.2): every quad of the strip's "
                  "cyclidic net carries a Dupin cyclide patch, meshed along its curvature lines");
  cmd->add_option("--surface-segments", args->surface_segments,
                  "Fine quads along every arc of the smooth surface (default 8)")
      ->check(Within(1, 1000));
  cmd->add_option("--surface-picture", args->surface_picture,
                  "Write a shaded SVG picture of the smooth cyclidic surface");
  cmd->add_option("--report", args->outputs.report, "Write a JSON report");
  cmd->add_option("--picture", args->outputs.picture,
                  "Write a shaded SVG picture of the canal mesh");
  cmd->callback([args, exit_code]() { *exit_code = RunCanal(*args); });
}

}  // namespace gproj
