// `field` in the registry: the curvature direction field of a triangle mesh (004 §3.1), the
// first step of remeshing a surface into a net that follows it.
#include <chrono>
#include <cmath>
#include <cstdio>
#include <map>

#include "gproj/geometry/mesh/curvature_field.h"
#include "gproj/geometry/mesh/scale_free.h"
#include "gproj/geometry/render/face_colours.h"
#include "gproj/geometry/render/svg_render.h"
#include "gproj/problems/run/builtin_problems.h"
#include "gproj/problems/run/construction.h"

namespace gproj::remesh {
namespace {

struct FieldSettings {
  std::string directions = "asymptotic";
  CurvatureFitOptions fit;
  double smooth = 0.0;  // alignment weight of the smoothing (0: the fitted lines as they are)
};

const OptionSchema<FieldSettings>& Schema() {
  static const OptionSchema<FieldSettings> schema = [] {
    using S = FieldSettings;
    OptionSchema<S> s;
    s.Field<std::string>("directions", OptionType::kChoice, "asymptotic (where K < 0) or principal",
                         [](S& x) -> std::string& { return x.directions; })
        .Choices({"asymptotic", "principal"});
    s.Field<int>("neighbours", OptionType::kInt,
                 "Vertices per jet fit at least (rings are added until there are as many)",
                 [](S& x) -> int& { return x.fit.min_points; })
        .Range(10, 1000);
    s.Custom("smooth", OptionType::kNumber,
             "Smooth the principal lines first, with this weight on the fitted ones against the "
             "smoothness (e.g. 1; for noisy meshes); not given: no smoothing",
             nullptr, [](const nlohmann::json& v, S* x) { x->smooth = v.get<double>(); })
        .Positive();
    return s;
  }();
  return schema;
}

// Both lines at every vertex as OBJ segments of `length` centred on the vertex.
std::string FieldObj(const PolyMesh& mesh, const DirectionField& field, double length) {
  std::vector<std::pair<Eigen::Vector3d, Eigen::Vector3d>> segments;
  for (auto v : mesh.vertices()) {
    const Eigen::Vector3d p(mesh.point(v).data());
    for (const Eigen::Vector3d& d : {field.first[v.idx()], field.second[v.idx()]})
      if (d.norm() > 0.0) segments.emplace_back(p - 0.5 * length * d, p + 0.5 * length * d);
  }
  return SegmentsObj(std::string("gproj field: ") +
                         (field.kind == DirectionKind::kPrincipal ? "principal" : "asymptotic") +
                         " directions, two segments per vertex",
                     segments);
}

// The mesh coloured by the sign of K at the fitted corners of each face (blue K < 0, yellow
// K = 0 or unfitted, red K > 0), the field over it (up to 2,000 vertices), singularities as dots.
std::string FieldSvg(const PolyMesh& mesh, const DirectionField& field) {
  std::vector<double> sign;
  for (auto f : mesh.faces()) {
    double k = 0.0;
    for (auto fv = mesh.cfv_iter(f); fv.is_valid(); ++fv)
      if (field.curvature[fv->idx()].fitted) k += field.curvature[fv->idx()].gaussian();
    sign.push_back(k < 0.0 ? 0.0 : k > 0.0 ? 1.0 : 0.5);
  }
  SvgOptions svg;
  svg.title = "Curvature field (black lines): K < 0 blue, K = 0 or unfitted yellow, K > 0 red; " +
              std::to_string(field.singularities.size()) + " singularities (red dots)";
  svg.face_colours = ColoursOf(sign, ColourScale{"sign of K", 0.0, 1.0, false});
  const size_t stride = 1 + mesh.n_vertices() / 2000;
  const double length = 0.6 * MeanEdgeLength(mesh) * std::sqrt(static_cast<double>(stride));
  for (size_t v = 0; v < mesh.n_vertices(); v += stride) {
    const Eigen::Vector3d p(mesh.point(mesh.vertex_handle(v)).data());
    for (const Eigen::Vector3d& d : {field.first[v], field.second[v]})
      if (d.norm() > 0.0) svg.segments.emplace_back(p - 0.5 * length * d, p + 0.5 * length * d);
  }
  svg.segment_colour = "rgb(30,30,30)";
  for (const Singularity& s : field.singularities)
    svg.dots.emplace_back(mesh.point(mesh.vertex_handle(s.vertex)).data());
  return RenderMeshSvg(mesh, svg);
}

// "singularities of the line field: 1 (index -1/2: 1)".
std::string SingularityLine(const DirectionField& field) {
  std::map<int, int> count;  // index × symmetry → singularities
  for (const Singularity& s : field.singularities)
    ++count[static_cast<int>(std::lround(s.index * field.symmetry))];
  std::string line = std::string("singularities of the ") +
                     (field.symmetry == 4 ? "cross" : "line") +
                     " field: " + std::to_string(field.singularities.size());
  for (auto it = count.begin(); it != count.end(); ++it) {
    int numerator = it->first, denominator = field.symmetry;
    while (denominator > 1 && numerator % 2 == 0) numerator /= 2, denominator /= 2;
    line += (it == count.begin() ? " (" : ", ") + std::string("index ") +
            (numerator > 0 ? "+" : "") + std::to_string(numerator) +
            (denominator > 1 ? "/" + std::to_string(denominator) : "") + ": " +
            std::to_string(it->second);
  }
  return line + (count.empty() ? "" : ")");
}

// The facts of the report and the lines of the log after the fit.
void Describe(const PolyMesh& mesh, const DirectionField& field, const FieldSettings& settings,
              double seconds, RunResult* result) {
  char line[512];
  std::snprintf(line, sizeof(line),
                "fitted %d of %zu vertices in %.3f s; K < 0 on %.1f%% of the area%s", field.fitted,
                mesh.n_vertices(), seconds, 100.0 * field.negative_area_fraction,
                field.kind == DirectionKind::kAsymptotic && field.negative_area_fraction < 1.0
                    ? " (no asymptotic directions elsewhere)"
                    : "");
  result->Info(line);
  if (field.fitted < static_cast<int>(mesh.n_vertices())) {
    std::snprintf(line, sizeof(line),
                  "note: %zu vertices have fewer than %d vertices within %d rings and no field "
                  "(lower `neighbours` to fit them)",
                  mesh.n_vertices() - field.fitted, settings.fit.min_points,
                  settings.fit.max_rings);
    result->Info(line);
  }
  if (field.undefined_area_fraction > 0.0) {
    std::snprintf(line, sizeof(line),
                  "principal directions undefined (flat or umbilic) on %.1f%% of the area%s",
                  100.0 * field.undefined_area_fraction,
                  field.singularities_reliable ? "" : ": no singularities reported");
    result->Info(line);
  }
  result->Info(SingularityLine(field));
  result->facts["directions"] = settings.directions;
  result->facts["smoothing"] = settings.smooth;
  result->facts["singularities_reliable"] = field.singularities_reliable;
  result->facts["singularities"] = nlohmann::json::array();
  for (const Singularity& s : field.singularities) {
    const auto& p = mesh.point(mesh.vertex_handle(s.vertex));
    result->facts["singularities"].push_back(
        {{"vertex", s.vertex}, {"index", s.index}, {"position", {p[0], p[1], p[2]}}});
  }
  Eigen::MatrixXd first(mesh.n_vertices(), 3), second(mesh.n_vertices(), 3);
  for (size_t v = 0; v < mesh.n_vertices(); ++v) {
    first.row(v) = field.first[v].transpose();
    second.row(v) = field.second[v].transpose();
  }
  result->arrays["first"] = first;
  result->arrays["second"] = second;
}

RunResult Run(const RunInputs& inputs, const nlohmann::json& values, const RunContext& context) {
  FieldSettings settings = Schema().Apply(values);
  settings.fit.stop = [&context] { return context.StopRequested(); };
  const PolyMesh& mesh = inputs.Mesh("mesh");
  const DirectionKind kind =
      settings.directions == "principal" ? DirectionKind::kPrincipal : DirectionKind::kAsymptotic;
  char line[512];
  std::snprintf(line, sizeof(line),
                "%s: %zu vertices, %zu faces; %s directions by a degree-%d jet fit on at least %d "
                "vertices",
                inputs.Source("mesh").c_str(), mesh.n_vertices(), mesh.n_faces(),
                settings.directions.c_str(), settings.fit.fit_degree, settings.fit.min_points);
  context.Headline(line);
  Construction construction(ConstructionMethod::kJetFit, "jet fit");
  if (settings.smooth > 0.0) {
    std::snprintf(line, sizeof(line),
                  "smoothing the principal lines (alignment weight %g; Knöppel et al. 2013)",
                  settings.smooth);
    context.Info(line);
  }
  DirectionField field;
  try {
    field = EstimateDirectionField(mesh, kind, settings.fit, settings.smooth);
  } catch (const RunStopped& e) {
    RunResult stopped;
    stopped.report = construction.Stopped(e);
    return stopped;
  }
  construction.Stop();
  const double seconds = construction.seconds();
  const NamedValues measures = {{"fitted_vertices", static_cast<double>(field.fitted)},
                                {"negative_area_fraction", field.negative_area_fraction},
                                {"undefined_area_fraction", field.undefined_area_fraction},
                                {"singularities", static_cast<double>(field.singularities.size())}};
  RunResult result;
  result.report = construction.Finish({}, measures, true);
  if (result.report.failed) return result;
  Describe(mesh, field, settings, seconds, &result);
  result.texts["output"] = FieldObj(mesh, field, 0.6 * MeanEdgeLength(mesh));
  if (context.Wants("picture")) result.texts["picture"] = FieldSvg(mesh, field);
  return result;
}

}  // namespace

ProblemSpec FieldSpec() {
  ProblemSpec spec;
  spec.name = "field";
  spec.summary =
      "Curvature direction field of a triangle mesh (004 §3.1): principal curvatures and "
      "directions per vertex by a 3rd-order jet fit (CGAL), the asymptotic pair where K < 0, and "
      "the singularities of the field with their indices (the asymptotic pair about the line "
      "d1, in halves; the principal cross, in quarters); smooth smooths the field first.";
  spec.inputs = {{"mesh", InputKind::kMesh, "Triangle mesh", true}};
  spec.outputs = {
      {"output", OutputKind::kSegments, "the field as OBJ line segments, two per vertex", true},
      {"picture", OutputKind::kSvg, "a picture of the mesh coloured by the sign of K"}};
  spec.options = Schema().specs();
  spec.run = Run;
  spec.arrays = {{"first", "#V x 3: the first line of the field at every vertex (0: no fit)"},
                 {"second", "#V x 3: the second line (the asymptotic partner, or d2)"}};
  return spec;
}

}  // namespace gproj::remesh
