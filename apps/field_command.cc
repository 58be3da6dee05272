// `gproj field`: the curvature direction field of a triangle mesh (004 §3.1), the first step of
// remeshing a surface into a net that follows it.
#include <chrono>
#include <cmath>
#include <cstdio>
#include <iostream>
#include <map>
#include <memory>
#include <string>

#include "apps/commands.h"
#include "geometry/curvature_field.h"
#include "geometry/face_colours.h"
#include "geometry/scale_free.h"
#include "geometry/svg_render.h"
#include "problems/circular_mesh.h"
#include "problems/report_json.h"

namespace gproj {
namespace {

struct FieldArgs {
  std::string input, output, report, picture, directions = "asymptotic";
  CurvatureFitOptions fit;
  double smooth = 0.0;  // alignment weight of the smoothing (0: the fitted lines as they are)
};

// Both lines at every vertex as OBJ segments of `length` centred on the vertex.
std::string FieldObj(const PolyMesh& mesh, const DirectionField& field, double length) {
  std::vector<std::pair<Eigen::Vector3d, Eigen::Vector3d>> segments;
  for (auto v : mesh.vertices()) {
    const auto& q = mesh.point(v);
    const Eigen::Vector3d p(q[0], q[1], q[2]);
    for (const Eigen::Vector3d& d : {field.first[v.idx()], field.second[v.idx()]})
      if (d.norm() > 0.0) segments.emplace_back(p - 0.5 * length * d, p + 0.5 * length * d);
  }
  return SegmentsObj(std::string("gproj field: ") +
                         (field.kind == DirectionKind::kPrincipal ? "principal" : "asymptotic") +
                         " directions, two segments per vertex",
                     segments);
}

int RunField(const FieldArgs& args) {
  PolyMesh mesh;
  DirectionField field;
  double seconds = 0.0;
  const DirectionKind kind =
      args.directions == "principal" ? DirectionKind::kPrincipal : DirectionKind::kAsymptotic;
  try {
    CheckOutputPaths({{"input", args.input}}, {{"--output", args.output, false, ".obj"},
                                               {"--report", args.report, false, ".json"},
                                               {"--picture", args.picture, false, ".svg"}});
    mesh = ReadMesh(args.input);
    std::printf(
        "gproj field: %s: %zu vertices, %zu faces; %s directions by a degree-%d jet fit "
        "on at least %d vertices\n",
        args.input.c_str(), mesh.n_vertices(), mesh.n_faces(), args.directions.c_str(),
        args.fit.fit_degree, args.fit.min_points);
    const auto start = std::chrono::steady_clock::now();
    if (args.smooth > 0.0)
      std::printf("smoothing the principal lines (alignment weight %g; Knöppel et al. 2013)\n",
                  args.smooth);
    field = EstimateDirectionField(mesh, kind, args.fit, args.smooth);
    seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  } catch (const InputError& e) {
    std::cerr << "gproj field: " << e.what() << "\n";
    return kExitInputError;
  }
  std::printf("fitted %d of %zu vertices in %.3f s; K < 0 on %.1f%% of the area%s\n", field.fitted,
              mesh.n_vertices(), seconds, 100.0 * field.negative_area_fraction,
              kind == DirectionKind::kAsymptotic && field.negative_area_fraction < 1.0
                  ? " (no asymptotic directions elsewhere)"
                  : "");
  if (field.fitted < static_cast<int>(mesh.n_vertices()))
    std::printf(
        "note: %zu vertices have fewer than %d vertices within %d rings and no field "
        "(lower --neighbours to fit them)\n",
        mesh.n_vertices() - field.fitted, args.fit.min_points, args.fit.max_rings);
  if (field.undefined_area_fraction > 0.0)
    std::printf("principal directions undefined (flat or umbilic) on %.1f%% of the area%s\n",
                100.0 * field.undefined_area_fraction,
                field.singularities_reliable ? "" : ": no singularities reported");
  // Counts per index, as fractions of the symmetry: "index -1/2: 1, +1/4: 4".
  std::map<int, int> count;  // index × symmetry → singularities
  for (const Singularity& s : field.singularities)
    ++count[static_cast<int>(std::lround(s.index * field.symmetry))];
  std::printf("singularities of the %s field: %zu", field.symmetry == 4 ? "cross" : "line",
              field.singularities.size());
  for (auto it = count.begin(); it != count.end(); ++it) {
    int numerator = it->first, denominator = field.symmetry;
    while (denominator > 1 && numerator % 2 == 0) numerator /= 2, denominator /= 2;
    std::printf("%sindex %s%d%s: %d", it == count.begin() ? " (" : ", ", numerator > 0 ? "+" : "",
                numerator, denominator > 1 ? ("/" + std::to_string(denominator)).c_str() : "",
                it->second);
  }
  std::printf("%s\n", count.empty() ? "" : ")");
  const NamedValues measures = {{"fitted_vertices", static_cast<double>(field.fitted)},
                                {"negative_area_fraction", field.negative_area_fraction},
                                {"undefined_area_fraction", field.undefined_area_fraction},
                                {"singularities", static_cast<double>(field.singularities.size())}};
  const RunReport report = ConstructionReport("jet fit", {}, measures, true, seconds);
  if (report.failed) return ConcludeRun("field", report, "", 0.0, {});
  nlohmann::json extra = {
      {"input", args.input}, {"directions", args.directions}, {"output", args.output}};
  extra["smoothing"] = args.smooth;
  extra["singularities_reliable"] = field.singularities_reliable;
  extra["singularities"] = nlohmann::json::array();
  for (const Singularity& s : field.singularities) {
    const auto& p = mesh.point(mesh.vertex_handle(s.vertex));
    extra["singularities"].push_back(
        {{"vertex", s.vertex}, {"index", s.index}, {"position", {p[0], p[1], p[2]}}});
  }
  try {
    OutputFiles files;
    files.AddText(args.output, FieldObj(mesh, field, 0.6 * MeanEdgeLength(mesh)));
    if (!args.picture.empty()) {
      // Faces by the sign of K at their fitted corners: blue K < 0, yellow K = 0 or no fit,
      // red K > 0.
      std::vector<double> sign;
      for (auto f : mesh.faces()) {
        double k = 0.0;
        for (auto fv = mesh.cfv_iter(f); fv.is_valid(); ++fv)
          if (field.curvature[fv->idx()].fitted) k += field.curvature[fv->idx()].gaussian();
        sign.push_back(k < 0.0 ? 0.0 : k > 0.0 ? 1.0 : 0.5);
      }
      SvgOptions svg;
      svg.title =
          "Curvature field (black lines): K < 0 blue, K = 0 or unfitted yellow, K > 0 "
          "red; " +
          std::to_string(field.singularities.size()) + " singularities (red dots)";
      svg.face_colours = ColoursOf(sign, ColourScale{"sign of K", 0.0, 1.0, false});
      // The field itself over it, at up to 2,000 vertices.
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
      files.AddText(args.picture, RenderMeshSvg(mesh, svg));
    }
    if (!args.report.empty())
      files.AddText(args.report, ReportJson("field", report, extra).dump(2) + "\n");
    files.Commit();
  } catch (const InputError& e) {
    std::cerr << "gproj field: " << e.what() << "\n";
    return kExitInputError;
  }
  return ConcludeRun("field", report, "", 0.0, {args.output, args.picture, args.report});
}

}  // namespace

void RegisterFieldCommand(CLI::App* app, int* exit_code) {
  auto args = std::make_shared<FieldArgs>();
  CLI::App* cmd = app->add_subcommand(
      "field",
      "Curvature direction field of a triangle mesh (004 §3.1): principal curvatures and "
      "directions per vertex by a 3rd-order jet fit (CGAL), the asymptotic pair where K < 0, and "
      "the singularities of the field with their indices (the asymptotic pair about the line d1, "
      "in "
      "halves; the principal cross, in quarters); --smooth smooths the field first. "
      "Exit codes as for planarize.");
  cmd->add_option("mesh", args->input, "Triangle mesh (.obj, .off, .ply)")->required();
  cmd->add_option("-o,--output", args->output, "The field as OBJ line segments, two per vertex")
      ->required();
  cmd->add_option("--directions", args->directions, "asymptotic (where K < 0) or principal")
      ->check(CLI::IsMember({"asymptotic", "principal"}))
      ->capture_default_str();
  cmd->add_option("--neighbours", args->fit.min_points,
                  "Vertices per jet fit at least (rings are added until there are as many)")
      ->check(Within(10, 1000))
      ->capture_default_str();
  cmd->add_option("--smooth", args->smooth,
                  "Smooth the principal lines first, with this weight on the fitted ones against "
                  "the smoothness (e.g. 1; for noisy meshes)")
      ->check(Positive());
  cmd->add_option("--report", args->report, "Write a JSON report (with every singularity)");
  cmd->add_option("--picture", args->picture,
                  "Write an SVG picture of the mesh coloured by the sign of K");
  cmd->callback([args, exit_code]() { *exit_code = RunField(*args); });
}

}  // namespace gproj
