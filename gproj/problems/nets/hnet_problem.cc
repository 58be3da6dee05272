// `hnet` in the registry: an A-net extended to smoothly joined rational bilinear patches.
#include <algorithm>
#include <cstdio>
#include <string>
#include <vector>

#include "gproj/geometry/mesh/quad_shape.h"
#include "gproj/geometry/render/svg_render.h"
#include "gproj/problems/nets/anet_options.h"
#include "gproj/problems/nets/diagonal_mesh.h"
#include "gproj/problems/nets/hnet.h"
#include "gproj/problems/run/builtin_problems.h"

namespace gproj::nets {
namespace {

struct HNetSettings {
  HNetOptions options;
  SolverKind solver = SolverKind::kGuidedProjection;
  std::string star_form = "normals";
  int samples = 8;
  std::string net = "edges";
  int diagonal_colour = -1;  // not given (0 with net diagonal)
};

const OptionSchema<HNetSettings>& Schema() {
  static const OptionSchema<HNetSettings> schema = [] {
    using S = HNetSettings;
    OptionSchema<S> s;
    AddANetOptions<S>(
        &s, [](S& x) -> ANetOptions& { return x.options.anet; },
        [](S& x) -> SolverKind& { return x.solver; },
        [](S& x) -> std::string& { return x.star_form; });
    s.Field<int>("rounds", OptionType::kInt, "Alternations of weight and vertex updates at most",
                 [](S& x) -> int& { return x.options.max_rounds; })
        .Range(1, 1000);
    s.Field<double>("frame_weight", OptionType::kNumber, "Weight of frame-point planarity",
                    [](S& x) -> double& { return x.options.frame_weight; })
        .Positive();
    s.Field<bool>("allow_not_simply_connected", OptionType::kBool,
                  "Optimise meshes that are not simply connected (no exact extension exists in "
                  "general): the vertices and the shape parameters are solved for together",
                  [](S& x) -> bool& { return x.options.allow_not_simply_connected; });
    s.Field<int>("samples", OptionType::kInt, "Samples per patch edge of the surface_mesh output",
                 [](S& x) -> int& { return x.samples; })
        .Range(1, 200);
    s.Field<std::string>(
         "net", OptionType::kChoice,
         "Which net to extend: edges (the mesh itself) or diagonal (one of the mesh's two "
         "diagonal meshes, for meshes whose diagonals follow the asymptotic directions: its "
         "edges are the quads' diagonals, its faces the rings of the other vertices; the H-net's "
         "vertices are the input's of one colour)",
         [](S& x) -> std::string& { return x.net; })
        .Choices({"edges", "diagonal"});
    s.Optional<int>("diagonal_colour", OptionType::kInt,
                    "With net diagonal: which diagonal mesh, by the colour of its vertices (0, "
                    "the default: the one through vertex 0)",
                    [](S& x) -> int& { return x.diagonal_colour; })
        .Range(0, 1);
    return s;
  }();
  return schema;
}

// The live log's columns: the star measures of every iterate, the A-net step's and the rounds'.
std::vector<std::string> LogMeasures() {
  return {"max_star_planarity", "mean_star_planarity", "non_convex_quads", "min_corner_angle_deg"};
}

// One H-net round as a line of the log's table, with the table's header before round 0; the
// iterates of the next vertex update get their header again.
void LogRound(const HNetRound& r, const RunContext& context) {
  char line[256];
  if (r.round == 0) {
    context.Info("H-net rounds:");
    std::snprintf(line, sizeof(line), "%5s %14s %12s %12s %12s %12s %8s", "round", "max_angle_deg",
                  "W_change", "W_min", "W_max", "max_star", "iters");
    context.Info(line);
  }
  std::snprintf(line, sizeof(line), "%5d %14.3e %12.3e %12.4e %12.4e %12.3e %8d", r.round,
                r.max_tangent_angle_deg, r.weight_change, r.min_w, r.max_w,
                r.star.max_star_planarity, r.solver_iterations);
  context.Info(line);
  context.Columns(LogMeasures());
}

// The log's lines and the warnings after a run with rounds.
void Describe(const HNetSummary& summary, const HNetOptions& options, bool with_reference,
              RunResult* result) {
  const HNetRound& last = summary.rounds.back();
  char line[512];
  std::snprintf(line, sizeof(line),
                "final: max tangent-plane angle %.3e deg, W in [%.4g, %.4g], max star planarity "
                "%.3e, max displacement %.3e of the bbox diagonal",
                last.max_tangent_angle_deg, last.min_w, last.max_w, last.star.max_star_planarity,
                last.star.max_displacement);
  result->Info(line);
  if (with_reference) {
    std::snprintf(line, sizeof(line),
                  "distance to the reference surface: max %.3e of its bbox diagonal",
                  summary.max_reference_distance);
    result->Info(line);
  }
  if (!summary.equitwist_violations.empty())
    result->Warn(std::to_string(summary.equitwist_violations.size()) +
                 " inner edges violate the equitwist condition (listed in the report)");
  if (!summary.simply_connected) {
    std::snprintf(line, sizeof(line),
                  "note: the mesh is not simply connected, so no exact extension need exist: "
                  "round 0 propagated the weights over a spanning tree, round 1 optimised the "
                  "vertices and weights together (W near 1, W >= %g); the report lists the worst "
                  "edges",
                  options.min_shape_parameter);
    result->Info(line);
  }
}

RunResult Run(const RunInputs& inputs, const nlohmann::json& values, const RunContext& context) {
  HNetSettings settings = Schema().Apply(values);
  HNetOptions& options = settings.options;
  options.anet.star_form = StarFormOf(settings.star_form);
  options.solver = settings.solver;
  options.anet.vertices.fixed = inputs.VertexIds("fixed");
  const PolyMesh& input = inputs.Mesh("mesh");
  const std::string source = inputs.Source("mesh");
  CheckANetTopology(input, source);
  const PolyMesh* reference = inputs.OptionalMesh("reference");
  // The diagonal net: the H-net of one diagonal mesh, the input mesh its reference surface.
  const bool diagonal = settings.net == "diagonal";
  if (!diagonal && settings.diagonal_colour >= 0)
    throw InputError("`diagonal_colour` chooses a diagonal mesh: it needs `net` diagonal");
  const int colour = std::max(settings.diagonal_colour, 0);
  DiagonalMesh diagonal_mesh;
  const std::string diagonal_name = "its diagonal mesh of colour " + std::to_string(colour);
  if (diagonal) {
    try {
      diagonal_mesh = MakeDiagonalMesh(input, colour, DiagonalRings::kQuads);
    } catch (const InputError& e) {
      throw InputError(source + ": `net` diagonal: " + e.what());
    }
    if (reference == nullptr) reference = &input;
    for (int& v : options.anet.vertices.fixed) {
      if (diagonal_mesh.vertex_of[v] < 0) {
        const DiagonalMesh other = MakeDiagonalMesh(input, 1 - colour, DiagonalRings::kAll);
        throw InputError("`fixed`: vertex " + std::to_string(v) +
                         " is not on the diagonal mesh of colour " + std::to_string(colour) +
                         (other.vertex_of[v] >= 0
                              ? " (use `diagonal_colour` " + std::to_string(1 - colour) + " for it)"
                              : " nor on the other (no ring of an inner vertex contains it)"));
      }
      v = diagonal_mesh.vertex_of[v];
    }
    // With `weld`, the ids are the welded mesh's: given as the input's first vertex of each.
    const auto weld = inputs.weld_maps.find("mesh");
    if (weld != inputs.weld_maps.end()) {
      std::vector<int> first(input.n_vertices(), -1);
      for (std::size_t k = weld->second.size(); k-- > 0;) first[weld->second[k]] = k;
      for (int& v : diagonal_mesh.input_vertices) v = first[v];
      for (int& v : diagonal_mesh.face_centres) v = first[v];
      for (int& v : diagonal_mesh.open_rings) v = first[v];
    }
  }
  const PolyMesh& mesh = diagonal ? diagonal_mesh.mesh : input;
  // Rings of singular vertices are not quads: holes of the diagonal mesh.
  std::string open_rings;
  if (!diagonal_mesh.open_rings.empty()) {
    open_rings = std::to_string(diagonal_mesh.open_rings.size()) +
                 " rings of singular vertices (not quads) are left open as holes of the diagonal "
                 "mesh: vertices ";
    for (std::size_t k = 0; k < diagonal_mesh.open_rings.size() && k < 10; ++k)
      open_rings += (k ? ", " : "") + std::to_string(diagonal_mesh.open_rings[k]);
    if (diagonal_mesh.open_rings.size() > 10) open_rings += ", ...";
  }
  std::unique_ptr<HNet> hnet;
  try {
    hnet = std::make_unique<HNet>(mesh, reference, options);
  } catch (const InputError& e) {
    throw InputError(source + ": " + (diagonal ? diagonal_name + ": " : std::string()) + e.what() +
                     (open_rings.empty() ? std::string() : " (" + open_rings + ")"));
  }
  context.Headline(source + ": " + std::to_string(input.n_vertices()) + " vertices, " +
                   std::to_string(input.n_faces()) + " quads" +
                   (diagonal ? "; " + diagonal_name + ": " + std::to_string(mesh.n_vertices()) +
                                   " vertices, " + std::to_string(mesh.n_faces()) + " quads"
                             : std::string()));
  if (!open_rings.empty()) context.Info(open_rings);
  context.Info("A-net step:");
  const HNetSummary summary =
      hnet->Run([&context](const RunRecord& r) { return context.Record(r); },
                [&context](const HNetRound& r) { LogRound(r, context); });
  RunResult result;
  result.report = summary.report;
  result.facts = HNet::ReportFacts(summary);
  result.facts["net"] = diagonal ? "diagonal" : "edges";
  if (diagonal) {
    result.facts["diagonal_colour"] = colour;
    result.facts["input_vertices"] = diagonal_mesh.input_vertices;
    result.facts["open_rings"] = diagonal_mesh.open_rings;
  }
  result.tolerance_measure = "weight_change";
  result.tolerance = options.weight_tolerance;
  if (result.report.failed || summary.rounds.empty()) return result;

  const HNetRound& last = summary.rounds.back();
  nlohmann::json output = HNetJson(hnet->mesh(), hnet->weights());
  if (diagonal) output["input_vertices"] = diagonal_mesh.input_vertices;
  result.texts["output"] = output.dump(1) + "\n";
  if (context.Wants("surface_mesh"))
    result.meshes["surface_mesh"] =
        SampleHNetSurface(hnet->mesh(), hnet->weights(), settings.samples);
  if (context.Wants("picture")) {
    SvgOptions svg;
    char title[160];
    std::snprintf(title, sizeof(title),
                  "H-net: %zu patches, max tangent-plane angle %.2e deg, W in [%.4g, %.4g]",
                  hnet->mesh().n_faces(), last.max_tangent_angle_deg, last.min_w, last.max_w);
    svg.title = title;
    result.texts["picture"] =
        RenderMeshSvg(SampleHNetSurface(hnet->mesh(), hnet->weights(), 2), svg);
  }
  Describe(summary, options, reference != nullptr, &result);
  // Folded patches are named whatever the exit: a converged net may have them when the input
  // had them or with `allow_folds`.
  std::vector<int> non_convex;
  const std::vector<QuadShape> shapes = MeasureQuadShapes(hnet->mesh());
  for (std::size_t f = 0; f < shapes.size(); ++f)
    if (!shapes[f].convex) non_convex.push_back(static_cast<int>(f));
  if (!non_convex.empty())
    result.Warn(std::to_string(non_convex.size()) +
                (non_convex.size() == 1 ? " quad is" : " quads are") +
                " not convex (a corner turns against the quad's diagonal normal: its patch "
                "folds): " +
                FacesNamed(non_convex, diagonal ? &diagonal_mesh : nullptr));
  if (!result.report.converged && !summary.faces_at_angle_bound.empty()) {
    char bound[64];
    std::snprintf(bound, sizeof(bound), "%g", options.anet.panels.min_angle_deg);
    result.shortfalls.push_back(
        std::to_string(summary.faces_at_angle_bound.size()) +
        " quads sit on their corner-angle bound (`min_angle` " + bound +
        "), which keeps them from folding where the frame rows pull: " +
        FacesNamed(summary.faces_at_angle_bound, diagonal ? &diagonal_mesh : nullptr));
  }
  if (!result.report.converged && !BoundaryControlNote(options.anet.vertices).empty())
    result.shortfalls.push_back(BoundaryControlNote(options.anet.vertices));
  return result;
}

}  // namespace

ProblemSpec HNetSpec() {
  ProblemSpec spec;
  spec.name = "hnet";
  spec.summary =
      "H-net (004 §2-3): extend an A-net (running the A-net step first when needed) to smoothly "
      "joined rational bilinear patches: corner weights per patch, shape parameters propagated "
      "and scaled, vertices and weights alternated until the weights settle.";
  spec.inputs = {
      {"mesh", InputKind::kQuadMesh,
       "Quad mesh roughly along asymptotic directions (simply connected, inner vertices of even "
       "valence)",
       true},
      {"reference", InputKind::kMesh,
       "Reference surface (polygon mesh) to stay close to; default: the input itself"},
      {"fixed", InputKind::kVertexIds,
       "Vertices that do not move at all (0-based ids; returned bit for bit)"}};
  spec.outputs = {{"output", OutputKind::kJson,
                   "the H-net: vertices, quad faces, four corner weights per face", true},
                  {"surface_mesh", OutputKind::kMesh,
                   "a triangle mesh sampling every patch on a (samples + 1)^2 grid"},
                  {"picture", OutputKind::kSvg, "a shaded picture of the patchwork"}};
  spec.options = Schema().specs();
  spec.log_measures = LogMeasures();
  spec.run = Run;
  return spec;
}

}  // namespace gproj::nets
