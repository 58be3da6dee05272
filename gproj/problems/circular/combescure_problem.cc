// `combescure` in the registry: a parallel mesh of a planar quad grid (000 §2.4–2.5).
#include <cstdio>

#include "gproj/geometry/mesh/quad_grid.h"
#include "gproj/geometry/render/svg_render.h"
#include "gproj/problems/circular/circular_mesh.h"
#include "gproj/problems/circular/combescure.h"
#include "gproj/problems/mesh/mesh_outputs.h"
#include "gproj/problems/run/builtin_problems.h"
#include "gproj/problems/run/shared_options.h"

namespace gproj::circular {
namespace {

struct CombescureSettings {
  CombescureOptions options;
  SolverKind solver = SolverKind::kDirect;
  std::vector<double> row, column, origin;  // empty: the reference's (scaled) / unchanged
  double row_scale = 1.0, column_scale = 1.0;
};

const OptionSchema<CombescureSettings>& Schema() {
  static const OptionSchema<CombescureSettings> schema = [] {
    using S = CombescureSettings;
    OptionSchema<S> s;
    AddSolverChoice<S>(&s, "solver",
                       "direct: propagation (linear time); gp: guided projection on "
                       "edge-parallelism rows; ceres: Levenberg-Marquardt on the same rows (the "
                       "cross-check)",
                       [](S& x) -> SolverKind& { return x.solver; },
                       {{"direct", SolverKind::kDirect},
                        {"gp", SolverKind::kGuidedProjection},
                        {"ceres", SolverKind::kCeres}});
    s.Optional<std::vector<double>>(
         "row_lengths", OptionType::kNumbers,
         "Signed lengths of edges (0, j) -> (0, j+1) (not given: the reference's times "
         "row_scale)",
         [](S & x) -> auto& { return x.row; })
        .Count(0, "L,L,...");
    s.Optional<std::vector<double>>(
         "column_lengths", OptionType::kNumbers,
         "Signed lengths of edges (i, 0) -> (i+1, 0) (not given: the reference's times "
         "column_scale)",
         [](S & x) -> auto& { return x.column; })
        .Count(0, "L,L,...");
    s.Field<double>("row_scale", OptionType::kNumber, "Scale of the reference's row lengths",
                    [](S& x) -> double& { return x.row_scale; })
        .Positive();
    s.Field<double>("column_scale", OptionType::kNumber, "Scale of the reference's column lengths",
                    [](S& x) -> double& { return x.column_scale; })
        .Positive();
    s.Optional<std::vector<double>>(
         "origin", OptionType::kNumbers, "Position of vertex (0, 0) (not given: unchanged)",
         [](S & x) -> auto& { return x.origin; })
        .Count(3, "X,Y,Z");
    s.Field<double>("tolerance", OptionType::kNumber,
                    "Largest reference planarity accepted (diagonal distance / mean edge)",
                    [](S& x) -> double& { return x.options.reference_tolerance; })
        .Positive();
    return s;
  }();
  return schema;
}

RunResult Run(const RunInputs& inputs, const nlohmann::json& values, const RunContext& context) {
  const CombescureSettings settings = Schema().Apply(values);
  const PolyMesh& reference = inputs.Mesh("mesh");
  const std::string source = inputs.Source("mesh");
  const GridShape shape = DetectGridShape(reference, source);
  CombescureLengths lengths = ReferenceLengths(reference, shape);
  for (double& l : lengths.row) l *= settings.row_scale;
  for (double& l : lengths.column) l *= settings.column_scale;
  if (!settings.row.empty()) lengths.row = settings.row;
  if (!settings.column.empty()) lengths.column = settings.column;
  if (!settings.origin.empty())
    lengths.origin = Eigen::Vector3d(settings.origin[0], settings.origin[1], settings.origin[2]);
  Combescure combescure(reference, shape, lengths, settings.options);
  const SolverKind solver = settings.solver;
  context.Headline(
      source + ": " + std::to_string(shape.rows) + " x " + std::to_string(shape.cols) + " faces; " +
      (solver == SolverKind::kGuidedProjection ? "guided projection with edge-parallelism rows"
       : solver == SolverKind::kCeres          ? "Levenberg-Marquardt on the edge-parallelism rows"
                                               : "propagation (000 eq. 4)"));
  context.Info(CircularMeasuresLine("reference", combescure.Measure()));
  const RunCallback record = [&context](const RunRecord& r) { return context.Record(r); };
  RunResult result;
  result.report = solver == SolverKind::kDirect  ? combescure.RunPropagation()
                  : solver == SolverKind::kCeres ? combescure.RunCeres(200, record)
                                                 : combescure.Run(record);
  result.tolerance_measure = "max_edge_parallelism_angle";
  result.tolerance = solver == SolverKind::kDirect ? settings.options.propagation_tolerance
                                                   : settings.options.tolerance;
  result.facts = {{"row_lengths", lengths.row}, {"column_lengths", lengths.column}};
  if (result.report.failed) return result;
  const double angle = ValueOf(result.report.final, "max_edge_parallelism_angle");
  char line[256];
  std::snprintf(line, sizeof(line), "solved in %.4f s; max edge-parallelism angle %.3e rad",
                result.report.seconds, angle);
  result.Info(line);
  result.Info(CircularMeasuresLine("result", result.report.final));
  const double min_ratio = ValueOf(result.report.final, "min_edge_length_ratio");
  if (min_ratio <= 0.0) {
    std::snprintf(line, sizeof(line),
                  "note: some edges are reversed (min length ratio %.3g): the parallel mesh folds "
                  "over",
                  min_ratio);
    result.Info(line);
  }
  result.meshes["output"] = combescure.Result();
  std::snprintf(line, sizeof(line), "Combescure transform, max edge angle %.1e rad", angle);
  AddMeshPicture(context, "picture", result.meshes["output"], line, &result);
  return result;
}

}  // namespace

ProblemSpec CombescureSpec() {
  ProblemSpec spec;
  spec.name = "combescure";
  spec.summary =
      "Combescure transformation (000 §2.4-2.5): a mesh with every edge parallel to a planar "
      "quad grid's (in `gproj grid` vertex order), from the edge lengths along row 0 and column "
      "0. Circular meshes stay circular.";
  spec.inputs = {{"mesh", InputKind::kQuadMesh, "Reference grid with planar quads", true}};
  spec.outputs = {{"output", OutputKind::kMesh, "the parallel mesh", true, true},
                  {"picture", OutputKind::kSvg, "a shaded picture of the result"}};
  spec.options = Schema().specs();
  spec.log_measures = {"max_edge_parallelism_angle", "max_planarity", "max_concyclicity"};
  spec.run = Run;
  return spec;
}

}  // namespace gproj::circular
