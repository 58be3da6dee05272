// `gproj beams`: torsion-free node axes and beams of constant height on a circular mesh
// (000 §4.3).
#include <chrono>
#include <cstdio>
#include <filesystem>
#include <iostream>
#include <memory>
#include <string>
#include <vector>

#include "apps/super_canal_commands.h"
#include "geometry/svg_render.h"
#include "problems/circular_mesh.h"
#include "problems/torsion_free_beams.h"

namespace gproj {
namespace {

struct BeamsArgs {
  std::string input, axes, offset;
  MeshOutputs outputs;
  BeamOptions options;
  double axis_length = 0.0;    // 0: 2 h
  double gap_tolerance = 0.0;  // 0: none
};

void CheckAxesPath(const std::string& path) {
  if (path.empty()) return;
  std::string ext = std::filesystem::path(path).extension().string();
  for (char& c : ext) c = static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
  if (ext != ".obj")
    throw InputError("--axes " + path + ": the axes are written as OBJ line segments (.obj)");
}

int RunBeams(const BeamsArgs& args) {
  PolyMesh mesh;
  BeamLayout layout;
  NamedValues input_measures;
  double seconds = 0.0;
  try {
    args.outputs.Check({{"input", args.input}},
                       {{"--axes", args.axes}, {"--offset", args.offset, true}});
    CheckAxesPath(args.axes);
    mesh = ReadMesh(args.input);
    std::printf("gproj beams: %s: %zu vertices, %zu faces, %zu edges; beams of height %g\n",
                args.input.c_str(), mesh.n_vertices(), mesh.n_faces(), mesh.n_edges(),
                args.options.height);
    input_measures = MeasureCircularMesh(mesh);
    PrintMeasures("input", input_measures);
    const auto start = std::chrono::steady_clock::now();
    layout = TorsionFreeBeams(mesh, args.options);
    seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  } catch (const InputError& e) {
    std::cerr << "gproj beams: " << e.what() << "\n";
    return kExitInputError;
  }
  const NamedValues& m = layout.measures;
  std::printf(
      "node axes by mirror images across the edges from vertex %d; they close around every face "
      "to %.2e rad\n",
      layout.root, ValueOf(m, "max_closing_angle"));
  std::printf(
      "beams: max non-planarity %.2e (per mean edge); offset at distance %g: max edge angle "
      "%.2e rad, distance error %.2e\n",
      ValueOf(m, "max_beam_planarity"), args.options.height, ValueOf(m, "max_offset_angle"),
      ValueOf(m, "max_offset_distance_error"));
  std::printf(
      "height gaps at the nodes (/ h): max %.4g, mean %.4g (%s; from the face normal: "
      "max %.4g)\n",
      ValueOf(m, "max_height_gap"), ValueOf(m, "mean_height_gap"),
      args.options.optimise ? "first axis optimised" : "first axis not optimised",
      ValueOf(m, "initial_max_height_gap"));
  NamedValues initial = input_measures;
  initial.push_back({"max_height_gap", ValueOf(m, "initial_max_height_gap")});
  const bool met = args.gap_tolerance <= 0.0 || ValueOf(m, "max_height_gap") <= args.gap_tolerance;
  const RunReport report = ConstructionReport("mirror images", initial, m, met, seconds);
  if (report.failed) return ConcludeRun("beams", report, "max_height_gap", args.gap_tolerance, {});
  nlohmann::json extra = {{"input", args.input},         {"height", args.options.height},
                          {"root_vertex", layout.root},  {"optimised", args.options.optimise},
                          {"output", args.outputs.mesh}, {"axes", args.axes},
                          {"offset", args.offset}};
  if (args.gap_tolerance > 0.0) extra["gap_tolerance"] = args.gap_tolerance;
  try {
    OutputFiles files;
    files.AddMesh(layout.beams, args.outputs.mesh);
    const double length = args.axis_length > 0.0 ? args.axis_length : 2.0 * args.options.height;
    if (!args.axes.empty()) files.AddText(args.axes, AxesObj(mesh, layout.axis, length));
    if (!args.offset.empty()) files.AddMesh(layout.offset, args.offset);
    if (!args.outputs.picture.empty()) {
      SvgOptions svg;
      char title[160];
      std::snprintf(title, sizeof(title),
                    "Torsion-free beams, %zu beams, height %g, max gap %.2g h", mesh.n_edges(),
                    args.options.height, ValueOf(m, "max_height_gap"));
      svg.title = title;
      files.AddText(args.outputs.picture, RenderMeshSvg(layout.beams, svg));
    }
    if (!args.outputs.report.empty())
      files.AddText(args.outputs.report, ReportJson("beams", report, extra).dump(2) + "\n");
    files.Commit();
  } catch (const InputError& e) {
    std::cerr << "gproj beams: " << e.what() << "\n";
    return kExitInputError;
  }
  return ConcludeRun(
      "beams", report, "max_height_gap", args.gap_tolerance,
      {args.outputs.mesh, args.axes, args.offset, args.outputs.picture, args.outputs.report});
}

}  // namespace

void RegisterBeamsCommand(CLI::App* app, int* exit_code) {
  auto args = std::make_shared<BeamsArgs>();
  CLI::App* cmd = app->add_subcommand(
      "beams",
      "Torsion-free beams on a circular mesh (000 §4.3): node axes by mirror images across the "
      "edges (they close around a face inscribed in a circle), so every beam is planar and the "
      "offset mesh at constant distance is parallel; beams of constant height as solids; the "
      "first axis chosen to minimise the height gaps at the nodes. Exit codes as for "
      "planarize (3: --gap-tolerance not met).");
  cmd->add_option("mesh", args->input, "Circular mesh (every face inscribed in a circle)")
      ->required();
  cmd->add_option("-o,--output", args->outputs.mesh, "Beams to write, one box per edge")
      ->required();
  cmd->add_option("--height", args->options.height, "Beam height, and the offset distance")
      ->check(Positive())
      ->required();
  cmd->add_option("--width", args->options.width,
                  "Beam thickness across its plane (default: 4% of the mean edge)")
      ->check(Positive());
  cmd->add_option("--axes", args->axes, "Write the node axes as OBJ line segments");
  cmd->add_option("--axis-length", args->axis_length,
                  "Length of the written axes (default: twice the height)")
      ->check(Positive());
  cmd->add_option("--offset", args->offset, "Write the offset mesh (parallel, at the height)");
  cmd->add_flag("!--no-optimise", args->options.optimise,
                "Keep the first axis at the central node's mean face normal");
  cmd->add_option("--gap-tolerance", args->gap_tolerance,
                  "Largest height gap at a node (in units of the height) for exit 0")
      ->check(Positive());
  cmd->add_option("--circularity-tolerance", args->options.circularity_tolerance,
                  "Largest closing angle (rad) of the axes around a face, at most 0.01")
      ->check(Within(1e-300, 1e-2))
      ->capture_default_str();
  cmd->add_option("--report", args->outputs.report, "Write a JSON report");
  cmd->add_option("--picture", args->outputs.picture, "Write a shaded SVG picture of the beams");
  cmd->callback([args, exit_code]() { *exit_code = RunBeams(*args); });
}

}  // namespace gproj
