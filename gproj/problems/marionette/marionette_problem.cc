// `marionette` in the registry: planar-quad meshes over a fixed plan view (002), every mode of
// MakeMarionetteRun (grid plans from guide curves or fits, plans of any connectivity from guide
// files and projections, plans of polygons, closed strips and rings) behind one command.
#include <cstdio>
#include <sstream>

#include "gproj/problems/marionette/marionette_run.h"
#include "gproj/problems/run/builtin_problems.h"
#include "gproj/problems/run/shared_options.h"

namespace gproj::marionette {
namespace {

struct MarionetteSettings {
  MarionetteRunOptions run;
};

void AddGuideOptions(OptionSchema<MarionetteSettings>* s) {
  using S = MarionetteSettings;
  s->Optional<std::vector<double>>(
      "row", OptionType::kNumbers, "Guide values of vertices (0, j), j = 0..cols of a grid plan",
      [](S & x) -> auto& { return x.run.row; });
  s->Optional<std::vector<double>>(
      "column", OptionType::kNumbers,
      "Guide values of vertices (i, 0), i = 0..rows; its first value must equal row's",
      [](S & x) -> auto& { return x.run.column; });
  s->Field<std::string>("projection", OptionType::kChoice,
                        "Lines of the vertices: vertical (values are heights), cylindrical "
                        "(through the plan vertex, perpendicular to axis; values are distances "
                        "from the axis) or central (through centre and the plan vertex; values "
                        "are distances from it)",
                        [](S& x) -> std::string& { return x.run.projection; })
      .Choices({"vertical", "cylindrical", "central"});
  s->Field<std::vector<double>>(
       "axis", OptionType::kNumbers, "Cylindrical axis: a point and a direction",
       [](S & x) -> auto& { return x.run.axis; })
      .Count(6, "PX,PY,PZ,DX,DY,DZ");
  s->Field<std::vector<double>>(
       "centre", OptionType::kNumbers, "Centre of the central projection",
       [](S & x) -> auto& { return x.run.centre; })
      .Count(3, "X,Y,Z");
}

void AddFitOptions(OptionSchema<MarionetteSettings>* s) {
  using S = MarionetteSettings;
  s->Custom("hold", OptionType::kVertexValues,
            "Hard constraint of a fit (002 §3.3), or the prescribed heights of a plan of "
            "polygons (002 §4.2): vertex heights met exactly (KKT system, solver direct)",
            nullptr, [](const nlohmann::json& v, S* x) {
              for (const nlohmann::json& p : v)
                x->run.constraints.heights.emplace_back(p[0].get<int>(), p[1].get<double>());
            });
  s->Custom("volume", OptionType::kNumber,
            "Hard constraint of a fit: the volume under the mesh over its plan (z = 0 as the "
            "base), met exactly",
            nullptr, [](const nlohmann::json& v, S* x) {
              x->run.constraints.with_volume = true;
              x->run.constraints.volume = v.get<double>();
            });
  s->Custom("max_height", OptionType::kNumber,
            "Hard constraint of a fit: no vertex above this height (active set)", nullptr,
            [](const nlohmann::json& v, S* x) {
              x->run.constraints.with_max_height = true;
              x->run.constraints.max_height = v.get<double>();
            });
}

void AddSolveOptions(OptionSchema<MarionetteSettings>* s) {
  using S = MarionetteSettings;
  AddSolverChoice<S>(s, "solver",
                     "direct: propagation (linear time) or the normal equations of the fit; "
                     "gp: guided projection (one iteration when vertical, several for other "
                     "projections; the guides are first checked by propagation); ceres: "
                     "Levenberg-Marquardt on the same rows (the cross-check)",
                     [](S& x) -> SolverKind& { return x.run.solver; },
                     {{"direct", SolverKind::kDirect},
                      {"gp", SolverKind::kGuidedProjection},
                      {"ceres", SolverKind::kCeres}});
  s->Field<int>("max_iterations", OptionType::kInt,
                "gp or ceres with a non-vertical projection: iterations at most",
                [](S& x) -> int& { return x.run.lift.solver.max_iterations; })
      .Range(1, 100000);
  s->Field<double>("tolerance", OptionType::kNumber,
                   "The result's planarity to reach in every mode (with guides or a projection: "
                   "max |det(p1-p0, p2-p0, p3-p0)| / (edge lengths) and the guide error; grid "
                   "plans and closed strips: max planarity, diagonal distance / mean edge)",
                   [](S& x) -> double& { return x.run.lift.tolerance; })
      .Positive();
  s->Field<double>("outer_height", OptionType::kNumber,
                   "closed_strip with a = 1: the height of the first outer vertex (free)",
                   [](S& x) -> double& { return x.run.outer_height; });
  s->Field<bool>("allow_folded_plan", OptionType::kBool,
                 "Lift a plan view whose quads overlap or are not convex in x, y (refused by "
                 "default), with a warning naming the faces",
                 [](S& x) -> bool& { return x.run.allow_folded_plan; });
}

const OptionSchema<MarionetteSettings>& Schema() {
  static const OptionSchema<MarionetteSettings> schema = [] {
    OptionSchema<MarionetteSettings> s;
    AddGuideOptions(&s);
    AddFitOptions(&s);
    AddSolveOptions(&s);
    return s;
  }();
  return schema;
}

// The inputs in memory, named by their sources in messages.
void SetInputs(const RunInputs& inputs, MarionetteRunOptions* o) {
  if (const PolyMesh* plan = inputs.OptionalMesh("plan")) {
    o->plan = inputs.Source("plan");
    o->plan_mesh = *plan;
  }
  if (const PolyMesh* fit = inputs.OptionalMesh("fit")) {
    o->fit = inputs.Source("fit");
    o->fit_mesh = *fit;
  }
  const auto text = [&inputs](const char* name, std::string* source,
                              std::optional<std::string>* value) {
    if (const std::string* t = inputs.Text(name)) *source = inputs.Source(name), *value = *t;
  };
  text("guides", &o->guides, &o->guides_text);
  text("fit_heights", &o->fit_heights, &o->fit_heights_text);
  text("closed_strip", &o->closed_strip, &o->closed_strip_text);
}

// The run's description: its first line the headline, warnings apart, the rest progress.
void Describe(const std::string& description, const RunContext& context, RunResult* result) {
  std::istringstream lines(description);
  bool first = true;
  for (std::string line; std::getline(lines, line); first = false) {
    if (first)
      context.Headline(line);
    else if (line.rfind("warning: ", 0) == 0)
      result->Warn(line.substr(9));
    else
      context.Info(line);
  }
}

RunResult Run(const RunInputs& inputs, const nlohmann::json& values, const RunContext& context) {
  MarionetteRunOptions options = Schema().Apply(values).run;
  SetInputs(inputs, &options);
  const std::unique_ptr<MarionetteRun> run = MakeMarionetteRun(options);
  RunResult result;
  Describe(run->Description(), context, &result);
  result.tolerance_measure = run->ToleranceMeasure();
  result.tolerance = options.lift.tolerance;
  context.Columns({"max_constraint", result.tolerance_measure});
  result.report = run->Run([&context](const RunRecord& r) { return context.Record(r); });
  if (result.report.failed) return result;
  result.facts = run->Facts();
  // The input files are the report's "input" and input keys (RunResultJson).
  for (const char* input : {"input", "fit", "guides", "fit_heights", "closed_strip"})
    result.facts.erase(input);
  result.facts["tolerance"] = options.lift.tolerance;
  result.meshes["output"] = run->Result();
  std::string final = "final:";
  char value[64];
  for (const NamedValue& v : result.report.final) {
    std::snprintf(value, sizeof(value), " %.3e", v.value);
    final += " " + v.name + value;
  }
  result.Info(final);
  return result;
}

}  // namespace

ProblemSpec MarionetteSpec() {
  ProblemSpec spec;
  spec.name = "marionette";
  spec.summary =
      "Marionette mesh (002): planar quads over a fixed plan view. Every vertex moves on its own "
      "line (projection): vertically (the plan's z is ignored), perpendicular to an axis through "
      "it, or through a centre; guide values are heights, distances from the axis or distances "
      "from the centre. The plan is a regular grid in `grid` order with row and column or fit, "
      "or any disk-like quad mesh (singular vertices allowed, 002 §2.4) with guides: it is split "
      "into regular patches along the separatrices, and the guides must cross every strip of "
      "patches exactly once. A plan of any polygons (Kagome: triangles and hexagons, 002 §4.2), "
      "or a quad plan that is no grid, is lifted vertically from hold heights with the fairness "
      "of 002 eq. 17 fixing the rest. closed_strip lifts a closed strip instead (002 §2.5, eq. "
      "8).";
  spec.inputs = {
      {"plan", InputKind::kMesh,
       "Plan view: a quad mesh, or polygons with hold; vertex ids are 0-based in file order", false,
       true},
      {"guides", InputKind::kText,
       "Guide file for a plan of any connectivity, one entry a line ('#' comments): 'guide START "
       "NEXT V0 V1 ...' gives values to the straight mesh polyline from vertex START through its "
       "neighbour NEXT (on through inner vertices of even valence), one per polyline vertex; "
       "'vertex ID VALUE' gives one vertex"},
      {"fit", InputKind::kMesh,
       "Target mesh with the plan's vertex order: least-squares fit of its heights (002 eq. 14) "
       "instead of guide curves (vertical grid plans)"},
      {"fit_heights", InputKind::kText,
       "A partial target: lines 'VERTEX HEIGHT'; the least-squares fit follows only these "
       "vertices (they must determine the lift; solver direct)"},
      {"closed_strip", InputKind::kText,
       "Closed strip instead of a plan (002 §2.5): one line per vertex pair 'XI YI ZI XO YO' "
       "(inner vertex with its prescribed height, outer vertex), quads (inner i, outer i, outer "
       "i+1, inner i+1) closing back to the first pair; several rings with more outer x y pairs "
       "per line. Reports a of eq. 8: a != 1 gives the one closing outer height; a = 1 projects "
       "the inner heights onto V.Z = 0"}};
  spec.outputs = {{"output", OutputKind::kMesh, "the lifted mesh", true, true}};
  spec.options = Schema().specs();
  spec.log_measures = {"max_constraint", "max_planarity"};
  spec.run = Run;
  return spec;
}

}  // namespace gproj::marionette
