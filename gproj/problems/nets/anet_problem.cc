// `anet` in the registry: planar vertex stars of a quad mesh along asymptotic directions.
#include <cstdio>

#include "gproj/problems/mesh/mesh_outputs.h"
#include "gproj/problems/nets/anet.h"
#include "gproj/problems/nets/anet_options.h"
#include "gproj/problems/run/builtin_problems.h"
#include "gproj/problems/run/shared_options.h"

namespace gproj::nets {
namespace {

struct ANetSettings {
  ANetOptions problem;
  SolverKind solver = SolverKind::kGuidedProjection;
  std::string star_form = "normals";
  std::string net = "edges";
};

const OptionSchema<ANetSettings>& Schema() {
  static const OptionSchema<ANetSettings> schema = [] {
    using S = ANetSettings;
    OptionSchema<S> s;
    AddANetOptions<S>(
        &s, [](S& x) -> ANetOptions& { return x.problem; },
        [](S& x) -> SolverKind& { return x.solver; },
        [](S& x) -> std::string& { return x.star_form; });
    s.Field<std::string>(
         "net", OptionType::kChoice,
         "Whose stars must be planar: edges (each vertex with its neighbours: the mesh is the "
         "A-net) or diagonal (each vertex with the corners opposite it in its quads: the mesh's "
         "two diagonal meshes are A-nets, for meshes whose diagonals follow the asymptotic "
         "directions; the quads, their bounds and fairness stay the mesh's own)",
         [](S& x) -> std::string& { return x.net; })
        .Choices({"edges", "diagonal"});
    return s;
  }();
  return schema;
}

RunResult Run(const RunInputs& inputs, const nlohmann::json& values, const RunContext& context) {
  ANetSettings settings = Schema().Apply(values);
  ANetOptions& options = settings.problem;
  options.star_form = StarFormOf(settings.star_form);
  options.net = settings.net == "diagonal" ? NetKind::kDiagonals : NetKind::kEdges;
  const bool diagonal = options.net == NetKind::kDiagonals;
  const PolyMesh& mesh = inputs.Mesh("mesh");
  const std::string source = inputs.Source("mesh");
  options.vertices.fixed = inputs.VertexIds("fixed");
  CheckANetTopology(mesh, source);
  std::unique_ptr<ANet> anet;
  try {
    anet = std::make_unique<ANet>(mesh, inputs.OptionalMesh("reference"), options);
  } catch (const InputError& e) {
    throw InputError(source + ": " + e.what());
  }
  char line[512];
  std::snprintf(line, sizeof(line), "%s: %zu vertices, %zu quads, %d variables%s", source.c_str(),
                mesh.n_vertices(), mesh.n_faces(), anet->problem().layout().num_variables(),
                diagonal ? "; stars along the diagonals" : "");
  context.Headline(line);

  const RunCallback record = [&context, &anet](const RunRecord& r) {
    const bool go_on = context.Record(r);
    context.Iterate(r.iteration, anet->MeasuredMesh());
    return go_on;
  };
  RunResult result;
  result.report = anet->RunWith(settings.solver, record, context.soft_free_start);
  result.tolerance_measure = "max_star_planarity";
  result.tolerance = options.tolerance;
  const PolyMesh net = anet->Result();
  result.facts = ANetFacts(mesh, net, options.net);
  result.facts["fixed_vertices"] = options.vertices.fixed.size();
  if (context.soft_free_start) result.facts["soft_free_start"] = true;
  if (result.report.failed) return result;

  const StarPlanarityMeasures m = anet->Measures();
  result.meshes["output"] = net;
  const char* star = diagonal ? "diagonal star" : "star";
  std::snprintf(line, sizeof(line), "A-net%s: %zu quads, max %s planarity %.2e",
                diagonal ? " on the diagonals" : "", mesh.n_faces(), star, m.max_star_planarity);
  AddFaceOutputTexts(net, FaceStarPlanarity(net, options.net),
                     StarPlanarityColourScale(net, options.net),
                     ANetFaceValuesCsv(net, options.net), line, context, &result);
  std::snprintf(line, sizeof(line),
                "final: max %s planarity %.3e, mean %.3e, max displacement %.3e of the bbox "
                "diagonal",
                star, m.max_star_planarity, m.mean_star_planarity, m.max_displacement);
  result.Info(line);
  AddPanelMessages(
      diagonal ? "an A-net on its diagonals (asymptotic diagonals)" : "an A-net (asymptotic)", mesh,
      net, kANetShapeChangeDeg, m.max_displacement, &result);
  if (!result.report.converged && !BoundaryControlNote(options.vertices).empty())
    result.shortfalls.push_back(BoundaryControlNote(options.vertices));
  return result;
}

}  // namespace

ProblemSpec ANetSpec() {
  ProblemSpec spec;
  spec.name = "anet";
  spec.summary =
      "A-net (004 §3.2): make the vertex stars of a quad mesh roughly along asymptotic "
      "directions planar, close to a reference surface (the input itself by default) and fair.";
  spec.inputs = {
      {"mesh", InputKind::kQuadMesh,
       "Quad mesh roughly along asymptotic directions (inner vertices of even valence)", true},
      {"reference", InputKind::kMesh,
       "Reference surface (polygon mesh) to stay close to; default: the input itself"},
      {"fixed", InputKind::kVertexIds,
       "Vertices that do not move at all (0-based ids; returned bit for bit)"}};
  spec.outputs = {
      {"output", OutputKind::kMesh, "the A-net", true, true},
      {"picture", OutputKind::kSvg,
       "a shaded picture of the result, each face coloured by the star planarity of its corners"},
      {"face_values", OutputKind::kCsv,
       "per-face values: face, star_planarity (largest of its corners), kink_deg, min_angle_deg"},
      {"heatmap", OutputKind::kPly,
       "the result with a colour per face (star planarity, log scale; the scale is in the "
       "report)"}};
  spec.options = Schema().specs();
  spec.log_measures = {"max_star_planarity", "mean_star_planarity", "non_convex_quads",
                       "min_corner_angle_deg"};
  spec.run = Run;
  return spec;
}

}  // namespace gproj::nets
