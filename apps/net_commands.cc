// `gproj hnet`: H-nets (smooth skins from rational bilinear patches); `gproj anet` comes from
// the registry (problems/anet_problem.cc).
#include <cstdio>
#include <iostream>
#include <memory>
#include <nlohmann/json.hpp>
#include <string>

#include "apps/commands.h"
#include "geometry/mesh_io.h"
#include "geometry/svg_render.h"
#include "problems/anet.h"
#include "problems/hnet.h"

namespace gproj {
namespace {

struct NetArgs {
  std::string input, output, reference, report, star_form = "normals", linear_solver = "cholmod",
                                                solver = "gp";
  std::string surface_mesh, picture, fixed, face_values, heatmap;
  int samples = 8;
  bool allow_not_simply_connected = false;
  HNetOptions options;
};

// After a run that missed its tolerance with the whole boundary held or gliding: why that is
// likely (the asymptotic lines' equations are hyperbolic, fixed by two crossing curves).
void HintBoundaryControl(const char* command, const VertexControlOptions& vertices,
                         bool converged) {
  if (converged || !(vertices.fix_boundary || vertices.glide_boundary)) return;
  std::fprintf(stderr,
               "gproj %s: note: an asymptotic net is fixed by two crossing boundary curves; "
               "keeping the whole boundary%s over-determines it unless the boundary is already "
               "asymptotic (hold a few vertices with --fixed instead)\n",
               command, vertices.glide_boundary ? " on the input's loops" : "");
}

void AddSharedOptions(CLI::App* cmd, NetArgs* args) {
  ANetOptions& o = args->options.anet;
  cmd->add_option("input", args->input,
                  "Quad mesh roughly along asymptotic directions (.obj/.off/.ply)")
      ->required();
  cmd->add_option("--reference", args->reference,
                  "Reference surface (polygon mesh) to stay close to; default: the input itself");
  cmd->add_option("--report", args->report, "Write a JSON report (history and final measures)");
  cmd->add_option("--star-form", args->star_form,
                  "Vertex-star planarity: normals (auxiliary normal per inner vertex) or quads "
                  "(n-2 quads of each star)")
      ->check(CLI::IsMember({"normals", "quads"}))
      ->capture_default_str();
  cmd->add_option("--solver", args->solver,
                  "gp: guided projection (default); ceres: Levenberg-Marquardt on the same rows "
                  "(cross-check; closeness and fairness at fixed weights)")
      ->check(CLI::IsMember({"gp", "ceres"}))
      ->capture_default_str();
  cmd->add_option("--tolerance", o.tolerance,
                  "A-net step stops when max star planarity (neighbour distance from the star "
                  "plane / mean edge) is <= this")
      ->check(Positive())
      ->capture_default_str();
  cmd->add_option("--tangent", o.tangent_weight,
                  "Weight of the distance to the reference's tangent planes")
      ->check(NonNegative())
      ->capture_default_str();
  cmd->add_option("--point", o.point_weight,
                  "Weight of the distance to the reference's closest points")
      ->check(NonNegative())
      ->capture_default_str();
  cmd->add_option("--fairness-order", o.fairness_order, "2: second differences, 3: third")
      ->check(CLI::IsMember({2, 3}))
      ->capture_default_str();
  AddSolverOptions(cmd, &o.solver, &args->linear_solver);
  AddPanelBoundsOptions(cmd, &o.panels);
  AddVertexControlOptions(cmd, &args->fixed, &o.vertices);
}

// Reads the inputs, checks the output paths and fills the options; returns false after printing
// the error.
bool Prepare(const char* name, NetArgs* args, PolyMesh* mesh,
             std::unique_ptr<PolyMesh>* reference) {
  args->options.anet.star_form =
      args->star_form == "quads" ? StarPlanarityForm::kQuads : StarPlanarityForm::kNormals;
  try {
    ApplyLinearSolver(args->linear_solver, &args->options.anet.solver);
    CheckHeatmapPath(args->heatmap);
    CheckOutputPaths(
        {{"input", args->input}, {"--reference", args->reference}, {"--fixed", args->fixed}},
        {{"--output", args->output, std::string(name) == "anet"},
         {"--report", args->report},
         {"--picture", args->picture},
         {"--face-values", args->face_values},
         {"--heatmap", args->heatmap, true},
         {"--surface-mesh", args->surface_mesh, true}});
    *mesh = ReadMesh(args->input, MeshRequirements{true});
    CheckANetTopology(*mesh, args->input);
    if (!args->fixed.empty())
      args->options.anet.vertices.fixed =
          ReadVertexIds(args->fixed, static_cast<int>(mesh->n_vertices()));
    if (!args->reference.empty()) reference->reset(new PolyMesh(ReadMesh(args->reference)));
  } catch (const InputError& e) {
    std::cerr << "gproj " << name << ": " << e.what() << "\n";
    return false;
  }
  return true;
}

const IterationLog& StarLog() {
  static const IterationLog log(
      {"max_star_planarity", "mean_star_planarity", "non_convex_quads", "min_corner_angle_deg"});
  return log;
}

// Prints one H-net round, with the table's header before round 0.
void LogRound(const HNetRound& r) {
  if (r.round == 0)
    std::printf("H-net rounds:\n%5s %14s %12s %12s %12s %12s %8s\n", "round", "max_angle_deg",
                "W_change", "W_min", "W_max", "max_star", "iters");
  std::printf("%5d %14.3e %12.3e %12.4e %12.4e %12.3e %8d\n", r.round, r.max_tangent_angle_deg,
              r.weight_change, r.min_w, r.max_w, r.star.max_star_planarity, r.solver_iterations);
  std::fflush(stdout);
}

// The patches (JSON), the sampled surface, the picture and the report.
void WriteHNetOutputs(const NetArgs& args, const HNet& hnet, const HNetRound& last,
                      const nlohmann::json& report) {
  OutputFiles files;
  files.AddText(args.output, HNetJson(hnet.mesh(), hnet.weights()).dump(1) + "\n");
  if (!args.surface_mesh.empty())
    files.AddMesh(SampleHNetSurface(hnet.mesh(), hnet.weights(), args.samples), args.surface_mesh);
  if (!args.picture.empty()) {
    SvgOptions svg;
    char title[160];
    std::snprintf(title, sizeof(title),
                  "H-net: %zu patches, max tangent-plane angle %.2e deg, W in [%.4g, %.4g]",
                  hnet.mesh().n_faces(), last.max_tangent_angle_deg, last.min_w, last.max_w);
    svg.title = title;
    files.AddText(args.picture,
                  RenderMeshSvg(SampleHNetSurface(hnet.mesh(), hnet.weights(), 2), svg));
  }
  if (!args.report.empty()) files.AddText(args.report, report.dump(2) + "\n");
  files.Commit();
}

int RunHNet(NetArgs& args) {
  PolyMesh mesh;
  std::unique_ptr<PolyMesh> reference;
  if (!Prepare("hnet", &args, &mesh, &reference)) return kExitInputError;
  args.options.allow_not_simply_connected = args.allow_not_simply_connected;
  args.options.use_ceres = args.solver == "ceres";
  std::unique_ptr<HNet> hnet;
  try {
    hnet = std::make_unique<HNet>(mesh, reference.get(), args.options);
  } catch (const InputError& e) {
    std::cerr << "gproj hnet: " << args.input << ": " << e.what() << "\n";
    return kExitInputError;
  }
  std::printf("gproj hnet: %s: %zu vertices, %zu quads\nA-net step:\n", args.input.c_str(),
              mesh.n_vertices(), mesh.n_faces());
  StarLog().PrintHeader();
  const HNetSummary summary =
      hnet->Run([](const RunRecord& r) { return StarLog().Print(r), true; }, LogRound);
  const RunReport& report = summary.report;
  if (report.failed || summary.rounds.empty()) return ConcludeRun("hnet", report, "", 0.0, {});
  nlohmann::json json = HNet::ReportJson(summary);
  json.update({{"input", args.input}, {"output", args.output}});
  try {
    WriteHNetOutputs(args, *hnet, summary.rounds.back(), json);
  } catch (const InputError& e) {
    std::cerr << "gproj hnet: " << e.what() << "\n";
    return kExitInputError;
  }
  const HNetRound& last = summary.rounds.back();
  std::printf(
      "final: max tangent-plane angle %.3e deg, W in [%.4g, %.4g], max star planarity %.3e, max "
      "displacement %.3e of the bbox diagonal\n",
      last.max_tangent_angle_deg, last.min_w, last.max_w, last.star.max_star_planarity,
      last.star.max_displacement);
  if (reference != nullptr)
    std::printf("distance to the reference surface: max %.3e of its bbox diagonal\n",
                summary.max_reference_distance);
  if (!summary.equitwist_violations.empty())
    std::printf("warning: %zu inner edges violate the equitwist condition (listed in the report)\n",
                summary.equitwist_violations.size());
  if (!summary.simply_connected)
    std::printf(
        "note: the mesh is not simply connected, so no exact extension need exist: round 0 "
        "propagated the weights over a spanning tree, round 1 optimised the vertices and weights "
        "together (W near 1, W >= %g); the report lists the worst edges\n",
        args.options.min_shape_parameter);
  HintBoundaryControl("hnet", args.options.anet.vertices, report.converged);
  return ConcludeRun("hnet", report, "weight_change", args.options.weight_tolerance,
                     {args.output, args.surface_mesh, args.picture, args.report});
}

}  // namespace

void RegisterNetCommands(CLI::App* app, int* exit_code) {
  auto hnet = std::make_shared<NetArgs>();
  CLI::App* h = app->add_subcommand(
      "hnet",
      "H-net: extend an A-net (running the A-net step first when needed) to smoothly joined "
      "rational bilinear patches (004 §2-3). Exit codes as for planarize.");
  AddSharedOptions(h, hnet.get());
  h->add_option("-o,--output", hnet->output,
                "H-net JSON to write: vertices, quad faces, four corner weights per face")
      ->required();
  h->add_option("--surface-mesh", hnet->surface_mesh,
                "Also write a triangle mesh sampling every patch (.obj/.off/.ply)");
  h->add_option("--picture", hnet->picture,
                "Also write a shaded picture of the patchwork (.svg, opens in any browser)");
  h->add_option("--samples", hnet->samples, "Samples per patch edge for --surface-mesh")
      ->check(Within(1, 200))
      ->capture_default_str();
  h->add_option("--rounds", hnet->options.max_rounds,
                "Alternations of weight and vertex updates at most")
      ->check(Within(1, 1000))
      ->capture_default_str();
  h->add_option("--frame-weight", hnet->options.frame_weight, "Weight of frame-point planarity")
      ->check(Positive())
      ->capture_default_str();
  h->add_flag(
      "--allow-not-simply-connected", hnet->allow_not_simply_connected,
      "Optimise meshes that are not simply connected (no exact extension exists in general): "
      "the vertices and the shape parameters are solved for together");
  h->callback([hnet, exit_code]() { *exit_code = RunHNet(*hnet); });
}

}  // namespace gproj
