// `gproj planarize`: PQ (or circular) planarisation of a quad mesh, on the shared run layer.
#include <cstdio>
#include <iostream>
#include <memory>
#include <string>

#include "apps/commands.h"
#include "geometry/mesh_io.h"
#include "geometry/svg_render.h"
#include "problems/pq_planarization.h"

namespace gproj {
namespace {

struct PlanarizeArgs {
  std::string input, output, report, picture, solver = "gp", linear_solver = "cholmod";
  std::string reference, fixed, face_values, heatmap;
  PQPlanarizationOptions options;
};

int RunPlanarize(PlanarizeArgs args) {
  PQPlanarizationOptions& options = args.options;
  std::unique_ptr<PQPlanarization> pq;
  PolyMesh input;
  try {
    ApplyLinearSolver(args.linear_solver, &options.solver);
    std::string why;
    if (!options.IsValid(&why)) throw InputError("invalid option: " + why);
    CheckHeatmapPath(args.heatmap);
    CheckOutputPaths(
        {{"input", args.input}, {"--reference", args.reference}, {"--fixed", args.fixed}},
        {{"--output", args.output, true},
         {"--report", args.report},
         {"--picture", args.picture},
         {"--face-values", args.face_values},
         {"--heatmap", args.heatmap, true}});
    input = ReadMesh(args.input, MeshRequirements{true});
    if (!args.fixed.empty())
      options.vertices.fixed = ReadVertexIds(args.fixed, static_cast<int>(input.n_vertices()));
    std::unique_ptr<PolyMesh> reference;
    if (!args.reference.empty()) reference = std::make_unique<PolyMesh>(ReadMesh(args.reference));
    pq = std::make_unique<PQPlanarization>(input, options, reference.get());
  } catch (const InputError& e) {
    std::cerr << "gproj planarize: " << e.what() << "\n";
    return kExitInputError;
  }
  const PlanarityMeasures initial = pq->Measures();
  std::printf("gproj planarize: %s: %zu vertices, %zu quads, %d variables, solver %s\n",
              args.input.c_str(), input.n_vertices(), input.n_faces(),
              pq->problem().layout().num_variables(),
              args.solver == "gp" ? LinearSolverTypeName(options.solver.linear_solver) : "ceres");
  std::printf("start: max planarity %.3e, mean %.3e (diagonal distance / mean edge)\n",
              initial.max_planarity, initial.mean_planarity);
  IterationLog log({"max_planarity", "mean_planarity", "non_convex_quads", "min_corner_angle_deg"});
  log.PrintHeader();
  const auto print = [&log](const RunRecord& r) { return log.Print(r), true; };
  const RunReport report =
      args.solver == "gp" ? pq->Run(print) : pq->RunCeres(options.solver.max_iterations, print);
  const PlanarityMeasures final_measures = pq->Measures();
  nlohmann::json extra = PlanarizationFacts(input, pq->Result(), options);
  extra["input"] = args.input;
  extra["output"] = report.failed ? "" : args.output;
  try {
    OutputFiles files;
    if (!report.failed) {
      const PolyMesh result = pq->Result();
      files.AddMesh(result, args.output);
      char title[128];
      std::snprintf(title, sizeof(title), "%zu quads, max planarity %.2e", input.n_faces(),
                    final_measures.max_planarity);
      AddFaceOutputs(result, RelativeFacePlanarity(result, options.circular),
                     PlanarityColourScale(result, options.circular),
                     QuadShapesCsv(result, options.circular), args.face_values, args.heatmap,
                     args.picture, title, &files);
    }
    if (!report.failed && !args.report.empty())
      files.AddText(args.report, ReportJson("planarize", report, extra).dump(2) + "\n");
    files.Commit();
  } catch (const InputError& e) {
    std::cerr << "gproj planarize: " << e.what() << "\n";
    return kExitInputError;
  }
  if (!report.failed) {
    std::printf(
        "final: max planarity %.3e, mean %.3e, max displacement %.3e of the bbox diagonal\n",
        final_measures.max_planarity, final_measures.mean_planarity,
        final_measures.max_displacement);
    if (final_measures.max_concyclicity >= 0.0)
      std::printf("       max concyclicity %.3e (distance to the fitted circle / mean edge)\n",
                  final_measures.max_concyclicity);
    PrintPanelSummary(report.initial, report.final);
    WarnIfFarFromInput("planarize", options.circular ? "a circular mesh" : "a PQ (conjugate) mesh",
                       input, pq->Result(), final_measures.max_displacement, 10.0);
  }
  const int code =
      ConcludeRun("planarize", report, "max_planarity", options.tolerance,
                  {args.output, args.picture, args.face_values, args.heatmap, args.report});
  if (code == kExitNotConverged) {
    const std::vector<int> above = pq->FacesAboveTolerance();
    const std::vector<int> held = pq->FacesAtAngleBound();
    if (!above.empty())
      std::fprintf(stderr, "gproj planarize: %zu quads above the tolerance, worst first: %s\n",
                   above.size(), FaceList(above).c_str());
    if (!held.empty())
      std::fprintf(stderr,
                   "gproj planarize: %zu quads sit on their corner-angle bound (--min-angle %g): "
                   "%s\n",
                   held.size(), options.panels.min_angle_deg, FaceList(held).c_str());
    const std::vector<std::array<int, 2>> short_or_long = pq->EdgesAtLengthBound();
    if (!short_or_long.empty())
      std::fprintf(stderr, "gproj planarize: %zu edges sit on their length bound (%s): %s\n",
                   short_or_long.size(),
                   options.panels.min_edge_length > 0.0 || options.panels.max_edge_length > 0.0
                       ? "--edge-length"
                       : "a tenth of their input length",
                   EdgeList(short_or_long).c_str());
  }
  return code;
}

}  // namespace

void RegisterPlanarizeCommand(CLI::App* app, int* exit_code) {
  auto args = std::make_shared<PlanarizeArgs>();
  CLI::App* cmd = app->add_subcommand(
      "planarize",
      "PQ planarisation: make every quad of a mesh planar while staying close to the input and "
      "fair. Exit codes: 0 converged, 1 bad input or option (nothing written), 3 tolerance not "
      "reached (result written), 4 numerical failure (nothing written).");
  cmd->add_option("input", args->input, "Quad mesh to planarise (.obj, .off or .ply)")->required();
  cmd->add_option("-o,--output", args->output,
                  "Where to write the planarised mesh (.obj, .off or .ply); written atomically")
      ->required();
  cmd->add_option("--report", args->report,
                  "Write a JSON report: converged, iterations, seconds, variables, per-iteration "
                  "history and the initial and final measures");
  AddFaceOutputOptions(cmd, &args->face_values, &args->heatmap, &args->picture,
                       "face, planarity (/ mean edge), planarity_abs (input units), kink_deg "
                       "(between the quad's two triangles), min_angle_deg (and concyclicity with "
                       "--circular)",
                       "planarity");
  cmd->add_option("--solver", args->solver,
                  "gp: guided projection (default); ceres: Levenberg-Marquardt on the same "
                  "residuals (cross-check)")
      ->check(CLI::IsMember({"gp", "ceres"}));
  cmd->add_option("--tolerance", args->options.tolerance,
                  "Stop when max planarity (diagonal distance / mean edge length) is <= this")
      ->check(Positive())
      ->capture_default_str();
  cmd->add_option("--closeness", args->options.closeness_weight,
                  "Weight of closeness to the input vertices (mesh scaled to mean edge 1)")
      ->check(NonNegative())
      ->capture_default_str();
  cmd->add_flag("--circular", args->options.circular,
                "Circular quads (planar and concyclic, 000 §2) instead of planar ones; the "
                "tolerance also bounds the concyclicity (distance to the fitted circle / mean "
                "edge)");
  cmd->add_option("--fairness-order", args->options.fairness_order,
                  "2: second differences, 3: third differences")
      ->check(CLI::IsMember({2, 3}))
      ->capture_default_str();
  cmd->add_option("--ceres-soft-scale", args->options.ceres_soft_scale,
                  "With --solver ceres: fixed factor on the closeness and fairness weights "
                  "(0: tolerance / 100)")
      ->check(NonNegative())
      ->capture_default_str();
  AddSolverOptions(cmd, &args->options.solver, &args->linear_solver);
  AddPanelBoundsOptions(cmd, &args->options.panels);
  AddVertexControlOptions(cmd, &args->fixed, &args->options.vertices);
  cmd->add_option("--reference", args->reference,
                  "Reference surface (triangle or polygon mesh): vertices keep close to it through "
                  "the tangent plane of their closest point (sliding along it) instead of to "
                  "their start");
  cmd->callback([args, exit_code]() { *exit_code = RunPlanarize(*args); });
}

}  // namespace gproj
