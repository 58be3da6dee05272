// `gproj combescure`, `gproj invert` and `gproj canal`: circular meshes by construction (000).
#include <chrono>
#include <cstdio>
#include <fstream>
#include <iostream>
#include <memory>
#include <nlohmann/json.hpp>
#include <sstream>
#include <string>
#include <vector>

#include "apps/commands.h"
#include "geometry/circle.h"
#include "geometry/mesh_io.h"
#include "geometry/mobius.h"
#include "geometry/quad_grid.h"
#include "geometry/svg_render.h"
#include "problems/canal_surface.h"
#include "problems/combescure.h"
#include "problems/pq_planarization.h"

namespace gproj {
namespace {

double SecondsSince(std::chrono::steady_clock::time_point start) {
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
}

Eigen::Vector3d Vector3(const std::vector<double>& v, const std::string& option) {
  if (v.size() != 3)
    throw InputError(option + " needs three comma-separated numbers, got " +
                     std::to_string(v.size()));
  const Eigen::Vector3d p(v[0], v[1], v[2]);
  if (!p.allFinite()) throw InputError(option + " must be finite");
  return p;
}

// The measures every circular-mesh command reports.
nlohmann::json MeshMeasures(const PolyMesh& mesh) {
  const PlanarityMeasures p = MeasurePlanarity(mesh, mesh);
  const CircularityMeasures c = MeasureCircularity(mesh);
  return {{"max_planarity", p.max_planarity},
          {"mean_planarity", p.mean_planarity},
          {"max_concyclicity", c.max_concyclicity},
          {"mean_concyclicity", c.mean_concyclicity},
          {"worst_concyclic_face", c.worst_face}};
}

void PrintMeasures(const char* label, const nlohmann::json& m) {
  std::printf(
      "%s: max planarity %.3e, max concyclicity %.3e (diagonal distance and distance to "
      "the fitted circle, per mean edge)\n",
      label, m["max_planarity"].get<double>(), m["max_concyclicity"].get<double>());
}

// Writes the mesh, an optional picture and an optional report; all atomically.
void WriteOutputs(const PolyMesh& mesh, const std::string& output, const std::string& picture,
                  const std::string& title, const std::string& report_path,
                  const nlohmann::json& report) {
  WriteMeshAtomically(mesh, output);
  if (!picture.empty()) {
    SvgOptions svg;
    svg.title = title;
    WriteTextFileAtomically(picture, RenderMeshSvg(mesh, svg));
  }
  if (!report_path.empty()) WriteTextFileAtomically(report_path, report.dump(2) + "\n");
  std::printf("wrote %s", output.c_str());
  if (!picture.empty()) std::printf(", %s", picture.c_str());
  if (!report_path.empty()) std::printf(", %s", report_path.c_str());
  std::printf("\n");
}

// ---------------------------------------------------------------------------------------------
struct CombescureArgs {
  std::string input, output, report, picture, method = "propagation";
  std::vector<double> row, column, origin;
  double row_scale = 1.0, column_scale = 1.0, tolerance = 1e-6;
};

// Every output path of a mesh-producing command, before any work.
void CheckMeshCommandOutputs(const std::string& output, const std::string& report,
                             const std::string& picture) {
  CheckMeshOutputPath("--output", output);
  CheckOutputPath("--report", report);
  CheckOutputPath("--picture", picture);
}

int RunCombescure(const CombescureArgs& args) {
  const auto start = std::chrono::steady_clock::now();
  try {
    CheckMeshCommandOutputs(args.output, args.report, args.picture);
    const PolyMesh reference = ReadMesh(args.input, MeshRequirements{true});
    const GridShape shape = DetectGridShape(reference, args.input);
    CombescureLengths lengths = ReferenceLengths(reference, shape);
    for (double& l : lengths.row) l *= args.row_scale;
    for (double& l : lengths.column) l *= args.column_scale;
    if (!args.row.empty()) lengths.row = args.row;
    if (!args.column.empty()) lengths.column = args.column;
    if (!args.origin.empty()) lengths.origin = Vector3(args.origin, "--origin");
    CheckCombescureInput(reference, shape, lengths, args.tolerance);
    const nlohmann::json before = MeshMeasures(reference);
    std::printf("gproj combescure: %s: %d x %d faces; %s\n", args.input.c_str(), shape.rows,
                shape.cols,
                args.method == "gp" ? "guided projection with edge-parallelism rows"
                                    : "propagation (000 eq. 4)");
    PrintMeasures("reference", before);
    PolyMesh out;
    nlohmann::json solver = {{"method", args.method}};
    const auto t = std::chrono::steady_clock::now();
    if (args.method == "gp") {
      Problem problem = MakeCombescureProblem(reference, shape, lengths);
      const SolverSummary s = Solve(CombescureSolverOptions(), &problem);
      std::printf("%s\n", s.BriefReport().c_str());
      if (!s.usable || !problem.x().allFinite()) {
        std::cerr << "gproj combescure: solver failed: " << s.message << "; nothing written\n";
        return kExitSolverFailure;
      }
      out = CombescureResult(reference, problem);
      solver["iterations"] = s.num_steps();
      solver["converged"] = s.converged();
      solver["variables"] = s.num_variables;
    } else {
      out = CombescureByPropagation(reference, shape, lengths, args.tolerance);
      solver["iterations"] = 0;
      solver["converged"] = true;
    }
    const double solve_seconds = SecondsSince(t);
    const ParallelismMeasures par = MeasureParallelism(reference, out);
    nlohmann::json after = MeshMeasures(out);
    after["max_edge_parallelism_angle"] = par.max_angle;
    after["worst_parallel_edge"] = par.worst_edge;
    after["min_edge_length_ratio"] = par.min_length_ratio;
    const bool converged = solver["converged"].get<bool>() && par.max_angle <= 1e-8;
    nlohmann::json report = {{"command", "combescure"},
                             {"input", args.input},
                             {"output", args.output},
                             {"converged", converged},
                             {"iterations", solver["iterations"]},
                             {"seconds", SecondsSince(start)},
                             {"solve_seconds", solve_seconds},
                             {"solver", solver},
                             {"row_lengths", lengths.row},
                             {"column_lengths", lengths.column},
                             {"reference", before},
                             {"final", after}};
    std::printf("solved in %.4f s; max edge-parallelism angle %.3e rad\n", solve_seconds,
                par.max_angle);
    PrintMeasures("result", after);
    if (par.min_length_ratio <= 0.0)
      std::printf(
          "note: some edges are reversed (min length ratio %.3g): the parallel mesh "
          "folds over\n",
          par.min_length_ratio);
    char title[160];
    std::snprintf(title, sizeof(title), "Combescure transform, max edge angle %.1e rad",
                  par.max_angle);
    WriteOutputs(out, args.output, args.picture, title, args.report, report);
    return converged ? kExitOk : kExitNotConverged;
  } catch (const InputError& e) {
    std::cerr << "gproj combescure: " << e.what() << "\n";
    return kExitInputError;
  }
}

// ---------------------------------------------------------------------------------------------
struct InvertArgs {
  std::string input, output, report, picture;
  std::vector<double> centre, m_revolution;
  double ratio = 1.0, t = 1.0;
  int root = 0;
};

int RunInvert(const InvertArgs& args) {
  const auto start = std::chrono::steady_clock::now();
  try {
    CheckMeshCommandOutputs(args.output, args.report, args.picture);
    const PolyMesh mesh = ReadMesh(args.input);
    nlohmann::json report = {{"command", "invert"}, {"input", args.input}, {"output", args.output}};
    Eigen::Vector3d centre;
    if (!args.m_revolution.empty()) {
      if (!args.centre.empty())
        throw InputError("give either --centre or --m-revolution, not both");
      if (args.m_revolution.size() != 12)
        throw InputError("--m-revolution needs the 12 coordinates of P1, P2, P3, P4, got " +
                         std::to_string(args.m_revolution.size()));
      std::array<Eigen::Vector3d, 4> quad;
      for (int j = 0; j < 4; ++j)
        quad[j] =
            Vector3({args.m_revolution.begin() + 3 * j, args.m_revolution.begin() + 3 * j + 3},
                    "--m-revolution point P" + std::to_string(j + 1));
      const std::vector<Eigen::Vector3d> centres = MRevolutionCentres(quad, args.t);
      if (args.root >= static_cast<int>(centres.size()))
        throw InputError("--root " + std::to_string(args.root) +
                         " asked, but t = " + std::to_string(args.t) + " gives " +
                         std::to_string(centres.size()) + " centre(s) off the circle");
      centre = centres[args.root];
      nlohmann::json list = nlohmann::json::array();
      for (const auto& c : centres) list.push_back({c.x(), c.y(), c.z()});
      std::array<Eigen::Vector3d, 4> image;
      for (int j = 0; j < 4; ++j) image[j] = Invert(quad[j], centre, args.ratio);
      const Eigen::Vector3d a = image[1] - image[0], b = image[2] - image[3];
      const double angle = std::atan2(a.cross(b).norm(), std::abs(a.dot(b)));
      report["m_revolution"] = {
          {"t", args.t},
          {"centres", list},
          {"root", args.root},
          {"image_side_angle", angle},
          {"image_diagonals", {(image[2] - image[0]).norm(), (image[3] - image[1]).norm()}}};
      std::printf(
          "M-revolution (000 §5.1), t = %g: %zu centre(s); using %d: (%.6g, %.6g, %.6g); "
          "image sides P1'P2', P4'P3' at %.2e rad, diagonals %.6g and %.6g\n",
          args.t, centres.size(), args.root, centre.x(), centre.y(), centre.z(), angle,
          (image[2] - image[0]).norm(), (image[3] - image[1]).norm());
    } else {
      centre = Vector3(args.centre, "--centre");
    }
    const nlohmann::json before = MeshMeasures(mesh);
    std::printf("gproj invert: %s: %zu vertices, %zu faces; centre (%.6g, %.6g, %.6g), ratio %g\n",
                args.input.c_str(), mesh.n_vertices(), mesh.n_faces(), centre.x(), centre.y(),
                centre.z(), args.ratio);
    PrintMeasures("input", before);
    const PolyMesh out = InvertMesh(mesh, centre, args.ratio);
    const nlohmann::json after = MeshMeasures(out);
    PrintMeasures("inverted", after);
    report["centre"] = {centre.x(), centre.y(), centre.z()};
    report["ratio"] = args.ratio;
    report["converged"] = true;
    report["iterations"] = 0;
    report["seconds"] = SecondsSince(start);
    report["input_measures"] = before;
    report["final"] = after;
    WriteOutputs(out, args.output, args.picture, "Inversion (Möbius transformation)", args.report,
                 report);
    return kExitOk;
  } catch (const InputError& e) {
    std::cerr << "gproj invert: " << e.what() << "\n";
    return kExitInputError;
  }
}

// ---------------------------------------------------------------------------------------------
struct CanalArgs {
  std::string curve, output, strip, report, picture;
  std::vector<double> first_point, lengths, normal;
  double length = 0.0, psi = 0.0;
  int segments = 12, max_iterations = 200;
  bool smooth = false;
  CanalSmoothingOptions smoothing;
};

// Points, one per line: three numbers separated by spaces or commas; '#' starts a comment.
std::vector<Eigen::Vector3d> ReadCurve(const std::string& path) {
  std::ifstream in(path);
  if (!in) throw InputError(path + ": cannot open the curve file");
  std::vector<Eigen::Vector3d> points;
  std::string line;
  for (int number = 1; std::getline(in, line); ++number) {
    line = line.substr(0, line.find('#'));
    for (char& c : line)
      if (c == ',') c = ' ';
    std::istringstream fields(line);
    std::vector<double> values;
    std::string token;
    while (fields >> token) {
      try {
        size_t used = 0;
        values.push_back(std::stod(token, &used));
        if (used != token.size()) throw std::invalid_argument(token);
      } catch (const std::exception&) {
        throw InputError(path + ":" + std::to_string(number) + ": '" + token + "' is not a number");
      }
    }
    if (values.empty()) continue;
    if (values.size() != 3)
      throw InputError(path + ":" + std::to_string(number) + ": a point needs 3 coordinates, got " +
                       std::to_string(values.size()));
    const Eigen::Vector3d p(values[0], values[1], values[2]);
    if (!p.allFinite())
      throw InputError(path + ":" + std::to_string(number) + ": coordinates must be finite");
    if (!points.empty() && (p - points.back()).norm() == 0.0)
      throw InputError(path + ":" + std::to_string(number) + ": repeats the previous point");
    points.push_back(p);
  }
  if (points.size() < 2)
    throw InputError(path + ": the curve needs at least two points, got " +
                     std::to_string(points.size()));
  return points;
}

// The strip's input from the options (curve, first point, lengths); checks the output paths.
CircularStripInput CanalInputFromArgs(const CanalArgs& args) {
  CheckMeshCommandOutputs(args.output, args.report, args.picture);
  CheckMeshOutputPath("--strip", args.strip);
  CircularStripInput input;
  input.curve = ReadCurve(args.curve);
  input.first_point = Vector3(args.first_point, "--first-point");
  const size_t n = input.curve.size();
  if (!args.lengths.empty()) {
    if (args.length > 0.0) throw InputError("give either --lengths or --length, not both");
    input.lengths = args.lengths;
  } else if (args.length > 0.0) {
    input.lengths.assign(n, args.length);
  } else {
    throw InputError(
        "give the lengths across the strip (--lengths, one per curve point, or "
        "--length for all)");
  }
  if (input.lengths.size() != n)
    throw InputError("--lengths needs one value per curve point (" + std::to_string(n) + "), got " +
                     std::to_string(input.lengths.size()));
  if (args.segments < 1 || args.segments > 100000)
    throw InputError("--segments must be in [1, 100000]");
  return input;
}

// Shape smoothing (000 eq. 5) by Ceres' line-search BFGS, logged; updates the lengths and
// angles and returns the smoothing's report, with the history in *history.
nlohmann::json SmoothStrip(const CanalArgs& args, const CircularStripInput& input,
                           double initial_energy, CircularStripInput* final_input,
                           FrameAngles* angles, bool* converged, int* iterations,
                           nlohmann::json* history) {
  CanalSmoothingOptions options = args.smoothing;
  options.max_iterations = args.max_iterations;
  std::printf(
      "shape smoothing (000 eq. 5) with Ceres line-search BFGS; F = sum of 1/R^2 over "
      "the strip's arcs, start %.6g\n%5s %14s\n",
      initial_energy, "iter", "objective");
  const CanalSmoothingSummary s =
      SmoothCanalStrip(input, *angles, options, [&](int iteration, double cost) {
        std::printf("%5d %14.6e\n", iteration, cost);
        history->push_back({{"iteration", iteration}, {"objective", cost}});
      });
  std::printf("%s\nF: %.6g -> %.6g\n", s.message.c_str(), s.initial_energy, s.final_energy);
  final_input->lengths = s.lengths;
  *angles = s.angles;
  *converged = s.converged;
  *iterations = s.iterations;
  return {{"message", s.message},
          {"initial_energy", s.initial_energy},
          {"final_energy", s.final_energy},
          {"length_weight", options.length_weight}};
}

int RunCanal(const CanalArgs& args) {
  const auto start = std::chrono::steady_clock::now();
  try {
    const CircularStripInput input = CanalInputFromArgs(args);
    const size_t n = input.curve.size();
    const CircularStrip initial = BuildCircularStrip(input);
    // Default normal: in the first quad's plane, across the curve (towards Q_0), so that the
    // crossing arcs leave the strip's plane.
    const Eigen::Vector3d along = (input.curve[1] - input.curve[0]).normalized();
    const Eigen::Vector3d across = initial.q[0] - input.curve[0];
    FrameAngles angles =
        AnglesFromNormal(args.normal.empty() ? Eigen::Vector3d(across - across.dot(along) * along)
                                             : Vector3(args.normal, "--normal"));
    angles.psi = args.psi;
    std::printf("gproj canal: %s: %zu curve points, %zu strip quads; first point (%g, %g, %g)\n",
                args.curve.c_str(), n, n - 1, input.first_point.x(), input.first_point.y(),
                input.first_point.z());
    nlohmann::json report = {{"command", "canal"}, {"curve", args.curve}, {"output", args.output}};
    nlohmann::json history = nlohmann::json::array();
    CircularStripInput final_input = input;
    bool converged = true;
    int iterations = 0;
    const double initial_energy = MakeCyclidicStrip(initial, angles).energy;
    if (args.smooth)
      report["smoothing"] = SmoothStrip(args, input, initial_energy, &final_input, &angles,
                                        &converged, &iterations, &history);
    const CircularStrip strip = BuildCircularStrip(final_input);
    const CyclidicStrip net = MakeCyclidicStrip(strip, angles);
    const PolyMesh mesh = MeshCanalSurface(net, args.segments);
    const PolyMesh strip_mesh = StripMesh(strip);
    const nlohmann::json strip_measures = MeshMeasures(strip_mesh);
    const nlohmann::json mesh_measures = MeshMeasures(mesh);
    PrintMeasures("strip", strip_measures);
    PrintMeasures("canal mesh", mesh_measures);
    const Eigen::Vector3d normal(std::cos(angles.lambda) * std::cos(angles.theta),
                                 std::cos(angles.lambda) * std::sin(angles.theta),
                                 std::sin(angles.lambda));
    report["converged"] = converged;
    report["iterations"] = iterations;
    report["seconds"] = SecondsSince(start);
    report["history"] = history;
    report["lengths"] = final_input.lengths;
    report["frame"] = {{"lambda", angles.lambda},
                       {"theta", angles.theta},
                       {"psi", angles.psi},
                       {"normal", {normal.x(), normal.y(), normal.z()}}};
    report["energy"] = {{"initial", initial_energy}, {"final", net.energy}};
    report["strip"] = strip_measures;
    report["final"] = mesh_measures;
    report["mesh"] = {{"rows", static_cast<int>(n) - 1}, {"segments", args.segments}};
    if (!args.strip.empty()) WriteMeshAtomically(strip_mesh, args.strip);
    char title[160];
    std::snprintf(title, sizeof(title), "Canal surface, %zu circular quads, max concyclicity %.1e",
                  mesh.n_faces(), mesh_measures["max_concyclicity"].get<double>());
    WriteOutputs(mesh, args.output, args.picture, title, args.report, report);
    if (!args.strip.empty()) std::printf("wrote the strip to %s\n", args.strip.c_str());
    if (!converged) {
      std::fprintf(stderr,
                   "gproj canal: the smoothing stopped before converging; the result was written, "
                   "exit code %d\n",
                   kExitNotConverged);
      return kExitNotConverged;
    }
    return kExitOk;
  } catch (const InputError& e) {
    std::cerr << "gproj canal: " << e.what() << "\n";
    return kExitInputError;
  }
}

void RegisterCombescureCommand(CLI::App* app, int* exit_code) {
  auto args = std::make_shared<CombescureArgs>();
  CLI::App* cmd = app->add_subcommand(
      "combescure",
      "Combescure transformation (000 §2.4-2.5): a mesh with every edge parallel to a planar "
      "quad grid's (in `gproj grid` vertex order), from the edge lengths along row 0 and "
      "column 0. Circular meshes stay circular. Exit codes as for planarize.");
  cmd->add_option("reference", args->input, "Reference grid with planar quads")->required();
  cmd->add_option("-o,--output", args->output, "Parallel mesh to write")->required();
  cmd->add_option("--row-lengths", args->row,
                  "Signed lengths of edges (0, j) -> (0, j+1) (comma separated; default: the "
                  "reference's times --row-scale)")
      ->delimiter(',');
  cmd->add_option("--column-lengths", args->column,
                  "Signed lengths of edges (i, 0) -> (i+1, 0) (default: the reference's times "
                  "--column-scale)")
      ->delimiter(',');
  cmd->add_option("--row-scale", args->row_scale, "Scale of the reference's row lengths")
      ->capture_default_str();
  cmd->add_option("--column-scale", args->column_scale, "Scale of the reference's column lengths")
      ->capture_default_str();
  cmd->add_option("--origin", args->origin, "Position of vertex (0, 0) (default: unchanged)")
      ->delimiter(',');
  cmd->add_option("--method", args->method,
                  "propagation (linear time) or gp (guided projection, edge-parallelism rows)")
      ->check(CLI::IsMember({"propagation", "gp"}))
      ->capture_default_str();
  cmd->add_option("--tolerance", args->tolerance,
                  "Largest reference planarity accepted (diagonal distance / mean edge)")
      ->check(CLI::PositiveNumber)
      ->capture_default_str();
  cmd->add_option("--report", args->report, "Write a JSON report");
  cmd->add_option("--picture", args->picture, "Write a shaded SVG picture of the result");
  cmd->callback([args, exit_code]() { *exit_code = RunCombescure(*args); });
}

void RegisterInvertCommand(CLI::App* app, int* exit_code) {
  auto args = std::make_shared<InvertArgs>();
  CLI::App* cmd = app->add_subcommand(
      "invert",
      "Inversion (Moebius transformation, 000 eq. 1) of a mesh: CM' = k / |CM|^2 CM. "
      "Circular meshes stay circular. With --m-revolution the centre solves 000 §5.1: it maps "
      "the concyclic quad P1 P2 P3 P4 to an isosceles trapezoid with P1'P2' = t P4'P3'.");
  cmd->add_option("mesh", args->input, "Mesh to invert (.obj/.off/.ply)")->required();
  cmd->add_option("-o,--output", args->output, "Inverted mesh to write")->required();
  cmd->add_option("--centre", args->centre, "Centre of inversion x,y,z")->delimiter(',');
  cmd->add_option("--ratio", args->ratio, "Ratio k of the inversion (non-zero)")
      ->capture_default_str();
  cmd->add_option("--m-revolution", args->m_revolution,
                  "P1,P2,P3,P4 (12 comma-separated numbers): four concyclic points whose image "
                  "must be an isosceles trapezoid")
      ->delimiter(',');
  cmd->add_option("--t", args->t, "Ratio of the trapezoid's parallel sides (> 0)")
      ->capture_default_str();
  cmd->add_option("--root", args->root, "Which of the (up to) two centres to use: 0 or 1")
      ->check(CLI::Range(0, 1))
      ->capture_default_str();
  cmd->add_option("--report", args->report, "Write a JSON report");
  cmd->add_option("--picture", args->picture, "Write a shaded SVG picture of the result");
  cmd->callback([args, exit_code]() { *exit_code = RunInvert(*args); });
}

void RegisterCanalCommand(CLI::App* app, int* exit_code) {
  auto args = std::make_shared<CanalArgs>();
  CLI::App* cmd = app->add_subcommand(
      "canal",
      "Canal surface from a circular strip (000 §3.2-3.3, §4.1): points P_k on a curve, a first "
      "point fixing the first circle and the lengths |P_k Q_k| give a strip of circular quads "
      "by propagation; a frame at P_0 makes it a cyclidic net whose crossing arcs are the "
      "canal surface's circles; the surface is meshed by circular quads between them. "
      "--smooth minimises 000 eq. 5 (Ceres line-search BFGS). Exit codes as for planarize.");
  cmd->add_option("curve", args->curve,
                  "Curve points P_0..P_n: one 'x y z' per line ('#' comments)")
      ->required();
  cmd->add_option("-o,--output", args->output, "Canal mesh to write (circular quads)")->required();
  cmd->add_option("--first-point", args->first_point,
                  "x,y,z of the point that fixes the first circle (with P_0 and P_1)")
      ->delimiter(',')
      ->required();
  cmd->add_option("--lengths", args->lengths, "|P_k Q_k| for every curve point (comma separated)")
      ->delimiter(',');
  cmd->add_option("--length", args->length, "The same |P_k Q_k| for every curve point");
  cmd->add_option(
         "--normal", args->normal,
         "Normal of the cyclidic net at P_0 (default: in the first quad's plane, across the "
         "curve)")
      ->delimiter(',');
  cmd->add_option("--psi", args->psi,
                  "Rotation (radians) of the frame's first tangent about the normal")
      ->capture_default_str();
  cmd->add_option("--segments", args->segments, "Quads across the strip in the canal mesh")
      ->capture_default_str();
  cmd->add_flag("--smooth", args->smooth, "Minimise the smoothness energy of 000 eq. 5");
  cmd->add_option("--length-weight", args->smoothing.length_weight,
                  "Weight keeping the lengths near the input during --smooth")
      ->check(CLI::NonNegativeNumber)
      ->capture_default_str();
  cmd->add_flag("!--fixed-lengths", args->smoothing.optimize_lengths,
                "Keep the lengths; smooth over the frame only");
  cmd->add_option("--max-iterations", args->max_iterations, "BFGS iterations at most")
      ->check(CLI::Range(1, 100000))
      ->capture_default_str();
  cmd->add_option("--strip", args->strip, "Also write the circular strip (2 x (n+1) vertices)");
  cmd->add_option("--report", args->report, "Write a JSON report");
  cmd->add_option("--picture", args->picture, "Write a shaded SVG picture of the canal mesh");
  cmd->callback([args, exit_code]() { *exit_code = RunCanal(*args); });
}

}  // namespace

void RegisterSuperCanalCommands(CLI::App* app, int* exit_code) {
  RegisterCombescureCommand(app, exit_code);
  RegisterInvertCommand(app, exit_code);
  RegisterCanalCommand(app, exit_code);
}

}  // namespace gproj
