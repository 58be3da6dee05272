// `gproj marionette`: planar-quad meshes over a fixed plan view (002), on the shared run layer.
#include <cmath>
#include <cstdio>
#include <iostream>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "apps/commands.h"
#include "geometry/text_input.h"
#include "problems/marionette_run.h"

namespace gproj {

namespace {

struct MarionetteArgs {
  std::string output, report;
  MarionetteRunOptions options;
  std::vector<std::string> hold;  // --hold VERTEX:HEIGHT, ...
  std::optional<double> volume, max_height;
};

// The hard constraints of the options: "VERTEX:HEIGHT" words, the volume and the max height.
MarionetteConstraints Constraints(const MarionetteArgs& args) {
  MarionetteConstraints c;
  for (const std::string& word : args.hold) {
    const size_t colon = word.find(':');
    const std::string where = "--hold '" + word + "'";
    if (colon == std::string::npos) throw InputError(where + ": give VERTEX:HEIGHT, e.g. 12:0.5");
    const double vertex = ParseNumber(word.substr(0, colon), where);
    if (vertex != std::floor(vertex) || vertex < 0 || vertex > 2e9)
      throw InputError(where + ": the vertex must be an index >= 0");
    c.heights.push_back({static_cast<int>(vertex), ParseNumber(word.substr(colon + 1), where)});
  }
  c.with_volume = args.volume.has_value();
  c.volume = args.volume.value_or(0.0);
  c.with_max_height = args.max_height.has_value();
  c.max_height = args.max_height.value_or(0.0);
  return c;
}

// Writes the mesh (unless the run failed) and the report; false (error printed) when it cannot.
bool WriteOutputs(const MarionetteArgs& args, const MarionetteRun& run, const RunReport& report) {
  nlohmann::json extra = run.Facts();
  extra.update(
      {{"output", report.failed ? "" : args.output}, {"tolerance", args.options.lift.tolerance}});
  try {
    OutputFiles files;
    if (!report.failed) files.AddMesh(run.Result(), args.output);
    if (!report.failed && !args.report.empty())
      files.AddText(args.report, ReportJson("marionette", report, extra).dump(2) + "\n");
    files.Commit();
    return true;
  } catch (const InputError& e) {
    std::cerr << "gproj marionette: " << e.what() << "\n";
    return false;
  }
}

int RunMarionette(const MarionetteArgs& args) {
  std::unique_ptr<MarionetteRun> run;
  try {
    MarionetteRunOptions o = args.options;
    CheckOutputPaths({{"plan", o.plan},
                      {"--guides", o.guides},
                      {"--fit", o.fit},
                      {"--fit-heights", o.fit_heights},
                      {"--closed-strip", o.closed_strip}},
                     {{"--output", args.output, true}, {"--report", args.report}});
    o.constraints = Constraints(args);
    run = MakeMarionetteRun(o);
  } catch (const InputError& e) {
    std::cerr << "gproj marionette: " << e.what() << "\n";
    return kExitInputError;
  }
  std::printf("%s", run->Description().c_str());
  const IterationLog log({"max_constraint", run->ToleranceMeasure()});
  if (args.options.solver != "direct") log.PrintHeader();
  const RunReport report = run->Run([&log](const RunRecord& r) { return log.Print(r), true; });
  if (!WriteOutputs(args, *run, report)) return kExitInputError;
  std::printf("final:");
  for (const NamedValue& v : report.final) std::printf(" %s %.3e", v.name.c_str(), v.value);
  std::printf("\n");
  return ConcludeRun("marionette", report, run->ToleranceMeasure(), args.options.lift.tolerance,
                     {args.output, args.report});
}

}  // namespace

void RegisterMarionetteCommand(CLI::App* app, int* exit_code) {
  auto args = std::make_shared<MarionetteArgs>();
  CLI::App* cmd = app->add_subcommand(
      "marionette",
      "Marionette mesh (002): planar quads over a fixed plan view. Every vertex moves on its own "
      "line (--projection): vertically (the plan's z is ignored), perpendicular to an axis "
      "through it, or through a centre; guide values are heights, distances from the axis or "
      "distances from the centre. The plan is a regular grid in `gproj grid` order with --row / "
      "--column / --fit, or any disk-like quad mesh (singular vertices allowed, 002 §2.4) with "
      "--guides: it is split into regular patches along the separatrices, and the guides must "
      "cross every strip of patches exactly once. A plan of any polygons (Kagome: triangles and "
      "hexagons, 002 §4.2), or a quad plan that is no grid, is lifted vertically from --hold "
      "heights with the fairness of 002 eq. 17 fixing the rest. --closed-strip lifts a closed "
      "strip instead (002 §2.5, eq. 8). Exit codes: 0 tolerance met, 1 bad input (nothing "
      "written), 3 "
      "tolerance not reached (result written), 4 numerical failure (nothing written).");
  cmd->add_option("plan", args->options.plan,
                  "Plan view: quad mesh, or polygons with --hold (.obj/.off/.ply); vertex ids "
                  "below are 0-based in file order");
  cmd->add_option("-o,--output", args->output, "Lifted mesh to write (atomically)")->required();
  cmd->add_option("--row", args->options.row,
                  "Guide values of vertices (0, j), j = 0..cols of a grid plan (comma separated)")
      ->check(Finite())
      ->delimiter(',');
  cmd->add_option("--column", args->options.column,
                  "Guide values of vertices (i, 0), i = 0..rows; its first value must equal "
                  "--row's")
      ->check(Finite())
      ->delimiter(',');
  cmd->add_option("--guides", args->options.guides,
                  "Guide file for a plan of any connectivity, one entry a line ('#' comments): "
                  "'guide START NEXT V0 V1 ...' gives values to the straight mesh polyline from "
                  "vertex START through its neighbour NEXT (on through inner vertices of even "
                  "valence), one per polyline vertex; 'vertex ID VALUE' gives one vertex. Errors "
                  "name the file line");
  cmd->add_option("--projection", args->options.projection,
                  "Lines of the vertices: vertical (values = heights), cylindrical (through the "
                  "plan vertex, perpendicular to --axis; values = distances from the axis) or "
                  "central (through --centre and the plan vertex; values = distances from it)")
      ->capture_default_str();
  cmd->add_option("--axis", args->options.axis,
                  "Cylindrical axis: point and direction px,py,pz,dx,dy,dz")
      ->check(Finite())
      ->delimiter(',')
      ->capture_default_str();
  cmd->add_option("--centre", args->options.centre, "Centre of the central projection x,y,z")
      ->check(Finite())
      ->delimiter(',')
      ->capture_default_str();
  cmd->add_option("--fit", args->options.fit,
                  "Target mesh with the plan's vertex order: least-squares fit of its heights "
                  "(002 eq. 14) instead of guide curves (vertical grid plans)");
  cmd->add_option("--fit-heights", args->options.fit_heights,
                  "A partial target: lines 'VERTEX HEIGHT'; the least-squares fit follows only "
                  "these vertices (they must determine the lift; --solver direct)");
  cmd->add_option("--hold", args->hold,
                  "Hard constraint of a fit (002 §3.3), or the prescribed heights of a plan of "
                  "polygons (002 §4.2): VERTEX:HEIGHT, comma-separated; met exactly (KKT system, "
                  "--solver direct)")
      ->delimiter(',');
  cmd->add_option("--volume", args->volume,
                  "Hard constraint of a fit: the volume under the mesh over its plan (z = 0 as "
                  "the base), met exactly")
      ->check(Finite());
  cmd->add_option("--max-height", args->max_height,
                  "Hard constraint of a fit: no vertex above this height (active set)")
      ->check(Finite());
  cmd->add_option("--solver", args->options.solver,
                  "direct: propagation (linear time) / normal equations of the fit; gp: guided "
                  "projection (one iteration when vertical, several for other projections; the "
                  "guides are first checked by propagation); ceres: Levenberg-Marquardt on the "
                  "same rows (the cross-check)")
      ->check(CLI::IsMember({"direct", "gp", "ceres"}))
      ->capture_default_str();
  cmd->add_option("--max-iterations", args->options.lift.solver.max_iterations,
                  "gp with a non-vertical projection: iterations at most")
      ->check(Within(1, 100000))
      ->capture_default_str();
  cmd->add_option("--tolerance", args->options.lift.tolerance,
                  "Every mode: the result's planarity to reach, else exit code 3 (with --guides "
                  "or a projection: max |det(p1-p0, p2-p0, p3-p0)| / (edge lengths) and the "
                  "guide error; grid plans and closed strips: max planarity, diagonal distance "
                  "/ mean edge)")
      ->check(Positive())
      ->capture_default_str();
  cmd->add_option("--closed-strip", args->options.closed_strip,
                  "Closed strip file instead of a plan (002 §2.5): one line per vertex pair "
                  "'XI YI ZI XO YO' (inner vertex with its prescribed height, outer vertex), "
                  "quads (inner i, outer i, outer i+1, inner i+1) closing back to the first pair. "
                  "Reports a of eq. 8: a != 1 gives the one closing outer height; a = 1 projects "
                  "the inner heights onto V.Z = 0");
  cmd->add_option("--outer-height", args->options.outer_height,
                  "--closed-strip with a = 1: height of the first outer vertex (free)")
      ->check(Finite())
      ->capture_default_str();
  cmd->add_flag("--allow-folded-plan", args->options.allow_folded_plan,
                "Lift a plan view whose quads overlap or are not convex in x, y (refused by "
                "default), with a warning naming the faces");
  cmd->add_option("--report", args->report, "Write a JSON report");
  cmd->callback([args, exit_code]() { *exit_code = RunMarionette(*args); });
}

}  // namespace gproj
