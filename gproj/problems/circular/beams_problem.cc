// `beams` in the registry: torsion-free node axes and beams of constant height on a circular
// mesh (000 §4.3).
#include <chrono>
#include <cstdio>

#include "gproj/geometry/render/svg_render.h"
#include "gproj/problems/circular/circular_mesh.h"
#include "gproj/problems/circular/torsion_free_beams.h"
#include "gproj/problems/mesh/mesh_outputs.h"
#include "gproj/problems/run/builtin_problems.h"
#include "gproj/problems/run/construction.h"

namespace gproj::circular {
namespace {

struct BeamsSettings {
  BeamOptions options;
  double axis_length = 0.0;    // 0: 2 h
  double gap_tolerance = 0.0;  // 0: none
};

const OptionSchema<BeamsSettings>& Schema() {
  static const OptionSchema<BeamsSettings> schema = [] {
    using S = BeamsSettings;
    OptionSchema<S> s;
    s.Custom("height", OptionType::kNumber, "Beam height, and the offset distance", nullptr,
             [](const nlohmann::json& v, S* x) { x->options.height = v.get<double>(); })
        .Positive()
        .Required()
        .Unit("input units");
    s.Custom("width", OptionType::kNumber,
             "Beam thickness across its plane (not given: 4% of the mean edge)", nullptr,
             [](const nlohmann::json& v, S* x) { x->options.width = v.get<double>(); })
        .Positive()
        .Unit("input units");
    s.Custom("axis_length", OptionType::kNumber,
             "Length of the axes output (not given: twice the height)", nullptr,
             [](const nlohmann::json& v, S* x) { x->axis_length = v.get<double>(); })
        .Positive()
        .Unit("input units");
    s.Field<bool>("optimise", OptionType::kBool,
                  "Choose the first axis to minimise the height gaps (off: keep it at the "
                  "central node's mean face normal)",
                  [](S& x) -> bool& { return x.options.optimise; })
        .Negation("no_optimise");
    s.Custom("gap_tolerance", OptionType::kNumber,
             "Largest height gap at a node (in units of the height) for convergence (not given: "
             "none)",
             nullptr, [](const nlohmann::json& v, S* x) { x->gap_tolerance = v.get<double>(); })
        .Positive();
    s.Field<double>("circularity_tolerance", OptionType::kNumber,
                    "Largest closing angle of the axes around a face, at most 0.01",
                    [](S& x) -> double& { return x.options.circularity_tolerance; })
        .Range(1e-300, 1e-2)
        .Unit("rad");
    return s;
  }();
  return schema;
}

// The log's lines after the construction.
void Describe(const BeamLayout& layout, const BeamOptions& options, RunResult* result) {
  const NamedValues& m = layout.measures;
  char line[512];
  std::snprintf(line, sizeof(line),
                "node axes by mirror images across the edges from vertex %d; they close around "
                "every face to %.2e rad",
                layout.root, ValueOf(m, "max_closing_angle"));
  result->Info(line);
  std::snprintf(line, sizeof(line),
                "beams: max non-planarity %.2e (per mean edge); offset at distance %g: max edge "
                "angle %.2e rad, distance error %.2e",
                ValueOf(m, "max_beam_planarity"), options.height, ValueOf(m, "max_offset_angle"),
                ValueOf(m, "max_offset_distance_error"));
  result->Info(line);
  std::snprintf(line, sizeof(line),
                "height gaps at the nodes (/ h): max %.4g, mean %.4g (%s; from the face normal: "
                "max %.4g)",
                ValueOf(m, "max_height_gap"), ValueOf(m, "mean_height_gap"),
                options.optimise ? "first axis optimised" : "first axis not optimised",
                ValueOf(m, "initial_max_height_gap"));
  result->Info(line);
}

RunResult Run(const RunInputs& inputs, const nlohmann::json& values, const RunContext& context) {
  const BeamsSettings settings = Schema().Apply(values);
  const BeamOptions& options = settings.options;
  const PolyMesh& mesh = inputs.Mesh("mesh");
  char line[512];
  std::snprintf(line, sizeof(line), "%s: %zu vertices, %zu faces, %zu edges; beams of height %g",
                inputs.Source("mesh").c_str(), mesh.n_vertices(), mesh.n_faces(), mesh.n_edges(),
                options.height);
  context.Headline(line);
  const NamedValues input_measures = MeasureCircularMesh(mesh);
  context.Info(CircularMeasuresLine("input", input_measures));
  Construction construction(ConstructionMethod::kClosedForm, "mirror images");
  const BeamLayout layout = TorsionFreeBeams(mesh, options);
  construction.Stop();
  const NamedValues& m = layout.measures;
  NamedValues initial = input_measures;
  initial.push_back({"max_height_gap", ValueOf(m, "initial_max_height_gap")});
  const bool met =
      settings.gap_tolerance <= 0.0 || ValueOf(m, "max_height_gap") <= settings.gap_tolerance;
  RunResult result;
  result.report = construction.Finish(initial, m, met);
  result.tolerance_measure = "max_height_gap";
  result.tolerance = settings.gap_tolerance;
  if (result.report.failed) return result;
  Describe(layout, options, &result);
  result.facts = {
      {"height", options.height}, {"root_vertex", layout.root}, {"optimised", options.optimise}};
  if (settings.gap_tolerance > 0.0) result.facts["gap_tolerance"] = settings.gap_tolerance;
  result.meshes["output"] = layout.beams;
  if (context.Wants("axes"))
    result.texts["axes"] =
        AxesObj(mesh, layout.axis,
                settings.axis_length > 0.0 ? settings.axis_length : 2.0 * options.height);
  if (context.Wants("offset")) result.meshes["offset"] = layout.offset;
  std::snprintf(line, sizeof(line), "Torsion-free beams, %zu beams, height %g, max gap %.2g h",
                mesh.n_edges(), options.height, ValueOf(m, "max_height_gap"));
  AddMeshPicture(context, "picture", layout.beams, line, &result);
  return result;
}

}  // namespace

ProblemSpec BeamsSpec() {
  ProblemSpec spec;
  spec.name = "beams";
  spec.summary =
      "Torsion-free beams on a circular mesh (000 §4.3): node axes by mirror images across the "
      "edges (they close around a face inscribed in a circle), so every beam is planar and the "
      "offset mesh at constant distance is parallel; beams of constant height as solids; the "
      "first axis chosen to minimise the height gaps at the nodes. Not converged when "
      "gap_tolerance is not met.";
  spec.inputs = {
      {"mesh", InputKind::kMesh, "Circular mesh (every face inscribed in a circle)", true}};
  spec.outputs = {{"output", OutputKind::kMesh, "the beams, one box per edge", true},
                  {"axes", OutputKind::kSegments, "the node axes as OBJ line segments"},
                  {"offset", OutputKind::kMesh, "the offset mesh (parallel, at the height)"},
                  {"picture", OutputKind::kSvg, "a shaded picture of the beams"}};
  spec.options = Schema().specs();
  spec.run = Run;
  return spec;
}

}  // namespace gproj::circular
