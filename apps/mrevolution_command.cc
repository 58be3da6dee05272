// `gproj mrevolution`: an M-revolution surface in one step (000 §5.1), from a planar curve and
// two points on the circle through its ends.
#include <chrono>
#include <cstdio>
#include <iostream>
#include <memory>
#include <string>
#include <vector>

#include "apps/super_canal_commands.h"
#include "geometry/text_input.h"
#include "problems/circular_mesh.h"
#include "problems/m_revolution.h"

namespace gproj {
namespace {

struct MRevolutionArgs {
  std::string curve, revolution;
  MeshOutputs outputs;
  std::vector<double> p2, p3, up;
  MRevolutionOptions options;
};

int RunMRevolution(const MRevolutionArgs& args) {
  MRevolutionSurface surface;
  RunReport report;
  try {
    args.outputs.Check({{"curve", args.curve}}, {{"--revolution", args.revolution, true}});
    const std::vector<Eigen::Vector3d> curve = ReadPoints(args.curve, 2);

    MRevolutionOptions options = args.options;
    if (!args.up.empty()) {
      options.up = Vector3(args.up, "--up");
      if (options.up.norm() == 0.0) throw InputError("--up must not be zero");
    }
    const auto start = std::chrono::steady_clock::now();
    surface =
        BuildMRevolutionSurface(curve, Vector3(args.p2, "--p2"), Vector3(args.p3, "--p3"), options);
    std::printf(
        "gproj mrevolution: %s: %zu points from P1 to P4, P2 and P3 on their circle; t = %g, "
        "root %d, %d segments per arch\n",
        args.curve.c_str(), curve.size(), args.options.t, args.options.root,
        args.options.arch_segments);
    NamedValues measures = MeasureCircularMesh(surface.mesh);
    measures.push_back({"curve_roundtrip", surface.curve_roundtrip});
    measures.push_back({"far_meridian_miss", surface.far_meridian_miss});
    measures.push_back({"arch_planarity", surface.arch_planarity});
    report = ConstructionReport(
        "inversion of a surface of revolution", MeasureCircularMesh(surface.revolution), measures,
        true, std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count());
  } catch (const InputError& e) {
    std::cerr << "gproj mrevolution: " << e.what() << "\n";
    return kExitInputError;
  }
  const Eigen::Vector3d& c = surface.choice.centre;
  std::printf(
      "inversion centre (%.6g, %.6g, %.6g), ratio %.6g: P1P2P3P4 maps to an isosceles trapezoid "
      "(sides at %.1e rad, diagonals %.6g and %.6g)\n",
      c.x(), c.y(), c.z(), surface.ratio, surface.choice.image.side_angle,
      surface.choice.image.diagonals[0], surface.choice.image.diagonals[1]);
  PrintMeasures("surface of revolution", report.initial);
  PrintMeasures("M-revolution surface", report.final);
  std::printf(
      "f^-1(f(curve)) against the curve %.1e, far meridian against P2, P3 %.1e, arches off their "
      "planes %.1e (curve extents)\n",
      surface.curve_roundtrip, surface.far_meridian_miss, surface.arch_planarity);
  nlohmann::json extra = {
      {"curve", args.curve}, {"t", args.options.t}, {"root", args.options.root}};
  extra["centre"] = {c.x(), c.y(), c.z()};
  extra["ratio"] = surface.ratio;
  extra["axis"] = {
      {"point", {surface.axis_point.x(), surface.axis_point.y(), surface.axis_point.z()}},
      {"direction",
       {surface.axis_direction.x(), surface.axis_direction.y(), surface.axis_direction.z()}}};
  char title[160];
  std::snprintf(title, sizeof(title), "M-revolution surface (000 §5.1), %zu circular quads",
                surface.mesh.n_faces());
  return WriteAndConclude("mrevolution", report, surface.mesh, title, args.outputs, extra, "", 0.0,
                          {{args.revolution, &surface.revolution}});
}

}  // namespace

void RegisterMRevolutionCommand(CLI::App* app, int* exit_code) {
  auto args = std::make_shared<MRevolutionArgs>();
  CLI::App* cmd = app->add_subcommand(
      "mrevolution",
      "M-revolution surface in one step (000 §5.1): the inversion centre that maps P1 P2 P3 P4 "
      "(P1, P4 the curve's ends) to an isosceles trapezoid, the surface of revolution whose "
      "meridian is the curve's image, meshed by meridians and parallels, inverted back: a "
      "circular mesh through the curve's points and P2, P3, with planar arches. Exit codes as for "
      "planarize.");
  cmd->add_option("curve", args->curve, "Planar curve P1 .. P4 (text: x y z per line)")->required();
  cmd->add_option("-o,--output", args->outputs.mesh, "The M-revolution mesh (.obj, .off, .ply)")
      ->required();
  cmd->add_option("--p2", args->p2, "P2 x,y,z: on the circle through P1 and P4 (drawing plane)")
      ->required()
      ->check(Finite())
      ->delimiter(',');
  cmd->add_option("--p3", args->p3, "P3 x,y,z: on the same circle")
      ->required()
      ->check(Finite())
      ->delimiter(',');
  cmd->add_option("--t", args->options.t, "Ratio P1'P2' / P4'P3' of the trapezoid (> 0)")
      ->check(Positive())
      ->capture_default_str();
  cmd->add_option("--root", args->options.root, "Which of the (up to) two centres: 0 or 1")
      ->check(Within(0, 1))
      ->capture_default_str();
  cmd->add_option("--arch-segments", args->options.arch_segments, "Quads along each arch")
      ->check(Within(2, 100000))
      ->capture_default_str();
  cmd->add_option(
         "--up", args->up,
         "x,y,z: the arches rise to this side of the drawing plane, which it must not lie in "
         "(default: +z, or the side of (P2 - P1) x (P4 - P1) when +z lies in the plane)")
      ->check(Finite())
      ->delimiter(',');
  cmd->add_option("--revolution", args->revolution,
                  "Also write the surface of revolution it is the inversion of");
  cmd->add_option("--report", args->outputs.report, "Write a JSON report");
  cmd->add_option("--picture", args->outputs.picture, "Write a shaded SVG picture");
  cmd->callback([args, exit_code]() { *exit_code = RunMRevolution(*args); });
}

}  // namespace gproj
