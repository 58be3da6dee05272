// `gproj marionette`: planar-quad meshes over a fixed plan view (002).
#include <chrono>
#include <cmath>
#include <cstdio>
#include <fstream>
#include <iostream>
#include <memory>
#include <nlohmann/json.hpp>
#include <sstream>
#include <string>
#include <vector>

#include "apps/commands.h"
#include "constraints/marionette_planarity.h"
#include "geometry/mesh_io.h"
#include "geometry/quad_grid.h"
#include "problems/marionette.h"
#include "problems/marionette_mesh.h"
#include "problems/pq_planarization.h"

namespace gproj {
namespace {

struct MarionetteArgs {
  std::string plan, output, fit, report, solver = "direct";
  std::vector<double> row, column;
  std::string guides, projection = "vertical", closed_strip;
  std::vector<double> axis = {0, 0, 0, 0, 0, 1}, centre = {0, 0, 0};
  int max_iterations = 50;
  double tolerance = 1e-9;
  double outer_height = 0.0;
};

double SecondsSince(std::chrono::steady_clock::time_point t) {
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - t).count();
}

// Non-empty, non-comment lines of a text file with their 1-based numbers, split into words.
std::vector<std::pair<int, std::vector<std::string>>> ReadWords(const std::string& path) {
  std::ifstream in(path);
  if (!in) throw InputError(path + ": cannot open the file");
  std::vector<std::pair<int, std::vector<std::string>>> lines;
  int number = 0;
  for (std::string line; std::getline(in, line);) {
    ++number;
    const size_t hash = line.find('#');
    if (hash != std::string::npos) line.resize(hash);
    std::istringstream words(line);
    std::vector<std::string> w;
    for (std::string word; words >> word;) w.push_back(word);
    if (!w.empty()) lines.emplace_back(number, std::move(w));
  }
  if (in.bad()) throw InputError(path + ": read error");
  if (lines.empty()) throw InputError(path + ": the file is empty");
  return lines;
}

double ParseNumber(const std::string& word, const std::string& where) {
  size_t used = 0;
  double value = 0.0;
  try {
    value = std::stod(word, &used);
  } catch (const std::exception&) {
    used = 0;
  }
  if (used != word.size()) throw InputError(where + ": '" + word + "' is not a number");
  if (!std::isfinite(value)) throw InputError(where + ": '" + word + "' is not finite");
  return value;
}

int ParseVertex(const std::string& word, const std::string& where, int num_vertices) {
  const double v = ParseNumber(word, where);
  if (v != std::floor(v) || v < 0 || v >= num_vertices)
    throw InputError(where + ": '" + word + "' is not a vertex id (0-based, the plan has " +
                     std::to_string(num_vertices) + " vertices)");
  return static_cast<int>(v);
}

// The --guides file: "guide START NEXT V0 V1 ..." (values on the straight polyline from START
// through its neighbour NEXT) and "vertex ID VALUE" lines; '#' starts a comment.
void ReadGuides(const std::string& path, int num_vertices, std::vector<MarionetteGuide>* guides,
                std::vector<MarionetteTarget>* single) {
  for (const auto& [number, w] : ReadWords(path)) {
    const std::string where = path + ":" + std::to_string(number);
    if (w[0] == "guide" && w.size() >= 5) {
      MarionetteGuide g;
      g.where = where;
      g.start = ParseVertex(w[1], where, num_vertices);
      g.next = ParseVertex(w[2], where, num_vertices);
      for (size_t k = 3; k < w.size(); ++k) g.values.push_back(ParseNumber(w[k], where));
      guides->push_back(std::move(g));
    } else if (w[0] == "vertex" && w.size() == 3) {
      single->push_back({ParseVertex(w[1], where, num_vertices), ParseNumber(w[2], where)});
    } else {
      throw InputError(where +
                       ": expected 'guide START NEXT VALUE VALUE ...' (two values at least) or "
                       "'vertex ID VALUE'");
    }
  }
}

// Plan (a quad mesh of any connectivity) + guides → lift on the lines of the projection.
// Writes the mesh and the optional report atomically; on failure prints the one-line error.
bool WriteMeshAndReport(const PolyMesh& mesh, const MarionetteArgs& args,
                        const nlohmann::json& report) {
  try {
    WriteMeshAtomically(mesh, args.output);
    if (!args.report.empty()) WriteTextFileAtomically(args.report, report.dump(2) + "\n");
    return true;
  } catch (const InputError& e) {
    std::cerr << "gproj marionette: " << e.what() << "\n";
    return false;
  }
}

// Every output path, before any work.
void CheckMarionetteOutputs(const MarionetteArgs& args) {
  CheckMeshOutputPath("--output", args.output);
  CheckOutputPath("--report", args.report);
}

// The projection of the plan's vertices (--projection, --axis, --centre).
MarionetteProjectionOptions ProjectionFromArgs(const MarionetteArgs& args) {
  MarionetteProjectionOptions projection;
  if (!ParseMarionetteProjection(args.projection, &projection.type))
    throw InputError("--projection must be vertical, cylindrical or central, not '" +
                     args.projection + "'");
  if (args.axis.size() != 6)
    throw InputError("--axis needs six numbers px,py,pz,dx,dy,dz, got " +
                     std::to_string(args.axis.size()));
  if (args.centre.size() != 3)
    throw InputError("--centre needs three numbers x,y,z, got " +
                     std::to_string(args.centre.size()));
  projection.axis_point = Eigen::Vector3d(args.axis[0], args.axis[1], args.axis[2]);
  projection.axis_direction = Eigen::Vector3d(args.axis[3], args.axis[4], args.axis[5]);
  projection.centre = Eigen::Vector3d(args.centre[0], args.centre[1], args.centre[2]);
  return projection;
}

// The guide values: from --guides, or --row and --column on a grid plan.
std::vector<MarionetteTarget> GuidesFromArgs(const MarionetteArgs& args, const PolyMesh& mesh,
                                             const MarionetteLines& lines) {
  std::vector<MarionetteGuide> guides;
  std::vector<MarionetteTarget> single;
  if (!args.guides.empty()) {
    if (!args.row.empty() || !args.column.empty())
      throw InputError("give either --guides or --row/--column, not both");
    ReadGuides(args.guides, lines.num_vertices(), &guides, &single);
  } else if (!args.row.empty() && !args.column.empty()) {
    const GridShape shape = DetectGridShape(mesh, args.plan);
    const int rows = shape.rows, cols = shape.cols;
    if (static_cast<int>(args.row.size()) != cols + 1 ||
        static_cast<int>(args.column.size()) != rows + 1)
      throw InputError("guide curves need " + std::to_string(cols + 1) + " row values and " +
                       std::to_string(rows + 1) + " column values, got " +
                       std::to_string(args.row.size()) + " and " +
                       std::to_string(args.column.size()));
    for (int j = 0; j <= cols; ++j) single.push_back({j, args.row[j]});
    for (int i = 0; i <= rows; ++i) single.push_back({i * (cols + 1), args.column[i]});
  } else {
    throw InputError("give the guides (--guides FILE, or --row and --column on a grid plan)");
  }
  return ResolveMarionetteGuides(mesh, guides, single);
}

// The report of a lift (the run's own keys — converged, termination, iterations, seconds,
// history — are added by the caller).
nlohmann::json LiftReport(const MarionetteArgs& args, const MarionetteLines& lines,
                          const MarionettePatchLayout& layout, const MarionetteMeshLift& lift,
                          size_t guide_values, const PlanarityMeasures& m, double max_det) {
  nlohmann::json patches = nlohmann::json::array();
  for (const MarionettePatch& p : layout.patches)
    patches.push_back(
        {{"faces", p.faces.size()}, {"rows", p.rows}, {"cols", p.cols}, {"corners", p.corners}});
  return {{"command", "marionette"},
          {"input", args.plan},
          {"guides", args.guides},
          {"output", args.output},
          {"projection", args.projection},
          {"solver", args.solver},
          {"variables", lines.num_vertices()},
          {"faces", lines.mesh.n_faces()},
          {"singular_vertices", layout.singular_vertices},
          {"patches", patches},
          {"patch_order", lift.patch_order},
          {"strips_of_patches", layout.patch_strips.size()},
          {"face_strips", layout.num_face_strips},
          {"design_dimension", layout.design_dimension()},
          {"guide_values", guide_values},
          {"redundant_faces", lift.redundant_faces},
          {"over_determined_patches", lift.over_determined_patches},
          {"final",
           {{"max_planarity", m.max_planarity},
            {"mean_planarity", m.mean_planarity},
            {"max_relative_det", max_det}}}};
}

// Prints one guided-projection iteration of a lift and returns it as JSON.
nlohmann::json LogLiftIteration(const IterationRecord& r) {
  const double seconds = r.assembly_seconds + r.factorization_seconds + r.solve_seconds;
  std::printf("%5d %13.6e %13.3e %11.3e %10.4f\n", r.iteration, r.energy, r.max_constraint,
              r.step_norm, seconds);
  std::fflush(stdout);
  return {{"iteration", r.iteration},
          {"energy", r.energy},
          {"max_residual", r.max_constraint},
          {"step", r.step_norm},
          {"seconds", seconds}};
}

// The lift by guided projection (--solver gp), logged; returns an exit code (0 when it ran).
int LiftByGuidedProjection(const MarionetteArgs& args, const MarionetteLines& lines,
                           const std::vector<MarionetteTarget>& prescribed, Eigen::VectorXd* t,
                           int* iterations, std::string* termination, bool* converged,
                           nlohmann::json* history) {
  std::printf("%5s %13s %13s %11s %10s\n", "iter", "energy", "max_residual", "step", "time_s");
  MarionetteMeshSolve solve;
  try {
    solve = SolveMarionetteMesh(lines, prescribed, args.max_iterations, args.tolerance,
                                [&](const IterationRecord& r, const Eigen::VectorXd&) {
                                  history->push_back(LogLiftIteration(r));
                                  return CallbackResult::kContinue;
                                });
  } catch (const InputError& e) {
    std::cerr << "gproj marionette: " << args.plan << ": " << e.what() << "\n";
    return kExitInputError;
  }
  if (solve.failed) {
    std::cerr << "gproj marionette: solver failed: " << solve.summary.message
              << "; nothing written\n";
    return kExitSolverFailure;
  }
  *t = solve.t;
  *iterations = solve.summary.num_steps();
  *termination =
      std::string(TerminationTypeName(solve.summary.termination)) + ": " + solve.summary.message;
  *converged = solve.converged;
  return kExitOk;
}

int RunMarionetteMesh(const MarionetteArgs& args) {
  const auto start = std::chrono::steady_clock::now();
  MarionetteLines lines;
  MarionettePatchLayout layout;
  std::vector<MarionetteTarget> prescribed;
  MarionetteMeshLift lift;
  MarionetteProjectionOptions projection;
  try {
    CheckMarionetteOutputs(args);
    projection = ProjectionFromArgs(args);
    if (!args.fit.empty())
      throw InputError("--fit works with the vertical projection and --row/--column only");
    if (!(args.tolerance > 0.0) || args.max_iterations < 1)
      throw InputError("--tolerance must be > 0 and --max-iterations ≥ 1");
    const PolyMesh mesh = ReadMesh(args.plan, MeshRequirements{true});
    lines = MakeMarionetteLines(mesh, projection, args.plan);
    layout = DecomposeIntoPatches(mesh);
    prescribed = GuidesFromArgs(args, mesh, lines);
    std::printf(
        "gproj marionette: %s: %d vertices, %zu quads, %s projection\n"
        "patches: %zu singular vertices, %zu separatrices, %zu patches, %zu strips of patches "
        "(%d face strips, %d closed): a lift needs %d guide values, the guides give %zu\n",
        args.plan.c_str(), lines.num_vertices(), mesh.n_faces(), args.projection.c_str(),
        layout.singular_vertices.size(), layout.separatrices.size(), layout.patches.size(),
        layout.patch_strips.size(), layout.num_face_strips, layout.num_closed_face_strips,
        layout.design_dimension(), prescribed.size());
    // The propagation also validates the guides for the solver path.
    lift = LiftMarionetteMesh(lines, layout, prescribed);
  } catch (const InputError& e) {
    std::cerr << "gproj marionette: " << e.what() << "\n";
    return kExitInputError;
  }
  if (!lift.redundant_faces.empty())
    std::printf("note: the guides over-determine %zu faces (patches %s...) but agree with them\n",
                lift.redundant_faces.size(),
                std::to_string(lift.over_determined_patches.front()).c_str());
  Eigen::VectorXd t = lift.t;
  bool converged = true;
  int iterations = 0;
  std::string termination = "propagation";
  nlohmann::json history = nlohmann::json::array();
  const auto t0 = std::chrono::steady_clock::now();
  if (args.solver == "gp") {
    const int code = LiftByGuidedProjection(args, lines, prescribed, &t, &iterations, &termination,
                                            &converged, &history);
    if (code != kExitOk) return code;
  }
  const double solve_seconds = SecondsSince(t0);
  const PolyMesh out = MarionetteLiftedMesh(lines, t);
  const PlanarityMeasures m = MeasurePlanarity(out, out);
  const double max_det = MaxLiftPlanarity(lines, t);
  nlohmann::json report = LiftReport(args, lines, layout, lift, prescribed.size(), m, max_det);
  report["converged"] = converged;
  report["termination"] = termination;
  report["iterations"] = iterations;
  report["seconds"] = SecondsSince(start);
  report["solve_seconds"] = solve_seconds;
  report["history"] = history;
  if (!WriteMeshAndReport(out, args, report)) return kExitInputError;
  std::printf(
      "solved in %.4f s (%s, %d iterations); max planarity %.3e (diagonal distance / mean edge), "
      "max |det| / edge lengths %.3e\nwrote %s%s%s\n",
      solve_seconds, args.solver == "gp" ? "guided projection" : "propagation", iterations,
      m.max_planarity, max_det, args.output.c_str(), args.report.empty() ? "" : " and ",
      args.report.c_str());
  if (!converged) {
    std::fprintf(stderr,
                 "gproj marionette: tolerance %.1e not reached (max |det| %.3e); the result was "
                 "written, exit code %d\n",
                 args.tolerance, max_det, kExitNotConverged);
    return kExitNotConverged;
  }
  return kExitOk;
}

// Reads a --closed-strip file ("XI YI ZI XO YO" per line: inner vertex with its height, outer
// vertex); errors name the file, line and quad.
void ReadClosedStripFile(const std::string& path, ClosedStrip* strip_out,
                         std::vector<double>* z_out) {
  ClosedStrip& strip = *strip_out;
  std::vector<double>& z = *z_out;
  std::vector<int> line_of;
  for (const auto& [number, w] : ReadWords(path)) {
    const std::string where = path + ":" + std::to_string(number);
    if (w.size() != 5)
      throw InputError(where + ": expected 5 numbers (inner x y z, outer x y), got " +
                       std::to_string(w.size()));
    double v[5];
    for (int k = 0; k < 5; ++k) v[k] = ParseNumber(w[k], where);
    strip.inner.emplace_back(v[0], v[1]);
    z.push_back(v[2]);
    strip.outer.emplace_back(v[3], v[4]);
    line_of.push_back(number);
  }
  const int n = static_cast<int>(z.size());
  if (n < 3)
    throw InputError(path + ": a closed strip needs at least 3 vertex pairs, got " +
                     std::to_string(n));
  for (int i = 0; i < n; ++i) {
    const int k = (i + 1) % n;
    double alpha, beta;
    if (!MarionettePlanarity::PlanCoefficients(strip.inner[i], strip.outer[i], strip.outer[k],
                                               strip.inner[k], &alpha, &beta))
      throw InputError(path + ":" + std::to_string(line_of[i]) + ": quad " + std::to_string(i) +
                       " (vertex pairs " + std::to_string(i) + " and " + std::to_string(k) +
                       ", lines " + std::to_string(line_of[i]) + " and " +
                       std::to_string(line_of[k]) + ") has a degenerate plan view: inner " +
                       std::to_string(i) + ", outer " + std::to_string(i) + " and inner " +
                       std::to_string(k) + " are collinear in x, y");
  }
}

// --closed-strip: "XI YI ZI XO YO" per line (inner vertex with its height, outer vertex).
int RunClosedStrip(const MarionetteArgs& args) {
  const auto start = std::chrono::steady_clock::now();
  const std::string& path = args.closed_strip;
  ClosedStrip strip;
  std::vector<double> z;
  ClosedStripLift lift;
  try {
    CheckMarionetteOutputs(args);
    if (!std::isfinite(args.outer_height)) throw InputError("--outer-height must be finite");
    ReadClosedStripFile(path, &strip, &z);
    const int n = static_cast<int>(z.size());
    lift =
        LiftClosedStrip(strip, Eigen::Map<const Eigen::VectorXd>(z.data(), n), args.outer_height);
  } catch (const InputError& e) {
    std::cerr << "gproj marionette: " << e.what() << "\n";
    return kExitInputError;
  }
  const int n = static_cast<int>(z.size());
  const PolyMesh out = ClosedStripMesh(strip, lift);
  const PlanarityMeasures m = MeasurePlanarity(out, out);
  const Eigen::VectorXd z0 = Eigen::Map<const Eigen::VectorXd>(z.data(), n);
  const double inner_change = (lift.inner_heights - z0).cwiseAbs().maxCoeff();
  std::printf("gproj marionette: closed strip %s: %d quads\n", path.c_str(), n);
  if (lift.a_is_one)
    std::printf(
        "a = %.12g (= 1 within 1e-9): the inner curve must satisfy V.Z = 0; projected onto it "
        "(moved by at most %.3e); the outer start height is free: z0* = %.6g\n",
        lift.a, inner_change, lift.outer_heights[0]);
  else
    std::printf(
        "a = %.12g (!= 1): one closing lift; inner curve kept; closing height z0* = zN* = "
        "V.Z / (1 - a) = %.12g\n",
        lift.a, lift.outer_heights[0]);
  nlohmann::json report = {
      {"command", "marionette"},
      {"closed_strip", path},
      {"output", args.output},
      {"converged", true},
      {"iterations", 0},
      {"seconds", SecondsSince(start)},
      {"quads", n},
      {"a", lift.a},
      {"a_is_one", lift.a_is_one},
      {"closing_height", lift.outer_heights[0]},
      {"v_dot_z", lift.v.dot(z0)},
      {"inner_curve_change", inner_change},
      {"final", {{"max_planarity", m.max_planarity}, {"mean_planarity", m.mean_planarity}}}};
  if (!WriteMeshAndReport(out, args, report)) return kExitInputError;
  std::printf("max planarity %.3e (diagonal distance / mean edge)\nwrote %s%s%s\n", m.max_planarity,
              args.output.c_str(), args.report.empty() ? "" : " and ", args.report.c_str());
  return kExitOk;
}

// The grid plan and, with --fit, the target heights; checks the outputs first.
void LoadGridInputs(const MarionetteArgs& args, PolyMesh* mesh, MarionettePlan* plan,
                    Eigen::VectorXd* z0) {
  CheckMarionetteOutputs(args);
  *mesh = ReadMesh(args.plan, MeshRequirements{true});
  *plan = MakeMarionettePlan(*mesh, args.plan);
  if (!args.fit.empty()) {
    const PolyMesh target = ReadMesh(args.fit);
    if (target.n_vertices() != mesh->n_vertices())
      throw InputError(args.fit + ": the target has " + std::to_string(target.n_vertices()) +
                       " vertices, the plan " + std::to_string(mesh->n_vertices()));
    z0->resize(plan->num_vertices());
    for (auto v : target.vertices()) (*z0)[v.idx()] = target.point(v)[2];
  } else if (args.row.empty() || args.column.empty()) {
    throw InputError(
        "give the guide curves (--row and --column heights, or --guides) or a target (--fit)");
  }
}

// The plan with its vertices at heights z.
PolyMesh WithHeights(const PolyMesh& plan, const Eigen::VectorXd& z) {
  PolyMesh out = plan;
  for (auto v : out.vertices()) {
    auto p = out.point(v);
    p[2] = z[v.idx()];
    out.set_point(v, p);
  }
  return out;
}

int RunMarionette(const MarionetteArgs& args) {
  if (!args.closed_strip.empty()) {
    if (!args.plan.empty()) {
      std::cerr << "gproj marionette: give either a plan or --closed-strip, not both\n";
      return kExitInputError;
    }
    return RunClosedStrip(args);
  }
  if (args.plan.empty()) {
    std::cerr << "gproj marionette: give a plan view (or --closed-strip FILE)\n";
    return kExitInputError;
  }
  if (!args.guides.empty() || args.projection != "vertical") return RunMarionetteMesh(args);
  const auto start = std::chrono::steady_clock::now();
  PolyMesh mesh;
  MarionettePlan plan;
  Eigen::VectorXd z0;
  try {
    LoadGridInputs(args, &mesh, &plan, &z0);
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
      z = args.fit.empty() ? LiftMarionette(plan, row, column) : FitMarionette(plan, z0);
    } else {
      std::string why;
      if (!SolveMarionette(plan, row, column, z0, &z, &why)) {
        std::cerr << "gproj marionette: solver failed: " << why << "; nothing written\n";
        return kExitSolverFailure;
      }
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
  const PolyMesh out = WithHeights(mesh, z);
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
  if (!WriteMeshAndReport(out, args, report)) return kExitInputError;
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
      "Marionette mesh (002): planar quads over a fixed plan view. Every vertex moves on its own "
      "line (--projection): vertically (the plan's z is ignored), perpendicular to an axis "
      "through it, or through a centre; guide values are heights, distances from the axis or "
      "distances from the centre. The plan is a regular grid in `gproj grid` order with --row / "
      "--column / --fit, or any disk-like quad mesh (singular vertices allowed, 002 §2.4) with "
      "--guides: it is split into regular patches along the separatrices, and the guides must "
      "cross every strip of patches exactly once. --closed-strip lifts a closed strip instead "
      "(002 §2.5, eq. 8). Exit codes: 0 done, 1 bad input (nothing written), 3 tolerance not "
      "reached (gp, result written), 4 numerical failure (nothing written).");
  cmd->add_option("plan", args->plan,
                  "Plan view: quad mesh (.obj/.off/.ply); vertex ids below are 0-based in file "
                  "order");
  cmd->add_option("-o,--output", args->output, "Lifted mesh to write (atomically)")->required();
  cmd->add_option("--row", args->row,
                  "Guide values of vertices (0, j), j = 0..cols of a grid plan (comma separated)")
      ->delimiter(',');
  cmd->add_option("--column", args->column,
                  "Guide values of vertices (i, 0), i = 0..rows; its first value must equal "
                  "--row's")
      ->delimiter(',');
  cmd->add_option("--guides", args->guides,
                  "Guide file for a plan of any connectivity, one entry a line ('#' comments): "
                  "'guide START NEXT V0 V1 ...' gives values to the straight mesh polyline from "
                  "vertex START through its neighbour NEXT (on through inner vertices of even "
                  "valence), one per polyline vertex; 'vertex ID VALUE' gives one vertex. Errors "
                  "name the file line");
  cmd->add_option("--projection", args->projection,
                  "Lines of the vertices: vertical (values = heights), cylindrical (through the "
                  "plan vertex, perpendicular to --axis; values = distances from the axis) or "
                  "central (through --centre and the plan vertex; values = distances from it)")
      ->capture_default_str();
  cmd->add_option("--axis", args->axis, "Cylindrical axis: point and direction px,py,pz,dx,dy,dz")
      ->delimiter(',')
      ->capture_default_str();
  cmd->add_option("--centre", args->centre, "Centre of the central projection x,y,z")
      ->delimiter(',')
      ->capture_default_str();
  cmd->add_option("--fit", args->fit,
                  "Target mesh with the plan's vertex order: least-squares fit of its heights "
                  "(002 eq. 14) instead of guide curves (vertical grid plans)");
  cmd->add_option("--solver", args->solver,
                  "direct: propagation (linear time) / normal equations of the fit; gp: guided "
                  "projection (one iteration when vertical, several for other projections; the "
                  "guides are first checked by propagation)")
      ->check(CLI::IsMember({"direct", "gp"}))
      ->capture_default_str();
  cmd->add_option("--max-iterations", args->max_iterations,
                  "gp with a non-vertical projection: iterations at most")
      ->capture_default_str();
  cmd->add_option("--tolerance", args->tolerance,
                  "gp with --guides or a projection: max |det(p1-p0, p2-p0, p3-p0)| / (edge "
                  "lengths) and guide error to reach, else exit code 3")
      ->capture_default_str();
  cmd->add_option("--closed-strip", args->closed_strip,
                  "Closed strip file instead of a plan (002 §2.5): one line per vertex pair "
                  "'XI YI ZI XO YO' (inner vertex with its prescribed height, outer vertex), "
                  "quads (inner i, outer i, outer i+1, inner i+1) closing back to the first pair. "
                  "Reports a of eq. 8: a != 1 gives the one closing outer height; a = 1 projects "
                  "the inner heights onto V.Z = 0");
  cmd->add_option("--outer-height", args->outer_height,
                  "--closed-strip with a = 1: height of the first outer vertex (free)")
      ->capture_default_str();
  cmd->add_option("--report", args->report, "Write a JSON report");
  cmd->callback([args, exit_code]() { *exit_code = RunMarionette(*args); });
}

}  // namespace gproj
