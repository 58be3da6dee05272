// `gproj invert`: an inversion (Möbius transformation, 000 eq. 1) of a mesh, optionally about
// the centre of an M-revolution surface (000 §5.1).
#include <chrono>
#include <cstdio>
#include <iostream>
#include <memory>
#include <string>
#include <vector>

#include "apps/super_canal_commands.h"
#include "geometry/mobius.h"
#include "problems/circular_mesh.h"

namespace gproj {
namespace {

struct InvertArgs {
  std::string input;
  MeshOutputs outputs;
  std::vector<double> centre, m_revolution;
  double ratio = 1.0, t = 1.0;
  int root = 0;
};

// The centre of the M-revolution asked for (000 §5.1), logged; its report in *report.
Eigen::Vector3d MRevolutionCentre(const InvertArgs& args, nlohmann::json* report) {
  if (!args.centre.empty()) throw InputError("give either --centre or --m-revolution, not both");
  if (args.m_revolution.size() != 12)
    throw InputError("--m-revolution needs the 12 coordinates of P1, P2, P3, P4, got " +
                     std::to_string(args.m_revolution.size()));
  std::array<Eigen::Vector3d, 4> quad;
  for (int j = 0; j < 4; ++j)
    quad[j] = Vector3({args.m_revolution.begin() + 3 * j, args.m_revolution.begin() + 3 * j + 3},
                      "--m-revolution point P" + std::to_string(j + 1));
  MRevolutionChoice choice;
  try {
    choice = ChooseMRevolutionCentre(quad, args.t, args.root, args.ratio);
  } catch (const InputError& e) {
    throw InputError(std::string("--m-revolution: ") + e.what());
  }
  *report = MRevolutionJson(choice, args.t, args.root);
  const Eigen::Vector3d& centre = choice.centre;
  std::printf(
      "M-revolution (000 §5.1), t = %g: %zu centre(s); using %d: (%.6g, %.6g, %.6g); "
      "image sides P1'P2', P4'P3' at %.2e rad, diagonals %.6g and %.6g\n",
      args.t, choice.centres.size(), args.root, centre.x(), centre.y(), centre.z(),
      choice.image.side_angle, choice.image.diagonals[0], choice.image.diagonals[1]);
  return centre;
}

int RunInvert(const InvertArgs& args) {
  const auto start = std::chrono::steady_clock::now();
  PolyMesh mesh, out;
  nlohmann::json extra = {{"input", args.input}, {"ratio", args.ratio}};
  try {
    args.outputs.Check({{"input", args.input}});
    mesh = ReadMesh(args.input);
    nlohmann::json m_revolution;
    const Eigen::Vector3d centre = args.m_revolution.empty()
                                       ? Vector3(args.centre, "--centre")
                                       : MRevolutionCentre(args, &m_revolution);
    if (!m_revolution.is_null()) extra["m_revolution"] = m_revolution;
    extra["centre"] = {centre.x(), centre.y(), centre.z()};
    std::printf("gproj invert: %s: %zu vertices, %zu faces; centre (%.6g, %.6g, %.6g), ratio %g\n",
                args.input.c_str(), mesh.n_vertices(), mesh.n_faces(), centre.x(), centre.y(),
                centre.z(), args.ratio);
    out = InvertMesh(mesh, centre, args.ratio);
  } catch (const InputError& e) {
    std::cerr << "gproj invert: " << e.what() << "\n";
    return kExitInputError;
  }
  const RunReport report = ConstructionReport(
      "none", MeasureCircularMesh(mesh), MeasureCircularMesh(out), true,
      std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count());
  PrintMeasures("input", report.initial);
  PrintMeasures("inverted", report.final);
  return WriteAndConclude("invert", report, out, "Inversion (Möbius transformation)", args.outputs,
                          extra, "max_concyclicity", 0.0);
}

}  // namespace

void RegisterInvertCommand(CLI::App* app, int* exit_code) {
  auto args = std::make_shared<InvertArgs>();
  CLI::App* cmd = app->add_subcommand(
      "invert",
      "Inversion (Moebius transformation, 000 eq. 1) of a mesh: CM' = k / |CM|^2 CM. "
      "Circular meshes stay circular. With --m-revolution the centre solves 000 §5.1: it maps "
      "the concyclic quad P1 P2 P3 P4 to an isosceles trapezoid with P1'P2' = t P4'P3'.");
  cmd->add_option("mesh", args->input, "Mesh to invert (.obj/.off/.ply)")->required();
  cmd->add_option("-o,--output", args->outputs.mesh, "Inverted mesh to write")->required();
  cmd->add_option("--centre", args->centre, "Centre of inversion x,y,z")
      ->check(Finite())
      ->delimiter(',');
  cmd->add_option("--ratio", args->ratio, "Ratio k of the inversion (non-zero)")
      ->check(Finite())
      ->capture_default_str();
  cmd->add_option("--m-revolution", args->m_revolution,
                  "P1,P2,P3,P4 (12 comma-separated numbers): four concyclic points whose image "
                  "must be an isosceles trapezoid")
      ->check(Finite())
      ->delimiter(',');
  cmd->add_option("--t", args->t, "Ratio of the trapezoid's parallel sides (> 0)")
      ->check(Positive())
      ->capture_default_str();
  cmd->add_option("--root", args->root, "Which of the (up to) two centres to use: 0 or 1")
      ->check(Within(0, 1))
      ->capture_default_str();
  cmd->add_option("--report", args->outputs.report, "Write a JSON report");
  cmd->add_option("--picture", args->outputs.picture, "Write a shaded SVG picture of the result");
  cmd->callback([args, exit_code]() { *exit_code = RunInvert(*args); });
}

}  // namespace gproj
