// `remesh` in the registry: a triangle mesh remeshed into quads along its asymptotic or
// principal directions (004 §3.1, Fig. 4), the start of the pipeline to A-nets and H-nets.
#include <cstdio>

#include "gproj/geometry/mesh/scale_free.h"
#include "gproj/geometry/render/face_colours.h"
#include "gproj/geometry/render/svg_render.h"
#include "gproj/problems/remesh/quad_remeshing.h"
#include "gproj/problems/run/builtin_problems.h"
#include "gproj/problems/run/construction.h"

namespace gproj::remesh {
namespace {

struct RemeshSettings {
  QuadRemeshOptions remesh;
  std::string directions = "asymptotic";
};

const OptionSchema<RemeshSettings>& Schema() {
  static const OptionSchema<RemeshSettings> schema = [] {
    using S = RemeshSettings;
    OptionSchema<S> s;
    s.Field<std::string>("directions", OptionType::kChoice, "asymptotic (where K < 0) or principal",
                         [](S& x) -> std::string& { return x.directions; })
        .Choices({"asymptotic", "principal"});
    s.Custom("edge_length", OptionType::kNumber,
             "Edge length of the quads (not given: 3 mean triangle edges)", nullptr,
             [](const nlohmann::json& v, S* x) { x->remesh.edge_length = v.get<double>(); })
        .Positive()
        .Unit("input units");
    s.Field<double>("smooth", OptionType::kNumber,
                    "Weight of the fitted directions against the field's smoothness (smaller: "
                    "smoother, fewer singularities)",
                    [](S& x) -> double& { return x.remesh.smoothing; })
        .Positive();
    s.Field<int>("neighbours", OptionType::kInt,
                 "Vertices per jet fit at least (rings are added until there are as many)",
                 [](S& x) -> int& { return x.remesh.fit.min_points; })
        .Range(10, 1000);
    s.Field<double>("min_net_angle", OptionType::kNumber,
                    "Asymptotic pairs closer than this are opened to it",
                    [](S& x) -> double& { return x.remesh.min_net_angle_deg; })
        .Range(1, 90)
        .Unit("deg");
    return s;
  }();
  return schema;
}

// The frame every face follows: two segments through its centroid.
std::vector<std::pair<Eigen::Vector3d, Eigen::Vector3d>> FrameSegments(
    const PolyMesh& mesh, const FieldParametrization& p, double length) {
  std::vector<std::pair<Eigen::Vector3d, Eigen::Vector3d>> segments;
  for (auto f : mesh.faces()) {
    Eigen::Vector3d c = Eigen::Vector3d::Zero();
    for (auto v : mesh.fv_range(f)) c += Eigen::Vector3d(mesh.point(v).data()) / 3.0;
    for (const Eigen::Vector3d& d : {p.frame_a[f.idx()], p.frame_b[f.idx()]})
      segments.emplace_back(c - 0.5 * length * d, c + 0.5 * length * d);
  }
  return segments;
}

// The quads coloured by their worst edge against the field, the singularities as dots.
std::string RemeshSvg(const PolyMesh& mesh, const QuadRemeshResult& r,
                      const std::string& directions, int irregular) {
  const FieldParametrization& p = r.parametrization;
  const QuadExtraction& x = r.extraction;
  std::vector<double> degrees(x.quads.n_faces(), 0.0);
  for (const QuadExtraction::Edge& e : x.edges) {
    const auto a = x.quads.vertex_handle(e.from), b = x.quads.vertex_handle(e.to);
    const Eigen::Vector3d d(Eigen::Vector3d(x.quads.point(b).data()) -
                            Eigen::Vector3d(x.quads.point(a).data()));
    const double angle = EdgeAgainstFrameDeg(d, p.frame_a[e.triangle], p.frame_b[e.triangle]);
    for (auto h : x.quads.voh_range(a))
      if (x.quads.to_vertex_handle(h) == b)
        for (auto f : {x.quads.face_handle(h), x.quads.opposite_face_handle(h)})
          if (f.is_valid()) degrees[f.idx()] = std::max(degrees[f.idx()], angle);
  }
  SvgOptions svg;
  svg.title = "Quad remeshing along the " + directions +
              " directions: " + std::to_string(x.quads.n_faces()) + " quads, " +
              std::to_string(irregular) + " irregular vertices (red: frame singularities and cuts)";
  const ColourScale scale{"worst edge against the field (deg)", 0.0, 10.0, false};
  svg.face_colours = ColoursOf(degrees, scale);
  svg.legend = "colour: the worst edge of each quad against the field, blue 0 to red 10 deg";
  for (const FrameSingularity& s : p.singularities)
    svg.dots.emplace_back(mesh.point(mesh.vertex_handle(s.vertex)).data());
  for (int e : p.cut_edges) {
    const auto h = mesh.halfedge_handle(mesh.edge_handle(e), 0);
    svg.segments.emplace_back(Eigen::Vector3d(mesh.point(mesh.from_vertex_handle(h)).data()),
                              Eigen::Vector3d(mesh.point(mesh.to_vertex_handle(h)).data()));
  }
  return RenderMeshSvg(x.quads, svg);
}

// The log's lines after the run.
void Describe(const QuadRemeshResult& r, double smoothing, RunResult* result) {
  const FieldParametrization& p = r.parametrization;
  const QuadExtraction& x = r.extraction;
  char line[512];
  std::snprintf(line, sizeof(line),
                "field: jet fit and smoothing (weight %g) in %.3f s; K < 0 on %.1f%% of the area",
                smoothing, r.seconds_field, 100.0 * r.field.negative_area_fraction);
  result->Info(line);
  std::string text = "frame singularities: " + std::to_string(p.singularities.size());
  for (const FrameSingularity& s : p.singularities) {
    std::snprintf(line, sizeof(line), "%s vertex %d (index %+g)",
                  &s == &p.singularities.front() ? ":" : ",", s.vertex, s.index);
    text += line;
  }
  result->Info(text);
  std::snprintf(line, sizeof(line),
                "integer-grid map: %zu cut edges (%d boundary loop%s%s, %d handle%s%s), %d folded "
                "triangles, in %.3f s",
                p.cut_edges.size(), p.boundary_loops, p.boundary_loops == 1 ? "" : "s",
                p.boundary_loops > 1 ? ", cut through the holes" : "", p.handles,
                p.handles == 1 ? "" : "s", p.handles > 0 ? " cut open" : "", p.folded_faces,
                r.seconds_map);
  result->Info(line);
  std::snprintf(line, sizeof(line), "quads: %zu faces, %zu vertices from %d grid points in %.3f s",
                x.quads.n_faces(), x.quads.n_vertices(), x.grid_points, r.seconds_extraction);
  result->Info(line);
  text = "inner valences:";
  for (size_t k = 0; k < r.inner_valence_count.size(); ++k)
    if (r.inner_valence_count[k] > 0)
      text += " " + std::to_string(k) + ": " + std::to_string(r.inner_valence_count[k]);
  result->Info(text + "; odd: " + std::to_string(r.odd_inner_vertices));
  std::snprintf(line, sizeof(line),
                "edges against the field: mean %.2f deg, max %.2f deg; area covered %.1f%%",
                r.mean_alignment_deg, r.max_alignment_deg, 100.0 * r.area_covered);
  result->Info(line);
}

RunResult Run(const RunInputs& inputs, const nlohmann::json& values, const RunContext& context) {
  RemeshSettings settings = Schema().Apply(values);
  QuadRemeshOptions& options = settings.remesh;
  options.fit.stop = [&context] { return context.StopRequested(); };
  options.directions =
      settings.directions == "principal" ? DirectionKind::kPrincipal : DirectionKind::kAsymptotic;
  const PolyMesh& mesh = inputs.Mesh("mesh");
  const std::string source = inputs.Source("mesh");
  char line[512];
  std::snprintf(line, sizeof(line),
                "%s: %zu vertices, %zu faces; quads of edge %g along the %s directions",
                source.c_str(), mesh.n_vertices(), mesh.n_faces(),
                options.edge_length > 0.0 ? options.edge_length : 3.0 * MeanEdgeLength(mesh),
                settings.directions.c_str());
  context.Headline(line);
  Construction construction(ConstructionMethod::kIntegerGridMap, "integer-grid map");
  QuadRemeshResult r;
  try {
    r = RemeshAlongField(mesh, options);
  } catch (const InputError& e) {
    throw InputError(source + ": " + e.what());
  } catch (const RunStopped& e) {
    RunResult stopped;
    stopped.report = construction.Stopped(e);
    return stopped;
  }
  construction.Stop();
  const FieldParametrization& p = r.parametrization;
  const QuadExtraction& x = r.extraction;
  int irregular = 0;
  for (size_t k = 0; k < r.inner_valence_count.size(); ++k)
    if (k != 4) irregular += r.inner_valence_count[k];
  const NamedValues measures = {
      {"quads", static_cast<double>(x.quads.n_faces())},
      {"quad_vertices", static_cast<double>(x.quads.n_vertices())},
      {"frame_singularities", static_cast<double>(p.singularities.size())},
      {"pieces", static_cast<double>(r.components)},
      {"pinched_vertices", static_cast<double>(r.pinched_vertices)},
      {"euler_characteristic", static_cast<double>(r.euler_characteristic)},
      {"irregular_inner_vertices", static_cast<double>(irregular)},
      {"odd_inner_vertices", static_cast<double>(r.odd_inner_vertices)},
      {"mean_alignment_deg", r.mean_alignment_deg},
      {"max_alignment_deg", r.max_alignment_deg},
      {"area_covered", r.area_covered},
      {"non_convex_quads", static_cast<double>(r.nonconvex_quads)},
      {"min_corner_angle_deg", r.min_corner_angle_deg},
      {"folded_triangles", static_cast<double>(p.folded_faces)},
      {"negative_area_fraction", r.field.negative_area_fraction}};
  // Converged when the quads are a valid net (QuadRemeshResult::Problems).
  const std::vector<std::string> problems = r.Problems();
  RunResult result;
  result.report = construction.Finish({}, measures, problems.empty());
  if (!problems.empty()) {
    result.report.termination = "the quads are not a valid net:";
    for (size_t k = 0; k < problems.size(); ++k)
      result.report.termination += (k ? ", " : " ") + problems[k];
  }
  if (result.report.failed) return result;
  Describe(r, options.smoothing, &result);
  result.facts = {{"directions", settings.directions},
                  {"edge_length", p.edge_length},
                  {"smoothing", options.smoothing},
                  {"boundary_loops", p.boundary_loops},
                  {"handles", p.handles},
                  {"singularities", nlohmann::json::array()},
                  {"inner_valences", nlohmann::json::object()}};
  for (const FrameSingularity& s : p.singularities) {
    const auto& q = mesh.point(mesh.vertex_handle(s.vertex));
    result.facts["singularities"].push_back(
        {{"vertex", s.vertex}, {"index", s.index}, {"position", {q[0], q[1], q[2]}}});
  }
  for (size_t k = 0; k < r.inner_valence_count.size(); ++k)
    if (r.inner_valence_count[k] > 0)
      result.facts["inner_valences"][std::to_string(k)] = r.inner_valence_count[k];
  result.meshes["output"] = x.quads;
  if (context.Wants("field"))
    result.texts["field"] =
        SegmentsObj("gproj remesh: the frame field per triangle, two segments each",
                    FrameSegments(mesh, p, 0.8 * MeanEdgeLength(mesh)));
  if (context.Wants("picture"))
    result.texts["picture"] = RemeshSvg(mesh, r, settings.directions, irregular);
  return result;
}

}  // namespace

ProblemSpec RemeshSpec() {
  ProblemSpec spec;
  spec.name = "remesh";
  spec.summary =
      "Quad remeshing of a triangulated disk, or of a surface with holes and handles, along its "
      "asymptotic "
      "(K < 0) or principal directions (004 §3.1): jet-fitted, smoothed direction field, "
      "seamless integer-grid map cut through the holes, around the handles and from its "
      "singularities to the "
      "boundary (mixed-integer quadrangulation, integer transitions across every cut), quads "
      "extracted along the integer iso-lines. Converged (exit 0) when the quads are a valid net "
      "(inner valences above 2, quads convex, map unfolded, one piece with the surface's Euler "
      "characteristic and no pinched vertex, and for asymptotic directions even valences, "
      "2-coloured vertices and K < 0 on 99% of the area); otherwise the quads are "
      "returned and the reasons named.";
  spec.inputs = {{"mesh", InputKind::kMesh,
                  "Triangle mesh of a surface with a boundary: a disk, or with holes and handles",
                  true}};
  spec.outputs = {
      {"output", OutputKind::kMesh, "the quad mesh", true},
      {"field", OutputKind::kSegments,
       "the frame field the quads follow (OBJ segments, two per triangle)"},
      {"picture", OutputKind::kSvg,
       "a picture of the quads coloured by their edges' deviation from the field, with the "
       "singularities"}};
  spec.options = Schema().specs();
  spec.run = Run;
  return spec;
}

}  // namespace gproj::remesh
