// `gproj weingarten`: Weingarten surfaces on B-splines (003).
#include <algorithm>
#include <cctype>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <iostream>
#include <memory>
#include <string>
#include <tuple>
#include <vector>

#include "apps/commands.h"
#include "problems/weingarten.h"
#include "problems/weingarten_paneling.h"

namespace gproj {
namespace {

struct WeingartenArgs {
  std::string input, report, solver = "gp";
  WeingartenFiles files;
  WeingartenSettings settings;
  std::vector<int> panel_grid;          // --panels NU,NV
  std::vector<double> panel_tolerance;  // --panel-tolerance GAP,KINK
  PanelSettings panels;
  std::string panel_picture, seam_histograms;
};

// The optional outputs: option, path, help.
struct Output {
  const char* option;
  std::string* path;
  const char* help;
};
std::vector<Output> Outputs(WeingartenArgs* a) {
  return {{"--report", &a->report, "Write a JSON report"},
          {"--diagram", &a->files.diagram, "Curvature diagram before/after (.svg)"},
          {"--curvature", &a->files.curvature, "H, K per sample before/after (.csv)"},
          {"--surface-mesh", &a->files.surface_mesh, "The result sampled as a quad mesh"},
          {"--picture", &a->files.picture, "A shaded picture of the result (.svg)"},
          {"--panel-picture", &a->panel_picture,
           "With --panels: the result's panels, one colour per mold (.svg)"},
          {"--seam-histograms", &a->seam_histograms,
           "With --panels: gaps and kinks at the seams, input against result (.svg)"}};
}

// The options from the preset and the overrides; the input; every output path checked.
WeingartenOptions Prepare(WeingartenArgs* args, BSplineSurface* input) {
  const WeingartenOptions options = args->settings.ToOptions();
  if (!args->panel_grid.empty()) {
    args->panels.panels_u = args->panel_grid[0];
    args->panels.panels_v = args->panel_grid[1];
  }
  if (!args->panel_tolerance.empty()) {
    args->panels.max_gap = args->panel_tolerance[0];
    args->panels.max_kink_deg = args->panel_tolerance[1];
  }
  if (!args->panels.enabled() && (!args->panel_tolerance.empty() || !args->panel_picture.empty() ||
                                  !args->seam_histograms.empty()))
    throw InputError(
        "--panel-tolerance, --panel-picture and --seam-histograms need --panels NU,NV");
  args->panels.Validate();
  std::vector<OutputPath> outputs = {{"--output", args->files.output}};
  for (const Output& o : Outputs(args))
    outputs.push_back({o.option, *o.path, o.path == &args->files.surface_mesh});
  CheckOutputPaths({{"input", args->input}}, outputs);
  std::string extension = std::filesystem::path(args->files.output).extension().string();
  for (char& c : extension) c = static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
  if (extension != ".json")
    throw InputError("--output " + args->files.output +
                     ": the result is a B-spline surface written as JSON, so its name must end "
                     "in .json (--surface-mesh writes it sampled as a mesh)");
  *input = ReadBSplineJson(args->input);
  return options;
}

int RunWeingartenCommand(WeingartenArgs args) try {
  BSplineSurface input;
  const WeingartenOptions options = Prepare(&args, &input);
  const IterationLog log(
      options.linear_relation_weight > 0.0
          ? std::vector<std::string>{"misalignment", "max_constraint", "max_relation_residual"}
          : std::vector<std::string>{"misalignment", "max_constraint"});
  const auto on_level = [&](int level, const WeingartenProblem& problem) {
    std::printf("gproj weingarten: %s, preset %s: %s", args.input.c_str(),
                args.settings.preset.c_str(), DescribeWeingartenLevel(level, problem).c_str());
    log.PrintHeader();
  };
  WeingartenRun run;
  try {
    run = RunWeingarten(
        input, options, args.solver != "gp", args.settings.molds,
        [&log](const RunRecord& r) { return log.Print(r), true; }, on_level);
  } catch (const InputError& e) {  // a property of the surface read from the input
    throw InputError(args.input + ": " + e.what());
  }
  std::optional<PanelComparison> panels;
  if (!run.report.failed && args.panels.enabled()) {
    std::printf("gproj weingarten: paneling the input and the result (%d x %d panels)...\n",
                args.panels.panels_u, args.panels.panels_v);
    std::fflush(stdout);
    panels = ComparePaneling(input, run.result, args.panels);
  }
  nlohmann::json report = WeingartenReportJson(options, run);
  if (panels) report["panels"] = PanelsJson(*panels);
  report.update(
      {{"input", args.input}, {"output", args.files.output}, {"preset", args.settings.preset}});
  OutputFiles files;
  if (!run.report.failed) AddWeingartenFiles(run, args.files, &files);
  if (panels && !args.panel_picture.empty())
    files.AddText(args.panel_picture, PanelPictureSvg(run.result, panels->final));
  if (panels && !args.seam_histograms.empty())
    files.AddText(args.seam_histograms, SeamHistogramsSvg(*panels));
  if (!run.report.failed && !args.report.empty()) files.AddText(args.report, report.dump(2) + "\n");
  files.Commit();
  if (!run.report.failed) std::printf("%s", SummarizeWeingartenRun(run).c_str());
  if (panels) std::printf("%s", SummarizePanels(*panels).c_str());
  const WeingartenFiles& f = args.files;
  const int code =
      ConcludeRun("weingarten", run.report, options.target_measure(), options.tolerance,
                  {f.output, args.report, f.diagram, f.curvature, f.surface_mesh, f.picture,
                   args.panel_picture, args.seam_histograms});
  if (code == kExitOk && run.folds()) {
    // A folded surface is not a result, whatever its misalignment.
    std::fprintf(stderr,
                 "gproj weingarten: the result folds: neighbouring normals turn by %.0f deg near "
                 "(u, v) = (%.4g, %.4g); the result was written, exit code %d\n",
                 std::acos(std::max(-1.0, run.normals_after.min_cosine)) * 180.0 / M_PI,
                 run.normals_after.u, run.normals_after.v, kExitNotConverged);
    return kExitNotConverged;
  }
  return code;
} catch (const InputError& e) {
  std::cerr << "gproj weingarten: " << e.what() << "\n";
  return kExitInputError;
}

}  // namespace

void RegisterWeingartenCommand(CLI::App* app, int* exit_code) {
  auto args = std::make_shared<WeingartenArgs>();
  std::string presets;
  for (const auto& n : WeingartenPresetNames()) presets += (presets.empty() ? "" : ", ") + n;
  CLI::App* cmd = app->add_subcommand(
      "weingarten",
      "Weingarten surface (003): moves a B-spline's control points (JSON, SPEC §4) so that the "
      "isolines of H and K align, close to the input. Exit codes as for planarize.");
  cmd->add_option("input", args->input, "B-spline surface (.json)")->required();
  cmd->add_option("-o,--output", args->files.output, "Optimised B-spline (.json)")->required();
  cmd->add_option("--preset", args->settings.preset, "Weights of 003 Table 1: " + presets)
      ->capture_default_str();
  cmd->add_option("--samples", args->settings.samples,
                  "Samples NU NV (default: 2 per control point and direction, as in Table 2)")
      ->check(Within(5, 100000))
      ->expected(2);
  cmd->add_option("--relation", args->settings.relation,
                  "Curvature relation: none, linear (fitted each iteration) or bspline")
      ->check(CLI::IsMember({"none", "linear", "bspline"}));
  cmd->add_option("--linear", args->settings.linear,
                  "Fixed linear relation a,b,c: a H + b K + c = 0 in input units (e.g. 0,1,0: "
                  "developable; 1,0,0: minimal; 1,0,-c: H = c)")
      ->check(Finite())
      ->delimiter(',');
  cmd->add_option("--relation-on", args->settings.relation_on,
                  "A fixed relation on the surface's own H, K (default) or the auxiliaries")
      ->check(CLI::IsMember({"surface", "auxiliaries"}));
  cmd->add_option("--steps", args->settings.steps,
                  "plain: every step kept; monotone: only steps that lower the energy (else ε "
                  "grows); projected: monotone, auxiliaries reset after each step (fig3)")
      ->check(CLI::IsMember({"plain", "monotone", "projected"}));
  cmd->add_option("--solver", args->solver,
                  "gp: guided projection; ceres: Levenberg-Marquardt on the same rows (soft "
                  "terms at their final weights)")
      ->check(CLI::IsMember({"gp", "ceres"}))
      ->capture_default_str();
  cmd->add_flag("--no-auxiliaries", args->settings.no_auxiliaries,
                "Control points are the only unknowns (needs --linear on the surface)");
  cmd->add_flag("--allow-folds", args->settings.allow_folds,
                "Keep steps that fold the surface (by default a step is refused when neighbouring "
                "normals on a grid 4x as dense as the samples turn by more than 60 degrees)");
  WeingartenSettings& s = args->settings;
  for (const auto& [name, value, help, check] : std::initializer_list<
           std::tuple<const char*, std::optional<double>*, const char*, CLI::Validator>>{
           {"--alignment", &s.alignment, "Override ω_al (isoline alignment)", NonNegative()},
           {"--closeness", &s.closeness, "Override ω_cl (closeness to the input)", NonNegative()},
           {"--shape", &s.shape, "Override ω_sh (control-net lengths)", NonNegative()},
           {"--geodesic-parallel", &s.geodesic_parallel, "Override ω_gp (eq. 8)", NonNegative()},
           {"--epsilon", &s.epsilon, "Override ε of eq. 11 (proximal weight)", Positive()},
           {"--soft-start", &s.soft_start, "Soft terms start this much stronger (≥ 1)",
            Within(1.0, 1e12)},
           {"--fairness", &s.fairness, "Override ω_f of eq. 11 (control-net fairness)",
            NonNegative()},
           {"--definitions", &s.definitions,
            "Weight of the rows defining the auxiliaries (relative errors; default 1)", Positive()},
           {"--boundary", &s.boundary, "Weight of gliding along the input's boundary polygon",
            NonNegative()}})
    cmd->add_option(name, *value, help)->check(check);
  cmd->add_option("--refine", args->settings.refine_levels,
                  "Multiresolution levels: insert a knot in every span and re-optimise")
      ->check(Within(0, 4))
      ->capture_default_str();
  cmd->add_option("--refine-method", args->settings.refine_method,
                  "How --refine refines: insert (a knot in every span: the same surface exactly) "
                  "or refit (least squares on a net 1.4 times as dense, as 003 §4.1.1)")
      ->check(CLI::IsMember({"insert", "refit"}))
      ->capture_default_str();
  cmd->add_option("--max-iterations", args->settings.max_iterations,
                  "Guided-projection iterations per level (default 10)")
      ->check(Within(1, 100000));
  cmd->add_option("--tolerance", args->settings.tolerance,
                  "Stop when the misalignment (--linear: max relation residual, input units) is "
                  "<= this, else exit 3. Default: none, the preset's iterations are run")
      ->check(Positive());
  cmd->add_option("--molds", args->settings.molds,
                  "Cluster the samples into at most this many molds in the (H, sqrt K) plane")
      ->check(Within(0, 1000000));
  cmd->add_option("--panels", args->panel_grid,
                  "Panel the input and the result: NU,NV panels over the parameter domain, "
                  "molds by clustering in the (H, sqrt K) plane, one cubic per mold (003 §4.2); "
                  "the report's panels object compares their gaps and kinks")
      ->check(Within(1, 1000))
      ->delimiter(',')
      ->expected(2);
  cmd->add_option("--mold-factor", args->panels.mold_factor,
                  "With --panels: k sqrt N molds for N panels")
      ->check(Within(0.01, 1000.0))
      ->capture_default_str();
  cmd->add_option("--panel-tolerance", args->panel_tolerance,
                  "With --panels: GAP,KINK (input units, degrees): report the molds the input and "
                  "the result need for max gap <= GAP and max kink <= KINK")
      ->check(Positive())
      ->delimiter(',')
      ->expected(2);
  for (const Output& o : Outputs(args.get())) cmd->add_option(o.option, *o.path, o.help);
  cmd->callback([args, exit_code]() { *exit_code = RunWeingartenCommand(*args); });
}

}  // namespace gproj
