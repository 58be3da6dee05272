// `gproj marionette`: planar-quad meshes over a fixed plan view (002).
#include <Eigen/Dense>
#include <chrono>
#include <cstdio>
#include <iostream>
#include <memory>
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "apps/commands.h"
#include "geometry/mesh_io.h"
#include "problems/marionette.h"
#include "problems/pq_planarization.h"

namespace gproj {
namespace {

struct MarionetteArgs {
  std::string plan, output, fit, report, solver = "direct";
  std::vector<double> row, column;
};

int RunMarionette(const MarionetteArgs& args) {
  const auto start = std::chrono::steady_clock::now();
  PolyMesh mesh;
  MarionettePlan plan;
  Eigen::VectorXd z0;
  try {
    mesh = ReadMesh(args.plan, MeshRequirements{true});
    plan = MakeMarionettePlan(mesh, args.plan);
    if (!args.fit.empty()) {
      const PolyMesh target = ReadMesh(args.fit);
      if (target.n_vertices() != mesh.n_vertices())
        throw InputError(args.fit + ": the target has " + std::to_string(target.n_vertices()) +
                         " vertices, the plan " + std::to_string(mesh.n_vertices()));
      z0.resize(plan.num_vertices());
      for (auto v : target.vertices()) z0[v.idx()] = target.point(v)[2];
    } else if (args.row.empty() || args.column.empty()) {
      throw InputError("give the guide curves (--row and --column heights) or a target (--fit)");
    }
  } catch (const InputError& e) {
    std::cerr << "gproj marionette: " << e.what() << "\n";
    return kExitInputError;
  }
  std::printf("gproj marionette: %s: %d x %d faces, %d heights, %s\n", args.plan.c_str(), plan.rows,
              plan.cols, plan.num_vertices(),
              args.fit.empty() ? "lift from guide curves" : "least-squares fit to a target");
  Eigen::VectorXd z;
  const auto t = std::chrono::steady_clock::now();
  try {
    const Eigen::VectorXd row = Eigen::Map<const Eigen::VectorXd>(args.row.data(), args.row.size());
    const Eigen::VectorXd column =
        Eigen::Map<const Eigen::VectorXd>(args.column.data(), args.column.size());
    if (args.solver == "direct") {
      if (args.fit.empty()) {
        z = LiftMarionette(plan, row, column);
      } else {
        const Eigen::MatrixXd a = MarionetteGuideMatrix(plan);  // 002 eq. 14
        z = a * (a.transpose() * a).ldlt().solve(a.transpose() * z0);
      }
    } else {
      std::vector<MarionetteTarget> hard, soft;
      if (args.fit.empty()) {
        if (row.size() != plan.cols + 1 || column.size() != plan.rows + 1 ||
            std::abs(row[0] - column[0]) > 1e-12 * (1 + std::abs(row[0])))
          LiftMarionette(plan, row, column);  // throws the same message as the direct path
        for (int j = 0; j <= plan.cols; ++j) hard.push_back({plan.Vertex(0, j), row[j]});
        for (int i = 1; i <= plan.rows; ++i) hard.push_back({plan.Vertex(i, 0), column[i]});
      } else {
        for (int v = 0; v < plan.num_vertices(); ++v) soft.push_back({v, z0[v]});
      }
      Problem problem = MakeMarionetteProblem(plan, hard, soft, 1.0, 1e-8);
      const SolverSummary s = Solve(MarionetteSolverOptions(), &problem);
      if (s.termination == TerminationType::kFailure) {
        std::cerr << "gproj marionette: solver failed: " << s.message << "; nothing written\n";
        return kExitSolverFailure;
      }
      z = problem.x();
    }
  } catch (const InputError& e) {
    std::cerr << "gproj marionette: " << e.what() << "\n";
    return kExitInputError;
  }
  const double solve_seconds =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - t).count();
  if (!z.allFinite()) {
    std::cerr << "gproj marionette: non-finite heights; nothing written\n";
    return kExitSolverFailure;
  }
  PolyMesh out = mesh;
  for (auto v : out.vertices()) {
    auto p = out.point(v);
    p[2] = z[v.idx()];
    out.set_point(v, p);
  }
  const PlanarityMeasures m = MeasurePlanarity(out, out);
  const double seconds =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  nlohmann::json report = {
      {"command", "marionette"},
      {"input", args.plan},
      {"output", args.output},
      {"solver", args.solver},
      {"converged", true},
      {"iterations", args.solver == "gp" ? 1 : 0},
      {"seconds", seconds},
      {"solve_seconds", solve_seconds},
      {"variables", plan.num_vertices()},
      {"faces", plan.rows * plan.cols},
      {"final", {{"max_planarity", m.max_planarity}, {"mean_planarity", m.mean_planarity}}}};
  if (z0.size() > 0)
    report["final"]["rms_distance_to_target"] = std::sqrt((z - z0).squaredNorm() / z.size());
  try {
    WriteMeshAtomically(out, args.output);
    if (!args.report.empty()) WriteTextFileAtomically(args.report, report.dump(2) + "\n");
  } catch (const InputError& e) {
    std::cerr << "gproj marionette: " << e.what() << "\n";
    return kExitInputError;
  }
  std::printf(
      "solved in %.4f s; max planarity %.3e (diagonal distance / mean edge)\nwrote %s%s%s\n",
      solve_seconds, m.max_planarity, args.output.c_str(), args.report.empty() ? "" : " and ",
      args.report.c_str());
  return kExitOk;
}

}  // namespace

void RegisterMarionetteCommand(CLI::App* app, int* exit_code) {
  auto args = std::make_shared<MarionetteArgs>();
  CLI::App* cmd = app->add_subcommand(
      "marionette",
      "Marionette mesh: lift a fixed plan view (a regular quad grid in `gproj grid` vertex order; "
      "its z is ignored) to planar quads from two guide curves, or fit it to a target (002). "
      "Exit codes as for planarize.");
  cmd->add_option("plan", args->plan, "Plan view: quad grid (.obj/.off/.ply)")->required();
  cmd->add_option("-o,--output", args->output, "Lifted mesh to write")->required();
  cmd->add_option("--row", args->row, "Heights of vertices (0, j), j = 0..cols (comma separated)")
      ->delimiter(',');
  cmd->add_option("--column", args->column,
                  "Heights of vertices (i, 0), i = 0..rows; its first value must equal --row's")
      ->delimiter(',');
  cmd->add_option("--fit", args->fit,
                  "Target mesh with the plan's vertex order: least-squares fit of its heights "
                  "(002 eq. 14) instead of guide curves");
  cmd->add_option("--solver", args->solver,
                  "direct: propagation / normal equations; gp: one guided-projection iteration")
      ->check(CLI::IsMember({"direct", "gp"}))
      ->capture_default_str();
  cmd->add_option("--report", args->report, "Write a JSON report");
  cmd->callback([args, exit_code]() { *exit_code = RunMarionette(*args); });
}

}  // namespace gproj
