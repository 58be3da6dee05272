// `dual` in the registry: the dual polygon mesh of a triangle mesh (gproj/geometry/mesh/
// dual_mesh.h), the start of a planar hexagonal or hex-dominant mesh for planarize.
#include <cstdio>

#include "gproj/geometry/mesh/dual_mesh.h"
#include "gproj/geometry/mesh/polygon_shape.h"
#include "gproj/problems/mesh/mesh_outputs.h"
#include "gproj/problems/run/builtin_problems.h"
#include "gproj/problems/run/construction.h"

namespace gproj::pq {
namespace {

struct DualSettings {
  std::string start = "centroids";
  std::string boundary = "drop";
};

const OptionSchema<DualSettings>& Schema() {
  static const OptionSchema<DualSettings> schema = [] {
    using S = DualSettings;
    OptionSchema<S> s;
    s.Field<std::string>(
         "start", OptionType::kChoice,
         "Where each dual vertex sits: centroids (of its triangle) or tangent_planes (where the "
         "tangent planes of its triangle's three vertices meet, where that is well conditioned; "
         "planar faces to first order, the start of Wang, Liu et al. 2008)",
         [](S& x) -> std::string& { return x.start; })
        .Choices({"centroids", "tangent_planes"});
    s.Field<std::string>(
         "boundary", OptionType::kChoice,
         "drop: faces for the interior vertices only; keep: boundary vertices get faces too, "
         "closed by the midpoints of their boundary edges and the vertex itself",
         [](S& x) -> std::string& { return x.boundary; })
        .Choices({"drop", "keep"});
    return s;
  }();
  return schema;
}

NamedValues PolygonValues(const PolygonMeshSummary& s) {
  NamedValues values = {{"max_planarity", s.max_planarity},
                        {"mean_planarity", s.mean_planarity},
                        {"non_convex_faces", static_cast<double>(s.non_convex)},
                        {"min_corner_angle_deg", s.min_angle_deg}};
  return values;
}

RunResult Run(const RunInputs& inputs, const nlohmann::json& values, const RunContext& context) {
  const Construction construction(ConstructionMethod::kClosedForm, "dual mesh");
  const DualSettings settings = Schema().Apply(values);
  const PolyMesh& mesh = inputs.Mesh("mesh");
  const std::string source = inputs.Source("mesh");
  DualOptions options;
  options.start =
      settings.start == "tangent_planes" ? DualStart::kTangentPlanes : DualStart::kCentroids;
  options.boundary = settings.boundary == "keep" ? DualBoundary::kKeep : DualBoundary::kDrop;
  char line[512];
  std::snprintf(line, sizeof(line), "%s: %zu vertices, %zu triangles; dual from %s, boundary %s",
                source.c_str(), mesh.n_vertices(), mesh.n_faces(), settings.start.c_str(),
                settings.boundary.c_str());
  context.Headline(line);
  DualStats stats;
  PolyMesh dual;
  try {
    dual = DualMesh(mesh, options, &stats);
  } catch (const InputError& e) {
    throw InputError(source + ": " + e.what());
  }
  const PolygonMeshSummary summary = SummarizePolygons(dual);
  RunResult result;
  result.report = construction.Finish({}, PolygonValues(summary), true);
  if (result.report.failed) return result;
  result.facts = {{"vertices", dual.n_vertices()},
                  {"faces", dual.n_faces()},
                  {"faces_by_corners", summary.faces_by_corners},
                  {"boundary_faces", stats.boundary_faces}};
  if (options.start == DualStart::kTangentPlanes)
    result.facts["tangent_planes"] = {{"vertices", stats.tangent_plane_vertices},
                                      {"planes_dependent", stats.rank_deficient},
                                      {"not_well_conditioned", stats.held_within_reach},
                                      {"left_at_centroid", stats.centroid_fallbacks},
                                      {"coincident_at_centroid", stats.coincident}};
  std::snprintf(line, sizeof(line), "dual: %zu vertices, %zu faces (%s)", dual.n_vertices(),
                dual.n_faces(), FaceCountsText(summary.faces_by_corners).c_str());
  result.Info(line);
  if (options.start == DualStart::kTangentPlanes) {
    std::snprintf(line, sizeof(line),
                  "tangent planes: %d vertices where the three planes meet (%d where they share "
                  "a line or plane); %d not well conditioned (the planes meet beyond the "
                  "triangle's longest edge: nearest them within it); %d at the centroid (%d "
                  "where two neighbours' planes meet in one point)",
                  stats.tangent_plane_vertices, stats.rank_deficient, stats.held_within_reach,
                  stats.centroid_fallbacks + stats.coincident, stats.coincident);
    result.Info(line);
  }
  std::snprintf(line, sizeof(line),
                "panels: max planarity %.3e, mean %.3e (/ mean edge), %d non-convex, smallest "
                "corner angle %.1f deg",
                summary.max_planarity, summary.mean_planarity, summary.non_convex,
                summary.min_angle_deg);
  result.Info(line);
  result.meshes["output"] = dual;
  AddMeshPicture(context, "picture", dual, "Dual polygon mesh", &result);
  return result;
}

}  // namespace

ProblemSpec DualSpec() {
  ProblemSpec spec;
  spec.name = "dual";
  spec.summary =
      "The dual polygon mesh of a triangle mesh: one vertex per triangle, one face per vertex "
      "(hexagons where the triangle mesh has valence 6), the start of a planar hexagonal or "
      "hex-dominant mesh. Dual vertices at the triangles' centroids or "
      "where their vertices' tangent planes meet.";
  spec.inputs = {{"mesh", InputKind::kMesh, "Triangle mesh", true}};
  spec.outputs = {{"output", OutputKind::kMesh, "the dual polygon mesh", true},
                  {"picture", OutputKind::kSvg, "a shaded picture of the dual"}};
  spec.options = Schema().specs();
  spec.run = Run;
  return spec;
}

}  // namespace gproj::pq
