// `gproj remesh`: a triangle mesh remeshed into quads along its asymptotic or principal
// directions (004 §3.1, Fig. 4), the start of the pipeline to A-nets and H-nets.
#include <cstdio>
#include <iostream>
#include <memory>
#include <string>

#include "apps/commands.h"
#include "geometry/face_colours.h"
#include "geometry/scale_free.h"
#include "geometry/svg_render.h"
#include "problems/circular_mesh.h"
#include "problems/quad_remeshing.h"
#include "problems/report_json.h"

namespace gproj {
namespace {

struct RemeshArgs {
  std::string input, output, report, picture, field, directions = "asymptotic";
  QuadRemeshOptions options;
};

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

int RunRemesh(RemeshArgs args) {
  PolyMesh mesh;
  QuadRemeshResult r;
  args.options.directions =
      args.directions == "principal" ? DirectionKind::kPrincipal : DirectionKind::kAsymptotic;
  try {
    CheckOutputPaths({{"input", args.input}}, {{"--output", args.output, true},
                                               {"--report", args.report, false, ".json"},
                                               {"--picture", args.picture, false, ".svg"},
                                               {"--field", args.field, false, ".obj"}});
    mesh = ReadMesh(args.input);
  } catch (const InputError& e) {
    std::cerr << "gproj remesh: " << e.what() << "\n";
    return kExitInputError;
  }
  try {
    const double edge =
        args.options.edge_length > 0.0 ? args.options.edge_length : 3.0 * MeanEdgeLength(mesh);
    std::printf(
        "gproj remesh: %s: %zu vertices, %zu faces; quads of edge %g along the %s directions\n",
        args.input.c_str(), mesh.n_vertices(), mesh.n_faces(), edge, args.directions.c_str());
    std::fflush(stdout);
    r = RemeshAlongField(mesh, args.options);
  } catch (const InputError& e) {
    std::cerr << "gproj remesh: " << args.input << ": " << e.what() << "\n";
    return kExitInputError;
  }
  const FieldParametrization& p = r.parametrization;
  const QuadExtraction& x = r.extraction;
  std::printf("field: jet fit and smoothing (weight %g) in %.3f s; K < 0 on %.1f%% of the area\n",
              args.options.smoothing, r.seconds_field, 100.0 * r.field.negative_area_fraction);
  std::printf("frame singularities: %zu", p.singularities.size());
  for (const FrameSingularity& s : p.singularities)
    std::printf("%s vertex %d (index %+g)", &s == &p.singularities.front() ? ":" : ",", s.vertex,
                s.index);
  std::printf("\n");
  std::printf("integer-grid map: %zu cut edges, %d folded triangles, in %.3f s\n",
              p.cut_edges.size(), p.folded_faces, r.seconds_map);
  std::printf("quads: %zu faces, %zu vertices from %d grid points in %.3f s\n", x.quads.n_faces(),
              x.quads.n_vertices(), x.grid_points, r.seconds_extraction);
  std::printf("inner valences:");
  for (size_t k = 0; k < r.inner_valence_count.size(); ++k)
    if (r.inner_valence_count[k] > 0) std::printf(" %zu: %d", k, r.inner_valence_count[k]);
  std::printf("; odd: %d\n", r.odd_inner_vertices);
  std::printf("edges against the field: mean %.2f deg, max %.2f deg; area covered %.1f%%\n",
              r.mean_alignment_deg, r.max_alignment_deg, 100.0 * r.area_covered);
  int singular = 0;
  for (size_t k = 0; k < r.inner_valence_count.size(); ++k)
    if (k != 4) singular += r.inner_valence_count[k];
  const NamedValues measures = {
      {"quads", static_cast<double>(x.quads.n_faces())},
      {"quad_vertices", static_cast<double>(x.quads.n_vertices())},
      {"frame_singularities", static_cast<double>(p.singularities.size())},
      {"irregular_inner_vertices", static_cast<double>(singular)},
      {"odd_inner_vertices", static_cast<double>(r.odd_inner_vertices)},
      {"mean_alignment_deg", r.mean_alignment_deg},
      {"max_alignment_deg", r.max_alignment_deg},
      {"area_covered", r.area_covered},
      {"nonconvex_quads", static_cast<double>(r.nonconvex_quads)},
      {"min_corner_angle_deg", r.min_corner_angle_deg},
      {"folded_triangles", static_cast<double>(p.folded_faces)},
      {"negative_area_fraction", r.field.negative_area_fraction}};
  // Exit 0 when the quads are a valid net (QuadRemeshResult::Problems).
  const std::vector<std::string> problems = r.Problems();
  RunReport report = ConstructionReport("integer-grid map", {}, measures, problems.empty(),
                                        r.seconds_field + r.seconds_map + r.seconds_extraction);
  if (!problems.empty()) {
    report.termination = "the quads are not a valid net:";
    for (size_t k = 0; k < problems.size(); ++k)
      report.termination += (k ? ", " : " ") + problems[k];
  }
  if (report.failed) return ConcludeRun("remesh", report, "", 0.0, {});
  nlohmann::json extra = {{"input", args.input},
                          {"directions", args.directions},
                          {"output", args.output},
                          {"edge_length", p.edge_length},
                          {"smoothing", args.options.smoothing}};
  extra["singularities"] = nlohmann::json::array();
  for (const FrameSingularity& s : p.singularities) {
    const auto& q = mesh.point(mesh.vertex_handle(s.vertex));
    extra["singularities"].push_back(
        {{"vertex", s.vertex}, {"index", s.index}, {"position", {q[0], q[1], q[2]}}});
  }
  extra["inner_valences"] = nlohmann::json::object();
  for (size_t k = 0; k < r.inner_valence_count.size(); ++k)
    if (r.inner_valence_count[k] > 0)
      extra["inner_valences"][std::to_string(k)] = r.inner_valence_count[k];
  try {
    OutputFiles files;
    files.AddMesh(x.quads, args.output);
    const double mean_edge = MeanEdgeLength(mesh);
    if (!args.field.empty())
      files.AddText(args.field,
                    SegmentsObj("gproj remesh: the frame field per triangle, two segments each",
                                FrameSegments(mesh, p, 0.8 * mean_edge)));
    if (!args.picture.empty()) {
      std::vector<double> degrees(x.quads.n_faces(), 0.0);
      // Per quad its worst edge against the field.
      for (const QuadExtraction::Edge& e : x.edges) {
        const auto a = x.quads.vertex_handle(e.from), b = x.quads.vertex_handle(e.to);
        const Eigen::Vector3d d(Eigen::Vector3d(x.quads.point(b).data()) -
                                Eigen::Vector3d(x.quads.point(a).data()));
        const double angle = std::min(LineAngleDeg(d, p.frame_a[e.triangle]),
                                      LineAngleDeg(d, p.frame_b[e.triangle]));
        for (auto h : x.quads.voh_range(a))
          if (x.quads.to_vertex_handle(h) == b)
            for (auto f : {x.quads.face_handle(h), x.quads.opposite_face_handle(h)})
              if (f.is_valid()) degrees[f.idx()] = std::max(degrees[f.idx()], angle);
      }
      SvgOptions svg;
      svg.title = "Quad remeshing along the " + args.directions +
                  " directions: " + std::to_string(x.quads.n_faces()) + " quads, " +
                  std::to_string(singular) + " irregular vertices (red dots: frame singularities)";
      const ColourScale scale{"worst edge against the field (deg)", 0.0, 10.0, false};
      svg.face_colours = ColoursOf(degrees, scale);
      svg.legend = "colour: the worst edge of each quad against the field, blue 0 to red 10 deg";
      for (const FrameSingularity& s : p.singularities)
        svg.dots.emplace_back(mesh.point(mesh.vertex_handle(s.vertex)).data());
      files.AddText(args.picture, RenderMeshSvg(x.quads, svg));
    }
    if (!args.report.empty())
      files.AddText(args.report, ReportJson("remesh", report, extra).dump(2) + "\n");
    files.Commit();
  } catch (const InputError& e) {
    std::cerr << "gproj remesh: " << e.what() << "\n";
    return kExitInputError;
  }
  return ConcludeRun("remesh", report, "", 0.0,
                     {args.output, args.field, args.picture, args.report});
}

}  // namespace

void RegisterRemeshCommand(CLI::App* app, int* exit_code) {
  auto args = std::make_shared<RemeshArgs>();
  CLI::App* cmd = app->add_subcommand(
      "remesh",
      "Quad remeshing of a triangulated disk along its asymptotic (K < 0) or principal "
      "directions (004 §3.1): jet-fitted, smoothed direction field, seamless integer-grid map "
      "cut from its singularities to the boundary (mixed-integer quadrangulation), quads "
      "extracted along the integer iso-lines. Exit 0 when the quads are a valid net (inner "
      "valences above 2, quads convex, map unfolded, and for asymptotic directions even valences "
      "and K < 0 on 99% of the area), 3 when not (result written, the reasons named); other codes "
      "as for planarize.");
  cmd->add_option("mesh", args->input, "Triangle mesh of a disk (.obj, .off, .ply)")->required();
  cmd->add_option("-o,--output", args->output, "The quad mesh (.obj, .off, .ply)")->required();
  cmd->add_option("--directions", args->directions, "asymptotic (where K < 0) or principal")
      ->check(CLI::IsMember({"asymptotic", "principal"}))
      ->capture_default_str();
  cmd->add_option("--edge-length", args->options.edge_length,
                  "Edge length of the quads (default: 3 mean triangle edges)")
      ->check(Positive());
  cmd->add_option("--smooth", args->options.smoothing,
                  "Weight of the fitted directions against the field's smoothness (smaller: "
                  "smoother, fewer singularities)")
      ->check(Positive())
      ->capture_default_str();
  cmd->add_option("--neighbours", args->options.fit.min_points,
                  "Vertices per jet fit at least (rings are added until there are as many)")
      ->check(Within(10, 1000))
      ->capture_default_str();
  cmd->add_option("--min-net-angle", args->options.min_net_angle_deg,
                  "Asymptotic pairs closer than this (degrees) are opened to it")
      ->check(Within(1, 90))
      ->capture_default_str();
  cmd->add_option("--field", args->field,
                  "Write the frame field the quads follow (OBJ segments, two per triangle)");
  cmd->add_option("--report", args->report, "Write a JSON report (with every singularity)");
  cmd->add_option("--picture", args->picture,
                  "Write an SVG picture of the quads coloured by their edges' deviation from the "
                  "field, with the singularities");
  cmd->callback([args, exit_code]() { *exit_code = RunRemesh(*args); });
}

}  // namespace gproj
