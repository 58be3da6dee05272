// `planarize` in the registry: PQ (or circular) planarisation of a quad mesh, and of polygon
// meshes (a plane per face of 4 or more vertices).
#include <algorithm>
#include <cstdio>

#include "gproj/geometry/mesh/polygon_shape.h"
#include "gproj/problems/mesh/mesh_options.h"
#include "gproj/problems/mesh/mesh_outputs.h"
#include "gproj/problems/nets/diagonal_mesh.h"
#include "gproj/problems/nets/hnet.h"
#include "gproj/problems/pq/pq_planarization.h"
#include "gproj/problems/run/builtin_problems.h"
#include "gproj/problems/run/shared_options.h"

namespace gproj::pq {
namespace {

struct PlanarizeSettings {
  PQPlanarizationOptions problem;
  SolverKind solver = SolverKind::kGuidedProjection;
  std::string net = "edges";
  int diagonal_colour = -1;  // not given (both diagonal meshes with net diagonal)
};

const OptionSchema<PlanarizeSettings>& Schema() {
  static const OptionSchema<PlanarizeSettings> schema = [] {
    using S = PlanarizeSettings;
    OptionSchema<S> s;
    AddMethodOption<S>(&s, [](S& x) -> SolverKind& { return x.solver; });
    s.Field<double>(
         "tolerance", OptionType::kNumber,
         "Stop when max planarity (diagonal distance; for a polygon of 5 or more vertices, twice "
         "its largest distance from its least-squares plane; / mean edge length) is <= "
         "this",
         [](S& x) -> double& { return x.problem.tolerance; })
        .Positive();
    s.Field<double>("closeness", OptionType::kNumber,
                    "Weight of closeness to the input vertices (mesh scaled to mean edge 1)",
                    [](S& x) -> double& { return x.problem.closeness_weight; })
        .NonNegative();
    s.Field<bool>("circular", OptionType::kBool,
                  "Circular quads (planar and concyclic, 000 §2) instead of planar ones; the "
                  "tolerance also bounds the concyclicity (distance to the fitted circle / mean "
                  "edge)",
                  [](S& x) -> bool& { return x.problem.circular; });
    s.Field<int>("fairness_order", OptionType::kInt, "2: second differences, 3: third differences",
                 [](S& x) -> int& { return x.problem.fairness_order; })
        .Range(2, 3);
    s.Field<double>("ceres_soft_scale", OptionType::kNumber,
                    "With solver ceres: fixed factor on the closeness and fairness weights (0: "
                    "tolerance / 100)",
                    [](S& x) -> double& { return x.problem.ceres_soft_scale; })
        .NonNegative();
    AddSolverOptions<S>(&s, [](S& x) -> SolverOptions& { return x.problem.solver; });
    AddPanelBoundsOptions<S>(&s, [](S& x) -> PanelBoundsOptions& { return x.problem.panels; });
    AddVertexControlOptions<S>(&s,
                               [](S& x) -> VertexControlOptions& { return x.problem.vertices; });
    s.Field<std::string>(
         "net", OptionType::kChoice,
         "Which faces to make planar: edges (the mesh's own faces) or diagonal (the faces of the "
         "quad mesh's diagonal meshes: the ring of every inner vertex, whose edges are the quads' "
         "diagonals; the result keeps the input's faces)",
         [](S& x) -> std::string& { return x.net; })
        .Choices({"edges", "diagonal"});
    s.Optional<int>("diagonal_colour", OptionType::kInt,
                    "With net diagonal: one diagonal mesh only, by the colour of its vertices (0: "
                    "the one through vertex 0; the other colour's vertices stay in place); not "
                    "given: both",
                    [](S& x) -> int& { return x.diagonal_colour; })
        .Range(0, 1);
    return s;
  }();
  return schema;
}

void AddShortfalls(const PQPlanarization& pq, const std::string& panels,
                   const nets::DiagonalMesh* diagonal, RunResult* result) {
  const PQPlanarizationOptions& options = pq.options();
  const std::vector<int> above = pq.FacesAboveTolerance();
  if (!above.empty())
    result->shortfalls.push_back(
        std::to_string(above.size()) + " " + panels +
        " above the tolerance, worst first: " + nets::FacesNamed(above, diagonal));
  const std::vector<int> held = pq.FacesAtAngleBound();
  char bound[64];
  std::snprintf(bound, sizeof(bound), "%g", options.panels.min_angle_deg);
  if (!held.empty())
    result->shortfalls.push_back(std::to_string(held.size()) + " " + panels +
                                 " sit on their corner-angle bound (`min_angle` " + bound +
                                 "): " + nets::FacesNamed(held, diagonal));
  const double outside = ValueOf(pq.MeasureAt(pq.problem().x()), "out_of_range_edges");
  if (outside > 0.0)
    result->shortfalls.push_back(std::to_string(static_cast<int>(outside)) +
                                 " edges end outside the `edge_length` range");
  const std::vector<std::array<int, 2>> edges = pq.EdgesAtLengthBound();
  if (!edges.empty())
    result->shortfalls.push_back(
        std::to_string(edges.size()) + " edges sit on their length bound (" +
        (options.panels.min_edge_length > 0.0 || options.panels.max_edge_length > 0.0
             ? "`edge_length`"
             : "a tenth of their input length") +
        "): " + EdgeList(edges));
}

// Quads folded across a diagonal: the normals of the two triangles of a split more than 90°
// apart (a skew quad can fold so while its corners, measured in the diagonals' plane, all turn
// the same way).
int FoldedQuads(const std::vector<QuadShape>& shapes) {
  return static_cast<int>(std::count_if(shapes.begin(), shapes.end(),
                                        [](const QuadShape& q) { return q.kink_deg > 90.0; }));
}

// With net diagonal: the written quads' shapes against the input's (the report's measures are
// the rings'), and not converged when more quads fold than in the input.
void DescribeKeptQuads(const PolyMesh& input, const PolyMesh& written, RunResult* result) {
  const std::vector<QuadShape> before = MeasureQuadShapes(input),
                               after = MeasureQuadShapes(written);
  const QuadShapeSummary a = Summarize(before), b = Summarize(after);
  const int folded_before = FoldedQuads(before), folded_after = FoldedQuads(after);
  char line[320];
  std::snprintf(line, sizeof(line),
                "quads kept: non-convex %d -> %d, folded across a diagonal (triangles more than 90 "
                "deg apart) %d -> %d, smallest corner angle %.1f -> %.1f deg, max kink %.3g -> "
                "%.3g deg",
                a.non_convex, b.non_convex, folded_before, folded_after, a.min_angle_deg,
                b.min_angle_deg, a.max_kink_deg, b.max_kink_deg);
  result->Info(line);
  result->facts["quads"] = {{"non_convex", b.non_convex},
                            {"folded", folded_after},
                            {"min_corner_angle_deg", b.min_angle_deg},
                            {"max_kink_deg", b.max_kink_deg}};
  if (folded_after > folded_before && !result->report.failed) {
    result->report.converged = false;
    result->report.termination = std::to_string(folded_after - folded_before) +
                                 " more quads fold across a diagonal than in the input (the rings "
                                 "cannot all be planar near this mesh without folding it)";
  }
}

RunResult Run(const RunInputs& inputs, const nlohmann::json& values, const RunContext& context) {
  PlanarizeSettings settings = Schema().Apply(values);
  PQPlanarizationOptions& options = settings.problem;
  const PolyMesh& given = inputs.Mesh("mesh");
  options.vertices.fixed = inputs.VertexIds("fixed");
  std::string why;
  if (!options.IsValid(&why)) throw InputError("invalid option: " + why);
  // With net diagonal the faces made planar are the diagonal meshes' on the input's vertices.
  const bool diagonal = settings.net == "diagonal";
  if (!diagonal && settings.diagonal_colour >= 0)
    throw InputError("`diagonal_colour` chooses a diagonal mesh: it needs `net` diagonal");
  if (diagonal && options.circular)
    throw InputError("`circular` applies to `net` edges (the faces of the mesh itself)");
  nets::DiagonalMesh diagonal_faces;
  if (diagonal) {
    for (auto f : given.faces())
      if (given.valence(f) != 4)
        throw InputError(inputs.Source("mesh") + ": face " + std::to_string(f.idx()) + " has " +
                         std::to_string(given.valence(f)) +
                         " vertices; `net` diagonal needs a quad mesh");
    try {
      diagonal_faces = nets::MakeDiagonalFaces(given, settings.diagonal_colour);
    } catch (const InputError& e) {
      throw InputError(inputs.Source("mesh") + ": `net` diagonal: " + e.what());
    }
  }
  // One diagonal mesh: the other colour's vertices are held where they are.
  if (diagonal && settings.diagonal_colour >= 0) {
    const std::vector<int> colours = nets::TwoColourVertices(given);
    std::vector<int>& fixed = options.vertices.fixed;
    for (int v = 0; v < static_cast<int>(colours.size()); ++v)
      if (colours[v] != settings.diagonal_colour) fixed.push_back(v);
    std::sort(fixed.begin(), fixed.end());
    fixed.erase(std::unique(fixed.begin(), fixed.end()), fixed.end());
  }
  const PolyMesh& input = diagonal ? diagonal_faces.mesh : given;
  const PolygonMeshSummary panels = SummarizePolygons(input);
  for (auto f : input.faces())
    if (options.circular && input.valence(f) != 4)
      throw InputError(inputs.Source("mesh") + ": face " + std::to_string(f.idx()) + " has " +
                       std::to_string(input.valence(f)) +
                       " vertices; a circular mesh is made of quads");
  if (panels.faces_by_corners.size() <= 4 && input.n_faces() > 0)
    throw InputError(inputs.Source("mesh") +
                     ": every face is a triangle; planarisation needs faces of 4 or more "
                     "vertices (gproj dual makes a polygon mesh of a triangle mesh)");
  // With net diagonal the input's quads keep their panel bounds too (they are what is written).
  PQPlanarization pq(input, options, inputs.OptionalMesh("reference"), diagonal ? &given : nullptr);
  const bool all_quads = panels.faces_by_corners.size() == 5 &&
                         panels.faces_by_corners[4] == static_cast<int>(input.n_faces());
  const std::string face_name = diagonal ? "diagonal faces" : all_quads ? "quads" : "faces";
  const bool ceres = settings.solver == SolverKind::kCeres;
  if (!ceres && options.ceres_soft_scale != PQPlanarizationOptions().ceres_soft_scale)
    throw InputError("`ceres_soft_scale` applies to `solver` ceres only");

  char line[512];
  const PlanarityMeasures initial = pq.Measures();
  std::snprintf(line, sizeof(line), "%s: %zu vertices, %zu %s, %d variables, solver %s",
                inputs.Source("mesh").c_str(), input.n_vertices(), input.n_faces(),
                face_name.c_str(), pq.problem().layout().num_variables(),
                ceres ? "ceres" : LinearSolverTypeName(options.solver.linear_solver));
  context.Headline(line);
  if (diagonal)
    context.Info(std::string("net diagonal: the faces planarised are the rings of the inner "
                             "vertices (") +
                 (settings.diagonal_colour >= 0
                      ? "the diagonal mesh of colour " + std::to_string(settings.diagonal_colour)
                      : std::string("both diagonal meshes")) +
                 "); the result keeps the input's " + std::to_string(given.n_faces()) + " quads");
  std::snprintf(line, sizeof(line),
                "start: max planarity %.3e, mean %.3e (diagonal distance / mean edge)",
                initial.max_planarity, initial.mean_planarity);
  context.Info(line);
  if (!all_quads && !diagonal) {
    context.Info("faces: " + FaceCountsText(panels.faces_by_corners) +
                 " (a plane per face of 4 or more vertices; triangles are left to closeness and "
                 "fairness)");
    std::vector<int> reflex;
    for (auto f : input.faces())
      if (input.valence(f) > 4 && !MeasurePolygonShape(FacePoints(input, f)).convex)
        reflex.push_back(f.idx());
    if (!reflex.empty() && options.panels.corners)
      context.Info(std::to_string(reflex.size()) + " polygons are not convex in the input (" +
                   FaceList(reflex) +
                   "; a planar polygon mesh cannot be convex where the surface is negatively "
                   "curved): their reflex corners are kept from getting worse, not made convex");
    const std::vector<int>& unbounded = pq.panel_bounds().unbounded_polygons;
    if (!unbounded.empty() && options.panels.corners)
      context.Info(std::to_string(unbounded.size()) + " faces of more than " +
                   std::to_string(kMaxBoundedCorners) + " vertices have no corner bounds (" +
                   FaceList(unbounded) + ")");
  }

  const RunCallback record = [&context, &pq](const RunRecord& r) {
    const bool go_on = context.Record(r);
    context.Iterate(r.iteration, pq.MeasuredMesh());
    return go_on;
  };
  RunResult result;
  result.report = pq.RunWith(settings.solver, record, context.soft_free_start);
  result.tolerance_measure = "max_planarity";
  result.tolerance = options.tolerance;
  const PolyMesh mesh = pq.Result();
  result.facts = PlanarizationFacts(input, mesh, options);
  result.facts.erase("options");
  result.facts["fixed_vertices"] = options.vertices.fixed.size();
  if (!all_quads) result.facts["faces_by_corners"] = panels.faces_by_corners;
  result.facts["net"] = settings.net;
  if (diagonal) {
    if (settings.diagonal_colour >= 0) result.facts["diagonal_colour"] = settings.diagonal_colour;
    result.facts["diagonal_face_centres"] = diagonal_faces.face_centres;
  }
  if (context.soft_free_start) result.facts["soft_free_start"] = true;
  if (result.report.failed) return result;

  const PlanarityMeasures final_measures = pq.Measures();
  PolyMesh written = diagonal ? given : mesh;  // with net diagonal: the input's quads, moved
  if (diagonal) {
    for (auto v : written.vertices()) written.set_point(v, mesh.point(v));
    if (context.Wants("diagonal_mesh")) result.meshes["diagonal_mesh"] = mesh;
  }
  result.meshes["output"] = written;
  std::snprintf(line, sizeof(line), "%zu %s, max planarity %.2e", input.n_faces(),
                face_name.c_str(), final_measures.max_planarity);
  AddFaceOutputTexts(mesh, RelativeFacePlanarity(mesh, options.circular),
                     PlanarityColourScale(mesh, options.circular),
                     QuadShapesCsv(mesh, options.circular), line, context, &result);
  std::snprintf(line, sizeof(line),
                "final: max planarity %.3e, mean %.3e, max displacement %.3e of the bbox diagonal",
                final_measures.max_planarity, final_measures.mean_planarity,
                final_measures.max_displacement);
  result.Info(line);
  if (final_measures.max_concyclicity >= 0.0) {
    std::snprintf(line, sizeof(line),
                  "       max concyclicity %.3e (distance to the fitted circle / mean edge)",
                  final_measures.max_concyclicity);
    result.Info(line);
  }
  AddPanelMessages(options.circular ? "a circular mesh"
                   : diagonal       ? "planar diagonal meshes"
                   : all_quads      ? "a PQ (conjugate) mesh"
                                    : "a planar polygon mesh",
                   diagonal ? given : input, written, 10.0, final_measures.max_displacement,
                   &result);
  if (diagonal) DescribeKeptQuads(given, written, &result);
  if (!result.report.converged) {
    AddShortfalls(pq, face_name, diagonal ? &diagonal_faces : nullptr, &result);
    const std::vector<int> held = pq.KeptFacesAtAngleBound();
    if (!held.empty())
      result.shortfalls.push_back(std::to_string(held.size()) +
                                  " quads sit on their corner-angle bound: " + FaceList(held));
  }
  return result;
}

}  // namespace

ProblemSpec PlanarizeSpec() {
  ProblemSpec spec;
  spec.name = "planarize";
  spec.summary =
      "PQ planarisation: make every quad of a mesh planar (or circular: planar and concyclic) "
      "while staying close to the input and fair. Polygon meshes too (hexagonal, "
      "hex-dominant: every face of 4 or more vertices planar; triangles are left to closeness "
      "and fairness).";
  spec.inputs = {
      {"mesh", InputKind::kMesh,
       "Quad mesh (or any polygon mesh; circular needs quads) to planarise", true, false,
       /*flat_face_corners=*/4},
      {"reference", InputKind::kMesh,
       "Reference surface (triangle or polygon mesh): vertices keep close to it through the "
       "tangent plane of their closest point (sliding along it) instead of to their start"},
      {"fixed", InputKind::kVertexIds,
       "Vertices that do not move at all (0-based ids; returned bit for bit)"}};
  spec.outputs = {
      {"output", OutputKind::kMesh, "the planarised mesh", true, true},
      {"picture", OutputKind::kSvg,
       "a shaded picture of the result, each face coloured by its planarity"},
      {"face_values", OutputKind::kCsv,
       "per-face values: face, planarity (/ mean edge), planarity_abs (input units), kink_deg "
       "(between the quad's two triangles), min_angle_deg (and concyclicity when circular)"},
      {"heatmap", OutputKind::kPly,
       "the result with a colour per face (planarity, log scale; the scale is in the report)"},
      {"diagonal_mesh", OutputKind::kMesh,
       "with net diagonal: the planarised diagonal faces on the input's vertices (the picture, "
       "face values and heat map show these faces)"}};
  spec.options = Schema().specs();
  spec.log_measures = {"max_planarity", "mean_planarity", "non_convex_quads",
                       "min_corner_angle_deg"};
  spec.run = Run;
  return spec;
}

}  // namespace gproj::pq
