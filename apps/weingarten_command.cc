// `gproj weingarten`: Weingarten surfaces on B-splines (003).
#include <chrono>
#include <cmath>
#include <cstdio>
#include <iostream>
#include <memory>
#include <nlohmann/json.hpp>
#include <sstream>
#include <string>
#include <vector>

#include "apps/commands.h"
#include "geometry/bspline_surface.h"
#include "geometry/curvature_diagram.h"
#include "geometry/svg_render.h"
#include "problems/weingarten.h"

namespace gproj {
namespace {

struct WeingartenArgs {
  std::string input, output, preset = "fig1", relation, report, diagram, curvature, picture,
                             surface_mesh, steps, relation_on, solver = "gp";
  bool no_auxiliaries = false;
  std::vector<int> samples;
  std::vector<double> linear;
  int refine = 0, max_iterations = 0, molds = 0;
  double alignment = -1, closeness = -1, shape = -1, geodesic = -1, boundary = -1, epsilon = -1,
         fairness = -1, definitions = -1, soft_start = -1;
};

std::string CurvatureCsv(const SampleMaps& maps, const WeingartenMeasures& before,
                         const WeingartenMeasures& after, const MoldClustering* molds) {
  std::ostringstream out;
  out.precision(10);
  out << "sample,u,v,H_before,K_before,H_after,K_after" << (molds ? ",mold" : "") << "\n";
  for (int a = 0; a < maps.su; ++a)
    for (int b = 0; b < maps.sv; ++b) {
      const int s = maps.Index(a, b);
      out << s << "," << maps.u[a] << "," << maps.v[b] << "," << before.h[s] << "," << before.k[s]
          << "," << after.h[s] << "," << after.k[s];
      if (molds) out << "," << molds->cluster[s];
      out << "\n";
    }
  return out.str();
}

WeingartenOptions OptionsFromArgs(const WeingartenArgs& args) {
  WeingartenOptions options = WeingartenPreset(args.preset);
  if (args.samples.size() == 2) {
    options.samples_u = args.samples[0];
    options.samples_v = args.samples[1];
  } else if (!args.samples.empty()) {
    throw InputError("--samples needs two numbers: NU NV");
  }
  if (!args.relation.empty()) {
    const double w = args.relation == "none" ? 0.0 : 1.0;
    options.linear_relation_weight = args.relation == "linear" ? w : 0.0;
    options.bspline_relation_weight = args.relation == "bspline" ? 10.0 * w : 0.0;
  }
  if (!args.linear.empty()) {
    if (args.linear.size() != 3) throw InputError("--linear needs a,b,c");
    options.fixed_linear_relation = true;
    options.linear_coefficients = Eigen::Vector3d(args.linear[0], args.linear[1], args.linear[2]);
    if (options.linear_relation_weight == 0.0) options.linear_relation_weight = 1.0;
    options.bspline_relation_weight = 0.0;
  }
  if (args.alignment >= 0) options.alignment_weight = args.alignment;
  if (args.closeness >= 0) options.closeness_weight = args.closeness;
  if (args.shape >= 0) options.shape_weight = args.shape;
  if (args.geodesic >= 0) options.geodesic_parallel_weight = args.geodesic;
  if (args.boundary >= 0) options.boundary_weight = args.boundary;
  if (args.epsilon > 0) options.epsilon = args.epsilon;
  if (args.fairness >= 0) options.fairness_weight = args.fairness;
  if (args.definitions > 0) options.definition_weight = args.definitions;
  if (args.soft_start >= 1) options.soft_start = args.soft_start;
  if (args.max_iterations > 0) options.max_iterations = args.max_iterations;
  if (!args.steps.empty()) {
    options.monotone = args.steps != "plain";
    options.project_auxiliaries = args.steps == "projected";
  }
  if (!args.relation_on.empty()) options.relation_on_surface = args.relation_on == "surface";
  if (args.no_auxiliaries) options.curvature_auxiliaries = false;
  options.refine_levels = args.refine;
  std::string why;
  if (!options.IsValid(&why)) throw InputError(why);
  return options;
}

nlohmann::json FamiliesJson(const RunRecord& r) {
  nlohmann::json families = nlohmann::json::object();
  for (const auto& f : r.families) families[f.name] = {{"max", f.max_abs}, {"rms", f.rms}};
  return families;
}

nlohmann::json WeingartenReport(const WeingartenArgs& args, const WeingartenOptions& options,
                                const WeingartenRun& run, double seconds) {
  nlohmann::json history = nlohmann::json::array(), levels = nlohmann::json::array();
  for (size_t i = 0; i < run.history.size(); ++i) {
    const RunRecord& r = run.history[i];
    history.push_back(
        {{"level", run.history_level[i]},
         {"iteration", r.iteration},
         {"energy", r.energy},
         {"max_constraint", std::isfinite(r.max_constraint) ? nlohmann::json(r.max_constraint)
                                                            : nlohmann::json(nullptr)},
         {"step", r.step},
         {"families", FamiliesJson(r)}});
  }
  for (const WeingartenLevel& l : run.levels)
    levels.push_back({{"level", l.level},
                      {"control_points", {l.nu, l.nv}},
                      {"samples", {l.su, l.sv}},
                      {"variables", l.variables},
                      {"iterations", l.iterations},
                      {"misalignment", l.misalignment}});
  const WeingartenMeasures& before = run.before;
  const WeingartenMeasures& after = run.after;
  nlohmann::json report = {
      {"command", "weingarten"},
      {"input", args.input},
      {"output", args.output},
      {"preset", args.preset},
      {"solver", args.solver},
      {"steps", options.project_auxiliaries ? "projected"
                : options.monotone          ? "monotone"
                                            : "plain"},
      {"converged", run.converged},
      {"termination", run.termination},
      {"iterations", run.iterations},
      {"seconds", seconds},
      {"variables", run.variables},
      {"samples", {run.su, run.sv}},
      {"levels", levels},
      {"history", history},
      {"initial", {{"misalignment", before.misalignment}}},
      {"final",
       {{"misalignment", after.misalignment},
        {"max_deviation", after.max_deviation},
        {"mean_deviation", after.mean_deviation},
        {"worst_sample", {after.worst_sample / run.sv, after.worst_sample % run.sv}},
        {"misalignment_ratio", before.misalignment / std::max(after.misalignment, 1e-300)}}}};
  if (!run.history.empty()) report["final"]["families"] = FamiliesJson(run.history.back());
  return report;
}

// The relation's worst residual over the samples (a² + b² = 1, input units).
double MaxRelationResidual(const WeingartenRun& run) {
  double worst = 0.0;
  for (size_t i = 0; i < run.after.h.size(); ++i)
    worst = std::max(worst, std::abs(run.relation[0] * run.after.h[i] +
                                     run.relation[1] * run.after.k[i] + run.relation[2]));
  return worst;
}

// The relation's coefficients and worst residual, and the mold clustering, into the report.
std::unique_ptr<MoldClustering> AddRelationAndMolds(const WeingartenArgs& args,
                                                    const WeingartenOptions& options,
                                                    const WeingartenRun& run,
                                                    nlohmann::json* report) {
  if (options.linear_relation_weight > 0.0) {
    const double worst = MaxRelationResidual(run);
    (*report)["final"]["linear_relation"] = {run.relation[0], run.relation[1], run.relation[2]};
    (*report)["final"]["max_relation_residual"] = worst;
    std::printf("linear relation %.6g H + %.6g K + %.6g = 0 (input units): max residual %.3e\n",
                run.relation[0], run.relation[1], run.relation[2], worst);
  }
  if (args.molds <= 0) return nullptr;
  auto molds = std::make_unique<MoldClustering>(ClusterMolds(run.after.h, run.after.k, args.molds));
  const MoldClustering molds_before = ClusterMolds(run.before.h, run.before.k, args.molds);
  (*report)["molds"] = {{"asked", args.molds},
                        {"clusters", molds->num_clusters},
                        {"cells_per_axis", molds->cells_per_axis},
                        {"cluster_sizes", molds->cluster_size},
                        {"before_cells_per_axis", molds_before.cells_per_axis}};
  return molds;
}

void WriteWeingartenOutputs(const WeingartenArgs& args, const WeingartenRun& run,
                            const MoldClustering* molds) {
  const BSplineSurface& current = run.result;
  WriteBSplineJson(current, args.output);
  const SampleMaps maps = MakeSampleMaps(current, run.su, run.sv);
  if (!args.curvature.empty())
    WriteTextFileAtomically(args.curvature, CurvatureCsv(maps, run.before, run.after, molds));
  if (!args.diagram.empty()) {
    DiagramOptions d;
    char title[160];
    std::snprintf(title, sizeof(title), "Curvature diagram: misalignment %.3g -> %.3g",
                  run.before.misalignment, run.after.misalignment);
    d.title = title;
    WriteTextFileAtomically(
        args.diagram, RenderCurvatureDiagramSvg({{"before", "#c0392b", run.before.h, run.before.k},
                                                 {"after", "#2c6fbb", run.after.h, run.after.k}},
                                                d));
  }
  if (!args.surface_mesh.empty())
    WriteMeshAtomically(SampleSurfaceMesh(current, 4 * current.nu, 4 * current.nv),
                        args.surface_mesh);
  if (!args.picture.empty()) {
    SvgOptions svg;
    svg.title = "Weingarten surface (" + std::to_string(current.nu) + " x " +
                std::to_string(current.nv) + " control points)";
    WriteTextFileAtomically(args.picture, RenderMeshSvg(SampleSurfaceMesh(current, 60, 60), svg));
  }
}

int RunWeingartenCommand(const WeingartenArgs& args) {
  const auto start = std::chrono::steady_clock::now();
  try {
    const WeingartenOptions options = OptionsFromArgs(args);
    CheckOutputPath("--output", args.output);
    for (const auto& [option, path] :
         {std::pair<const char*, const std::string*>{"--report", &args.report},
          {"--diagram", &args.diagram},
          {"--curvature", &args.curvature},
          {"--picture", &args.picture}})
      CheckOutputPath(option, *path);
    CheckMeshOutputPath("--surface-mesh", args.surface_mesh);
    const BSplineSurface input = ReadBSplineJson(args.input);
    const auto on_level = [&](int level, const WeingartenProblem& problem) {
      const WeingartenMeasures m = problem.Measures();
      const BSplineSurface surface = problem.Result();  // the level's start
      std::printf(
          "gproj weingarten: %s%s: %d x %d control points, bi-degree (%d, %d), %d x %d samples, "
          "%d unknowns; preset %s\n",
          args.input.c_str(), level > 0 ? (" (level " + std::to_string(level) + ")").c_str() : "",
          surface.nu, surface.nv, surface.degree_u, surface.degree_v, problem.maps().su,
          problem.maps().sv, problem.num_variables(), args.preset.c_str());
      std::printf("start: misalignment %.4e, mean |principal curvature| %.4g (scaled by %.4g)\n",
                  m.misalignment, m.mean_abs_principal_curvature, problem.scale());
      std::printf("%5s %13s %12s %11s %10s\n", "iter", "energy", "max_constr", "step", "seconds");
    };
    const auto on_iteration = [&](const RunRecord& r) {
      char constraint[32] = "           -";  // Ceres reports no per-row maximum
      if (std::isfinite(r.max_constraint))
        std::snprintf(constraint, sizeof(constraint), "%12.4e", r.max_constraint);
      std::printf("%5d %13.6e %s %11.3e %10.3f\n", r.iteration, r.energy, constraint, r.step,
                  std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count());
      std::fflush(stdout);
      return true;
    };
    const WeingartenRun run =
        RunWeingarten(input, options, args.solver != "gp", on_iteration, on_level);
    if (run.failed) {
      std::cerr << "gproj weingarten: solver failed: " << run.termination << "; nothing written\n";
      return kExitSolverFailure;
    }
    const double seconds =
        std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    nlohmann::json report = WeingartenReport(args, options, run, seconds);
    const std::unique_ptr<MoldClustering> molds = AddRelationAndMolds(args, options, run, &report);
    WriteWeingartenOutputs(args, run, molds.get());
    if (!args.report.empty()) WriteTextFileAtomically(args.report, report.dump(2) + "\n");
    std::printf(
        "misalignment %.4e -> %.4e (%.1fx lower), deviation max %.3e (sample %d, %d) / "
        "mean %.3e of the bbox diagonal, %d iterations, %.2f s\n",
        run.before.misalignment, run.after.misalignment,
        run.before.misalignment / std::max(run.after.misalignment, 1e-300), run.after.max_deviation,
        run.after.worst_sample / run.sv, run.after.worst_sample % run.sv, run.after.mean_deviation,
        run.iterations, seconds);
    if (molds)
      std::printf("molds: %d clusters in the (H, sqrt K) plane (grid %d x %d)\n",
                  molds->num_clusters, molds->cells_per_axis, molds->cells_per_axis);
    std::printf("wrote %s", args.output.c_str());
    for (const std::string* f :
         {&args.report, &args.diagram, &args.curvature, &args.surface_mesh, &args.picture})
      if (!f->empty()) std::printf(", %s", f->c_str());
    std::printf("\n");
    return kExitOk;
  } catch (const InputError& e) {
    std::cerr << "gproj weingarten: " << e.what() << "\n";
    return kExitInputError;
  }
}

}  // namespace

void RegisterWeingartenCommand(CLI::App* app, int* exit_code) {
  auto args = std::make_shared<WeingartenArgs>();
  std::string presets;
  for (const auto& n : WeingartenPresetNames()) presets += (presets.empty() ? "" : ", ") + n;
  CLI::App* cmd = app->add_subcommand(
      "weingarten",
      "Weingarten surface (003): moves the control points of a B-spline (JSON, SPEC §4) so that "
      "the isolines of H and K align, keeping it close to the input. Exit codes as for "
      "planarize.");
  cmd->add_option("input", args->input, "B-spline surface (.json)")->required();
  cmd->add_option("-o,--output", args->output, "Optimised B-spline (.json)")->required();
  cmd->add_option("--preset", args->preset, "Weights of 003 Table 1: " + presets)
      ->capture_default_str();
  cmd->add_option("--samples", args->samples,
                  "Samples NU NV (default: 2 per control point and direction, as in Table 2)")
      ->expected(2);
  cmd->add_option("--relation", args->relation,
                  "Curvature relation: none, linear (fitted each iteration) or bspline")
      ->check(CLI::IsMember({"none", "linear", "bspline"}));
  cmd->add_option("--linear", args->linear,
                  "Fixed linear relation a,b,c: a H + b K + c = 0 in input units (e.g. 0,1,0: "
                  "developable; 1,0,0: minimal; 1,0,-c: H = c)")
      ->delimiter(',');
  cmd->add_option("--relation-on", args->relation_on,
                  "A fixed relation's rows use H, K of the surface itself (default) or the "
                  "auxiliaries (003 §3.2.2)")
      ->check(CLI::IsMember({"surface", "auxiliaries"}));
  cmd->add_option("--steps", args->steps,
                  "plain: every step kept (default); monotone: a step is kept only if it lowers "
                  "the energy, else ε grows; projected: monotone, and the auxiliaries are reset "
                  "to their exact values after each step (default of preset fig3)")
      ->check(CLI::IsMember({"plain", "monotone", "projected"}));
  cmd->add_option("--solver", args->solver,
                  "gp: guided projection (default); ceres: Levenberg-Marquardt on the same rows "
                  "(soft terms at their final weights)")
      ->check(CLI::IsMember({"gp", "ceres"}))
      ->capture_default_str();
  cmd->add_flag("--no-auxiliaries", args->no_auxiliaries,
                "Control points are the only unknowns (only with --linear and the relation on "
                "the surface)");
  cmd->add_option("--alignment", args->alignment, "Override ω_al (isoline alignment)");
  cmd->add_option("--closeness", args->closeness, "Override ω_cl (closeness to the input)");
  cmd->add_option("--shape", args->shape, "Override ω_sh (control-net lengths)");
  cmd->add_option("--geodesic-parallel", args->geodesic, "Override ω_gp (eq. 8)");
  cmd->add_option("--epsilon", args->epsilon, "Override ε of eq. 11 (proximal weight)");
  cmd->add_option("--soft-start", args->soft_start,
                  "Soft terms start this many times stronger and relax to their weights (≥ 1)");
  cmd->add_option("--fairness", args->fairness, "Override ω_f of eq. 11 (control-net fairness)");
  cmd->add_option("--definitions", args->definitions,
                  "Weight of the rows defining the auxiliaries (relative errors; default 1)");
  cmd->add_option("--boundary", args->boundary,
                  "Weight of boundary gliding along the input's boundary control polygon");
  cmd->add_option("--refine", args->refine,
                  "Multiresolution levels: insert a knot in every span and re-optimise")
      ->check(CLI::Range(0, 4))
      ->capture_default_str();
  cmd->add_option("--max-iterations", args->max_iterations,
                  "Guided-projection iterations per level (default 10)");
  cmd->add_option("--molds", args->molds,
                  "Cluster the samples into at most this many molds in the (H, sqrt K) plane");
  cmd->add_option("--diagram", args->diagram, "Curvature diagram before/after (.svg)");
  cmd->add_option("--curvature", args->curvature, "H, K per sample before/after (.csv)");
  cmd->add_option("--surface-mesh", args->surface_mesh, "The result sampled as a quad mesh");
  cmd->add_option("--picture", args->picture, "A shaded picture of the result (.svg)");
  cmd->add_option("--report", args->report, "Write a JSON report");
  cmd->callback([args, exit_code]() { *exit_code = RunWeingartenCommand(*args); });
}

}  // namespace gproj
