// `weingarten` in the registry: Weingarten surfaces on B-splines (003), with mold paneling.
#include <cmath>
#include <cstdio>

#include "gproj/geometry/render/svg_render.h"
#include "gproj/problems/run/builtin_problems.h"
#include "gproj/problems/run/shared_options.h"
#include "gproj/problems/weingarten/weingarten.h"
#include "gproj/problems/weingarten/weingarten_options.h"
#include "gproj/problems/weingarten/weingarten_paneling.h"
#include "gproj/problems/weingarten/weingarten_run.h"
#include "gproj/problems/weingarten/weingarten_settings.h"

namespace gproj::weingarten {
namespace {

struct WeingartenCommandSettings {
  WeingartenSettings settings;
  SolverKind solver = SolverKind::kGuidedProjection;
  PanelSettings panels;
};

using S = WeingartenCommandSettings;

// An override of the preset: absent unless given.
void AddOverride(OptionSchema<S>* s, const std::string& name, const std::string& doc,
                 std::optional<double> WeingartenSettings::*member, bool positive) {
  auto b =
      s->Custom(name, OptionType::kNumber, doc, nullptr,
                [member](const nlohmann::json& v, S* x) { x->settings.*member = v.get<double>(); });
  positive ? b.Positive() : b.NonNegative();
}

// A choice that defaults to the preset's.
void AddPresetChoice(OptionSchema<S>* s, const std::string& name, const std::string& doc,
                     std::vector<std::string> choices, std::string WeingartenSettings::*member) {
  s->Custom(name, OptionType::kChoice, doc + " (not given: the preset's)", nullptr,
            [member](const nlohmann::json& v, S* x) { x->settings.*member = v.get<std::string>(); })
      .Choices(std::move(choices));
}

// preset, solver, samples, the relation and the kind of steps.
void AddProblemOptions(OptionSchema<S>* schema) {
  OptionSchema<S>& s = *schema;
  s.Field<std::string>("preset", OptionType::kChoice, "Weights of 003 Table 1",
                       [](S& x) -> std::string& { return x.settings.preset; })
      .Choices(WeingartenPresetNames());
  AddSolverChoice<S>(&s, "solver",
                     "gp: guided projection; ceres: Levenberg-Marquardt on the same rows (soft "
                     "terms at their final weights)",
                     [](S& x) -> SolverKind& { return x.solver; },
                     {{"gp", SolverKind::kGuidedProjection}, {"ceres", SolverKind::kCeres}});
  s.Custom("samples", OptionType::kInts,
           "Samples NU,NV (not given: 2 per control point and direction, as in Table 2)", nullptr,
           [](const nlohmann::json& v, S* x) { x->settings.samples = v.get<std::vector<int>>(); })
      .Range(5, 100000)
      .Count(2, "NU,NV");
  AddPresetChoice(&s, "relation",
                  "Curvature relation: none, linear (fitted each iteration) or bspline",
                  {"none", "linear", "bspline"}, &WeingartenSettings::relation);
  s.Custom("linear", OptionType::kNumbers,
           "Fixed linear relation a,b,c: a H + b K + c = 0 in input units (e.g. 0,1,0: "
           "developable; 1,0,0: minimal; 1,0,-c: H = c)",
           nullptr,
           [](const nlohmann::json& v, S* x) { x->settings.linear = v.get<std::vector<double>>(); })
      .Count(3, "A,B,C");
  AddPresetChoice(&s, "relation_on",
                  "A fixed relation on the surface's own H, K or on the auxiliaries",
                  {"surface", "auxiliaries"}, &WeingartenSettings::relation_on);
  AddPresetChoice(&s, "steps",
                  "plain: every step kept; monotone: only steps that lower the energy (else "
                  "epsilon grows); projected: monotone, auxiliaries reset after each step",
                  {"plain", "monotone", "projected"}, &WeingartenSettings::steps);
  s.Field<bool>("no_auxiliaries", OptionType::kBool,
                "Control points are the only unknowns (needs linear on the surface)",
                [](S& x) -> bool& { return x.settings.no_auxiliaries; });
  s.Field<bool>("allow_folds", OptionType::kBool,
                "Keep steps that fold the surface (by default a step is refused when "
                "neighbouring normals on a grid 4x as dense as the samples turn by more than 60 "
                "degrees)",
                [](S& x) -> bool& { return x.settings.allow_folds; });
}

// The preset's weights overridden, and the multiresolution levels.
void AddWeightOptions(OptionSchema<S>* schema) {
  OptionSchema<S>& s = *schema;
  using W = WeingartenSettings;
  AddOverride(&s, "alignment", "Override omega_al (isoline alignment)", &W::alignment, false);
  AddOverride(&s, "closeness", "Override omega_cl (closeness to the input)", &W::closeness, false);
  AddOverride(&s, "shape", "Override omega_sh (control-net lengths)", &W::shape, false);
  AddOverride(&s, "geodesic_parallel", "Override omega_gp (eq. 8)", &W::geodesic_parallel, false);
  AddOverride(&s, "epsilon", "Override epsilon of eq. 11 (proximal weight)", &W::epsilon, true);
  s.Custom("soft_start", OptionType::kNumber, "Soft terms start this much stronger", nullptr,
           [](const nlohmann::json& v, S* x) { x->settings.soft_start = v.get<double>(); })
      .Range(1.0, 1e12);
  AddOverride(&s, "fairness", "Override omega_f of eq. 11 (control-net fairness)", &W::fairness,
              false);
  AddOverride(&s, "definitions",
              "Weight of the rows defining the auxiliaries (relative errors; default 1)",
              &W::definitions, true);
  AddOverride(&s, "boundary", "Weight of gliding along the input's boundary polygon", &W::boundary,
              false);
  s.Field<int>("refine", OptionType::kInt,
               "Multiresolution levels: insert a knot in every span and re-optimise",
               [](S& x) -> int& { return x.settings.refine_levels; })
      .Range(0, 4);
  s.Field<std::string>("refine_method", OptionType::kChoice,
                       "How refine refines: insert (a knot in every span: the same surface "
                       "exactly) or refit (least squares on a net 1.4 times as dense, 003 "
                       "§4.1.1)",
                       [](S& x) -> std::string& { return x.settings.refine_method; })
      .Choices({"insert", "refit"});
  s.Custom("max_iterations", OptionType::kInt,
           "Guided-projection iterations per level (not given: the preset's)", nullptr,
           [](const nlohmann::json& v, S* x) { x->settings.max_iterations = v.get<int>(); })
      .Range(1, 100000);
}

// The tolerance, mold clustering and paneling.
void AddMoldOptions(OptionSchema<S>* schema) {
  OptionSchema<S>& s = *schema;
  s.Custom(
       "tolerance", OptionType::kNumber,
       "Converged when the misalignment (with linear: max relation residual, input units) "
       "is <= this, and the run stops there (not given: the preset's iterations are run; with a "
       "fixed linear relation they are converged when it holds to 1% of |a| k + |b| k^2, k "
       "the input's typical principal curvature; otherwise there is no tolerance)",
       nullptr, [](const nlohmann::json& v, S* x) { x->settings.tolerance = v.get<double>(); })
      .Positive();
  s.Field<int>("molds", OptionType::kInt,
               "Cluster the samples into at most this many molds in the (H, sqrt K) plane (0: "
               "none)",
               [](S& x) -> int& { return x.settings.molds; })
      .Range(0, 1000000);
  s.Custom("panels", OptionType::kInts,
           "Panel the input and the result: NU,NV panels over the parameter domain, molds by "
           "clustering in the (H, sqrt K) plane, one cubic per mold (003 §4.2)",
           nullptr,
           [](const nlohmann::json& v, S* x) {
             x->panels.panels_u = v[0].get<int>(), x->panels.panels_v = v[1].get<int>();
           })
      .Range(1, 1000)
      .Count(2, "NU,NV");
  s.Field<double>("mold_factor", OptionType::kNumber, "With panels: k sqrt N molds for N panels",
                  [](S& x) -> double& { return x.panels.mold_factor; })
      .Range(0.01, 1000.0);
  s.Custom("panel_tolerance", OptionType::kNumbers,
           "With panels: GAP,KINK (input units, degrees): report the molds the input and the "
           "result need for max gap <= GAP and max kink <= KINK",
           nullptr,
           [](const nlohmann::json& v, S* x) {
             x->panels.max_gap = v[0].get<double>(), x->panels.max_kink_deg = v[1].get<double>();
           })
      .Positive()
      .Count(2, "GAP,KINK");
}

const OptionSchema<S>& Schema() {
  static const OptionSchema<S> schema = [] {
    OptionSchema<S> s;
    AddProblemOptions(&s);
    AddWeightOptions(&s);
    AddMoldOptions(&s);
    return s;
  }();
  return schema;
}

// The outputs asked for, into `result`.
void AddOutputs(const WeingartenRun& run, const std::optional<PanelComparison>& panels,
                const RunContext& context, RunResult* result) {
  const BSplineSurface& surface = run.result;
  result->texts["output"] = BSplineToJson(surface);
  if (context.Wants("curvature"))
    result->texts["curvature"] =
        WeingartenCurvatureCsv(run, run.molds ? &run.molds->cluster : nullptr);
  if (context.Wants("diagram")) result->texts["diagram"] = WeingartenDiagramSvg(run);
  if (context.Wants("surface_mesh"))
    result->meshes["surface_mesh"] = SampleSurfaceMesh(surface, 4 * surface.nu, 4 * surface.nv);
  if (context.Wants("picture")) {
    SvgOptions svg;
    svg.title = "Weingarten surface (" + std::to_string(surface.nu) + " x " +
                std::to_string(surface.nv) + " control points)";
    result->texts["picture"] = RenderMeshSvg(SampleSurfaceMesh(surface, 60, 60), svg);
  }
  if (panels && context.Wants("panel_picture"))
    result->texts["panel_picture"] = PanelPictureSvg(surface, panels->final);
  if (panels && context.Wants("seam_histograms"))
    result->texts["seam_histograms"] = SeamHistogramsSvg(*panels);
}

// Lines of text ("a\nb\n") as kInfo messages.
void AddLines(const std::string& text, RunResult* result) {
  size_t start = 0;
  while (start < text.size()) {
    const size_t end = text.find('\n', start);
    result->Info(text.substr(start, end - start));
    if (end == std::string::npos) break;
    start = end + 1;
  }
}

RunResult Run(const RunInputs& inputs, const nlohmann::json& values, const RunContext& context) {
  S s = Schema().Apply(values);
  const bool panel_outputs = context.Wants("panel_picture") || context.Wants("seam_histograms");
  if (!s.panels.enabled() && (values.contains("panel_tolerance") || panel_outputs))
    throw InputError(
        "`panel_tolerance`, `panel_picture` and `seam_histograms` need `panels` NU,NV");
  s.panels.Validate();
  const WeingartenOptions options = s.settings.ToOptions();
  const BSplineSurface& input = inputs.Surface("surface");
  const std::string source = inputs.Source("surface");
  const std::vector<std::string> columns =
      options.linear_relation_weight > 0.0
          ? std::vector<std::string>{"misalignment", "max_constraint", "max_relation_residual"}
          : std::vector<std::string>{"misalignment", "max_constraint"};
  const auto on_level = [&](int level, const WeingartenProblem& problem) {
    std::string text = DescribeWeingartenLevel(level, problem);
    if (!text.empty() && text.back() == '\n') text.pop_back();
    context.Headline(source + ", preset " + s.settings.preset + ": " + text);
    context.Columns(columns);
  };
  WeingartenRun run;
  try {
    run = RunWeingarten(
        input, options, s.solver, s.settings.molds,
        [&context](const RunRecord& r) { return context.Record(r); }, on_level);
  } catch (const InputError& e) {  // a property of the surface read from the input
    throw InputError(source + ": " + e.what());
  }
  RunResult result;
  result.report = run.report;
  result.tolerance_measure = run.tolerance > 0.0 ? options.target_measure() : "";
  result.tolerance = run.tolerance;
  std::optional<PanelComparison> panels;
  // Paneling is a stage of its own (seconds on a 10 x 10 paneling): a stopped run skips it.
  const bool stopped = StatusOf(run.report) == RunStatus::kUserAbort;
  if (stopped && s.panels.enabled())
    result.Info("paneling skipped: the run was stopped before it (no panel report or pictures)");
  if (!run.report.failed && !stopped && s.panels.enabled()) {
    context.Headline("paneling the input and the result (" + std::to_string(s.panels.panels_u) +
                     " x " + std::to_string(s.panels.panels_v) + " panels)...");
    try {
      panels = ComparePaneling(input, run.result, s.panels,
                               [&context] { return context.StopRequested(); });
    } catch (const RunStopped&) {
      result.Info("paneling stopped: the run was stopped during it (no panel report or pictures)");
      result.report.converged = false;
      result.report.termination = "USER_ABORT: stopped during the paneling";
    }
  }
  result.facts = WeingartenReportFacts(options, run);
  result.facts["preset"] = s.settings.preset;
  if (panels) result.facts["panels"] = PanelsJson(*panels);
  for (int level : run.history_level) result.history_facts.push_back({{"level", level}});
  if (run.report.failed) return result;
  AddOutputs(run, panels, context, &result);
  AddLines(SummarizeWeingartenRun(run), &result);
  if (panels) AddLines(SummarizePanels(*panels), &result);
  if (result.report.converged && run.folds()) {
    // A folded surface is not a result, whatever its misalignment.
    char line[256];
    std::snprintf(line, sizeof(line),
                  "the result folds: neighbouring normals turn by %.0f deg near (u, v) = (%.4g, "
                  "%.4g)",
                  std::acos(std::max(-1.0, run.normals_after.min_cosine)) * 180.0 / M_PI,
                  run.normals_after.u, run.normals_after.v);
    result.report.converged = false;
    result.report.termination += "; " + std::string(line);
    result.shortfalls.push_back(line);
  }
  return result;
}

}  // namespace

ProblemSpec WeingartenSpec() {
  ProblemSpec spec;
  spec.name = "weingarten";
  spec.summary =
      "Weingarten surface (003): moves a B-spline's control points (JSON, docs/formats.md) so that "
      "the "
      "isolines of H and K align, close to the input; optionally a fixed or fitted curvature "
      "relation, multiresolution, mold clustering and paneling.";
  spec.inputs = {{"surface", InputKind::kBSpline, "B-spline surface", true}};
  spec.outputs = {
      {"output", OutputKind::kJson, "the optimised B-spline", true},
      {"diagram", OutputKind::kSvg, "the curvature diagram before/after"},
      {"curvature", OutputKind::kCsv, "H, K per sample before/after (and the mold of each)"},
      {"surface_mesh", OutputKind::kMesh, "the result sampled as a quad mesh"},
      {"picture", OutputKind::kSvg, "a shaded picture of the result"},
      {"panel_picture", OutputKind::kSvg, "with panels: the result's panels, one colour per mold"},
      {"seam_histograms", OutputKind::kSvg,
       "with panels: gaps and kinks at the seams, input against result"}};
  spec.options = Schema().specs();
  spec.log_measures = {"misalignment", "max_constraint"};
  spec.run = Run;
  return spec;
}

}  // namespace gproj::weingarten
