// `gproj combescure`: a parallel mesh of a planar quad grid (000 §2.4–2.5).
#include <cstdio>
#include <iostream>
#include <memory>
#include <string>
#include <vector>

#include "apps/super_canal_commands.h"
#include "geometry/quad_grid.h"
#include "problems/combescure.h"

namespace gproj {
namespace {

struct CombescureArgs {
  std::string input, method = "propagation";
  MeshOutputs outputs;
  std::vector<double> row, column, origin;
  double row_scale = 1.0, column_scale = 1.0;
  CombescureOptions options;
};

// The lengths of the reference scaled, or those given, and the origin.
CombescureLengths LengthsFromArgs(const CombescureArgs& args, const PolyMesh& reference,
                                  const GridShape& shape) {
  CombescureLengths lengths = ReferenceLengths(reference, shape);
  for (double& l : lengths.row) l *= args.row_scale;
  for (double& l : lengths.column) l *= args.column_scale;
  if (!args.row.empty()) lengths.row = args.row;
  if (!args.column.empty()) lengths.column = args.column;
  if (!args.origin.empty()) lengths.origin = Vector3(args.origin, "--origin");
  return lengths;
}

int RunCombescure(const CombescureArgs& args) {
  std::unique_ptr<Combescure> combescure;
  CombescureLengths lengths;
  try {
    args.outputs.Check({{"input", args.input}});
    const PolyMesh reference = ReadMesh(args.input, MeshRequirements{true});
    const GridShape shape = DetectGridShape(reference, args.input);
    lengths = LengthsFromArgs(args, reference, shape);
    combescure = std::make_unique<Combescure>(reference, shape, lengths, args.options);
    std::printf("gproj combescure: %s: %d x %d faces; %s\n", args.input.c_str(), shape.rows,
                shape.cols,
                args.method == "gp"      ? "guided projection with edge-parallelism rows"
                : args.method == "ceres" ? "Levenberg-Marquardt on the edge-parallelism rows"
                                         : "propagation (000 eq. 4)");
  } catch (const InputError& e) {
    std::cerr << "gproj combescure: " << e.what() << "\n";
    return kExitInputError;
  }
  PrintMeasures("reference", combescure->Measure());
  const RunReport report = args.method == "gp"      ? combescure->Run()
                           : args.method == "ceres" ? combescure->RunCeres(200)
                                                    : combescure->RunPropagation();
  const double angle = ValueOf(report.final, "max_edge_parallelism_angle");
  if (!report.failed) {
    std::printf("solved in %.4f s; max edge-parallelism angle %.3e rad\n", report.seconds, angle);
    PrintMeasures("result", report.final);
    const double min_ratio = ValueOf(report.final, "min_edge_length_ratio");
    if (min_ratio <= 0.0)
      std::printf(
          "note: some edges are reversed (min length ratio %.3g): the parallel mesh "
          "folds over\n",
          min_ratio);
  }
  char title[160];
  std::snprintf(title, sizeof(title), "Combescure transform, max edge angle %.1e rad", angle);
  const nlohmann::json extra = {{"input", args.input},
                                {"method", args.method},
                                {"row_lengths", lengths.row},
                                {"column_lengths", lengths.column}};
  const double tolerance =
      args.method == "propagation" ? args.options.propagation_tolerance : args.options.tolerance;
  return WriteAndConclude("combescure", report, combescure->Result(), title, args.outputs, extra,
                          "max_edge_parallelism_angle", tolerance);
}

}  // namespace

void RegisterCombescureCommand(CLI::App* app, int* exit_code) {
  auto args = std::make_shared<CombescureArgs>();
  CLI::App* cmd = app->add_subcommand(
      "combescure",
      "Combescure transformation (000 §2.4-2.5): a mesh with every edge parallel to a planar "
      "quad grid's (in `gproj grid` vertex order), from the edge lengths along row 0 and "
      "column 0. Circular meshes stay circular. Exit codes as for planarize.");
  cmd->add_option("reference", args->input, "Reference grid with planar quads")->required();
  cmd->add_option("-o,--output", args->outputs.mesh, "Parallel mesh to write")->required();
  cmd->add_option("--row-lengths", args->row,
                  "Signed lengths of edges (0, j) -> (0, j+1) (comma separated; default: the "
                  "reference's times --row-scale)")
      ->check(Finite())
      ->delimiter(',');
  cmd->add_option("--column-lengths", args->column,
                  "Signed lengths of edges (i, 0) -> (i+1, 0) (default: the reference's times "
                  "--column-scale)")
      ->check(Finite())
      ->delimiter(',');
  cmd->add_option("--row-scale", args->row_scale, "Scale of the reference's row lengths (> 0)")
      ->check(Positive())
      ->capture_default_str();
  cmd->add_option("--column-scale", args->column_scale,
                  "Scale of the reference's column lengths (> 0)")
      ->check(Positive())
      ->capture_default_str();
  cmd->add_option("--origin", args->origin, "Position of vertex (0, 0) (default: unchanged)")
      ->check(Finite())
      ->delimiter(',');
  cmd->add_option("--method", args->method,
                  "propagation (linear time), gp (guided projection, edge-parallelism rows) or "
                  "ceres (Levenberg-Marquardt on the same rows: the cross-check)")
      ->check(CLI::IsMember({"propagation", "gp", "ceres"}))
      ->capture_default_str();
  cmd->add_option("--tolerance", args->options.reference_tolerance,
                  "Largest reference planarity accepted (diagonal distance / mean edge)")
      ->check(Positive())
      ->capture_default_str();
  cmd->add_option("--report", args->outputs.report, "Write a JSON report");
  cmd->add_option("--picture", args->outputs.picture, "Write a shaded SVG picture of the result");
  cmd->callback([args, exit_code]() { *exit_code = RunCombescure(*args); });
}

}  // namespace gproj
