// `gproj planarize`: PQ planarisation of a quad mesh.
#include <chrono>
#include <cmath>
#include <cstdio>
#include <iostream>
#include <memory>
#include <nlohmann/json.hpp>
#include <string>

#include "apps/commands.h"
#include "geometry/mesh_io.h"
#include "geometry/svg_render.h"
#include "problems/pq_planarization.h"

namespace gproj {
namespace {

struct PlanarizeArgs {
  std::string input;
  std::string output;
  std::string report;
  std::string picture;
  std::string solver = "gp";
  std::string linear_solver = "cholmod";
  PQPlanarizationOptions options;
};

nlohmann::json MeasuresJson(const PlanarityMeasures& m) {
  nlohmann::json j = {{"max_planarity", m.max_planarity},
                      {"mean_planarity", m.mean_planarity},
                      {"max_displacement", m.max_displacement},
                      {"mean_edge_length", m.mean_edge_length}};
  if (m.max_concyclicity >= 0.0) j["max_concyclicity"] = m.max_concyclicity;
  return j;
}

int RunPlanarize(const PlanarizeArgs& args) {
  const auto start = std::chrono::steady_clock::now();
  PQPlanarizationOptions options = args.options;
  if (!ParseLinearSolverType(args.linear_solver, &options.linear_solver)) {
    std::cerr << "gproj planarize: --linear-solver must be cholmod or eigen, not '"
              << args.linear_solver << "'\n";
    return kExitInputError;
  }
  std::string why;
  if (!options.IsValid(&why)) {
    std::cerr << "gproj planarize: invalid option: " << why << "\n";
    return kExitInputError;
  }
  std::unique_ptr<PQPlanarization> pq;
  PolyMesh input;
  try {
    input = ReadMesh(args.input, MeshRequirements{true});
    pq = std::make_unique<PQPlanarization>(input, options);
  } catch (const InputError& e) {
    std::cerr << "gproj planarize: " << e.what() << "\n";
    return kExitInputError;
  }
  const PlanarityMeasures initial = pq->Measures();
  std::printf("gproj planarize: %s: %zu vertices, %zu quads, %d variables, solver %s\n",
              args.input.c_str(), input.n_vertices(), input.n_faces(),
              pq->problem().layout().num_variables(),
              args.solver == "gp" ? LinearSolverTypeName(options.linear_solver) : "ceres");
  std::printf("start: max planarity %.3e, mean %.3e (diagonal distance / mean edge)\n",
              initial.max_planarity, initial.mean_planarity);

  nlohmann::json history = nlohmann::json::array();
  bool converged = false, failed = false;
  std::string message;
  int iterations = 0;
  if (args.solver == "gp") {
    std::printf("%5s %13s %13s %13s %11s %10s\n", "iter", "energy", "max_planarity", "mean_planar",
                "step", "time_s");
    const SolverSummary summary =
        pq->Solve([&](const IterationRecord& r, const PlanarityMeasures& m) {
          const double t = r.assembly_seconds + r.factorization_seconds + r.solve_seconds;
          std::printf("%5d %13.6e %13.3e %13.3e %11.3e %10.4f\n", r.iteration, r.energy,
                      m.max_planarity, m.mean_planarity, r.step_norm, t);
          std::fflush(stdout);
          nlohmann::json families = nlohmann::json::object();
          for (const FamilyResidual& f : r.families)
            families[f.name] = {{"max", f.max_abs}, {"rms", f.rms}};
          history.push_back({{"iteration", r.iteration},
                             {"energy", r.energy},
                             {"max_planarity", m.max_planarity},
                             {"mean_planarity", m.mean_planarity},
                             {"step", r.step_norm},
                             {"epsilon", r.epsilon},
                             {"soft_scale", r.soft_scale},
                             {"families", families},
                             {"assembly_seconds", r.assembly_seconds},
                             {"factorization_seconds", r.factorization_seconds},
                             {"solve_seconds", r.solve_seconds}});
          return CallbackResult::kContinue;
        });
    converged = summary.converged();
    failed = summary.termination == TerminationType::kFailure;
    message = std::string(TerminationTypeName(summary.termination)) + ": " + summary.message;
    iterations = summary.num_steps();
  } else {
    std::printf("%5s %13s %13s %13s %11s %10s\n", "iter", "cost", "max_planarity", "mean_planar",
                "step", "time_s");
    const CeresSummary summary = pq->SolveWithCeres(
        options.max_iterations, [&](const CeresIterationRecord& s, const PlanarityMeasures& m) {
          std::printf("%5d %13.6e %13.3e %13.3e %11.3e %10.4f\n", s.iteration, s.cost,
                      m.max_planarity, m.mean_planarity, s.step_norm, s.iteration_time_in_seconds);
          std::fflush(stdout);
          history.push_back({{"iteration", s.iteration},
                             {"energy", s.cost},
                             {"max_planarity", m.max_planarity},
                             {"mean_planarity", m.mean_planarity},
                             {"step", s.step_norm},
                             {"seconds", s.iteration_time_in_seconds}});
          return true;
        });
    const PlanarityMeasures m = pq->Measures();
    converged = pq->MeetsTolerance(m);
    failed = summary.termination == TerminationType::kFailure || !pq->problem().x().allFinite();
    message = "ceres " + summary.ceres_termination + ": " + summary.message;
    iterations = summary.num_steps();
  }
  const PlanarityMeasures final_measures = pq->Measures();
  const double seconds =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();

  nlohmann::json report = {{"command", "planarize"},
                           {"input", args.input},
                           {"output", failed ? "" : args.output},
                           {"solver", args.solver},
                           {"linear_solver", LinearSolverTypeName(options.linear_solver)},
                           {"converged", converged},
                           {"termination", message},
                           {"iterations", iterations},
                           {"seconds", seconds},
                           {"variables", pq->problem().layout().num_variables()},
                           {"vertices", input.n_vertices()},
                           {"faces", input.n_faces()},
                           {"options",
                            {{"tolerance", options.tolerance},
                             {"max_iterations", options.max_iterations},
                             {"planarity_weight", options.planarity_weight},
                             {"closeness_weight", options.closeness_weight},
                             {"fairness_weight", options.fairness_weight},
                             {"fairness_order", options.fairness_order},
                             {"soft_weight_decay", options.soft_weight_decay},
                             {"soft_weight_floor", options.soft_weight_floor},
                             {"epsilon", options.epsilon},
                             {"ceres_soft_scale", options.ceres_soft_scale}}},
                           {"initial", MeasuresJson(initial)},
                           {"final", MeasuresJson(final_measures)},
                           {"history", history}};

  try {
    if (!failed) WriteMeshAtomically(pq->Result(), args.output);
    if (!failed && !args.picture.empty()) {
      SvgOptions svg;
      char title[128];
      std::snprintf(title, sizeof(title), "%zu quads, max planarity %.2e", input.n_faces(),
                    final_measures.max_planarity);
      svg.title = title;
      WriteTextFileAtomically(args.picture, RenderMeshSvg(pq->Result(), svg));
    }
    if (!args.report.empty()) WriteTextFileAtomically(args.report, report.dump(2) + "\n");
  } catch (const InputError& e) {
    std::cerr << "gproj planarize: " << e.what() << "\n";
    return kExitInputError;
  }
  std::printf("%s after %d iterations, %.3f s\n", message.c_str(), iterations, seconds);
  std::printf("final: max planarity %.3e, mean %.3e, max displacement %.3e of the bbox diagonal\n",
              final_measures.max_planarity, final_measures.mean_planarity,
              final_measures.max_displacement);
  if (final_measures.max_concyclicity >= 0.0)
    std::printf("       max concyclicity %.3e (distance to the fitted circle / mean edge)\n",
                final_measures.max_concyclicity);
  if (failed) {
    std::fprintf(stderr, "gproj planarize: solver failed (%s); no mesh written\n", message.c_str());
    return kExitSolverFailure;
  }
  std::printf("wrote %s%s%s\n", args.output.c_str(), args.report.empty() ? "" : " and ",
              args.report.c_str());
  if (!converged) {
    std::fprintf(stderr,
                 "gproj planarize: tolerance %.1e not reached (max planarity %.3e); the result was "
                 "written, exit code %d\n",
                 options.tolerance, final_measures.max_planarity, kExitNotConverged);
    return kExitNotConverged;
  }
  return kExitOk;
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
                  "history and the final measures");
  cmd->add_option("--picture", args->picture,
                  "Also write a shaded picture of the result (.svg, opens in any browser)");
  cmd->add_option("--solver", args->solver,
                  "gp: guided projection (default); ceres: Levenberg-Marquardt on the same "
                  "residuals (cross-check)")
      ->check(CLI::IsMember({"gp", "ceres"}));
  cmd->add_option("--max-iterations", args->options.max_iterations, "Iterations at most")
      ->check(CLI::Range(0, 100000))
      ->capture_default_str();
  cmd->add_option("--tolerance", args->options.tolerance,
                  "Stop when max planarity (diagonal distance / mean edge length) is <= this")
      ->check(CLI::PositiveNumber)
      ->capture_default_str();
  cmd->add_option("--closeness", args->options.closeness_weight,
                  "Weight of closeness to the input vertices (mesh scaled to mean edge 1)")
      ->check(CLI::NonNegativeNumber)
      ->capture_default_str();
  cmd->add_option("--fairness", args->options.fairness_weight,
                  "omega_f: weight of the second-difference fairness along mesh polylines")
      ->check(CLI::NonNegativeNumber)
      ->capture_default_str();
  cmd->add_flag(
      "--circular", args->options.circular,
      "Circular quads (planar and concyclic, 000 §2) instead of planar ones; the "
      "tolerance also bounds the concyclicity (distance to the fitted circle / mean edge)");
  cmd->add_option("--fairness-order", args->options.fairness_order,
                  "2: second differences, 3: third differences")
      ->check(CLI::IsMember({2, 3}))
      ->capture_default_str();
  cmd->add_option("--soft-decay", args->options.soft_weight_decay,
                  "Closeness and fairness weights are multiplied by this each iteration ...")
      ->check(CLI::Range(1e-12, 1.0))
      ->capture_default_str();
  cmd->add_option("--soft-floor", args->options.soft_weight_floor,
                  "... down to this fraction of their initial value")
      ->check(CLI::Range(0.0, 1.0))
      ->capture_default_str();
  cmd->add_option("--epsilon", args->options.epsilon,
                  "epsilon: weight of the proximal term eps^2 |x - x^k|^2")
      ->check(CLI::PositiveNumber)
      ->capture_default_str();
  cmd->add_option("--ceres-soft-scale", args->options.ceres_soft_scale,
                  "With --solver ceres: fixed factor on the closeness and fairness weights "
                  "(0: tolerance / 100)")
      ->check(CLI::NonNegativeNumber)
      ->capture_default_str();
  cmd->add_option("--linear-solver", args->linear_solver,
                  "Sparse Cholesky backend for gp: cholmod (supernodal) or eigen")
      ->check(CLI::IsMember({"cholmod", "eigen"}))
      ->capture_default_str();
  cmd->add_option("--threads", args->options.num_threads,
                  "Threads for BLAS / Ceres (0: library default)")
      ->check(CLI::Range(0, 256))
      ->capture_default_str();
  cmd->callback([args, exit_code]() { *exit_code = RunPlanarize(*args); });
}

}  // namespace gproj
