// `gproj cyclidic`: the smooth cyclidic surface of a circular mesh (000 §2.1–2.2): a frame at one
// vertex makes it a cyclidic net, every quad carries a Dupin cyclide patch, and the patches join
// with common tangent planes.
#include <chrono>
#include <cstdio>
#include <iostream>
#include <memory>
#include <string>
#include <vector>

#include "apps/super_canal_commands.h"
#include "geometry/quad_grid.h"
#include "problems/circular_mesh.h"
#include "problems/cyclidic_surface.h"

namespace gproj {
namespace {

struct CyclidicArgs {
  std::string input;
  MeshOutputs outputs;
  std::vector<double> normal;
  double psi = 0.0;
  int max_iterations = 200;
  double closure_tolerance = 1e-6;  // degrees
  double tangent_tolerance = 1e-4;  // degrees
  CyclidicSurfaceOptions options;
};

int RunCyclidic(const CyclidicArgs& args) {
  CyclidicSurface surface;
  RunReport report;
  GridFrameFairing fairing;
  FrameAngles angles;
  try {
    args.outputs.Check({{"input", args.input}});
    std::string why;
    if (!args.options.IsValid(&why)) throw InputError(why);
    const PolyMesh mesh = ReadMesh(args.input);
    const GridShape shape = DetectGridShape(mesh, args.input);
    std::vector<Eigen::Vector3d> points;
    for (auto v : mesh.vertices()) {
      const auto& p = mesh.point(v);
      points.emplace_back(p[0], p[1], p[2]);
    }
    std::printf("gproj cyclidic: %s: %d x %d quads in grid order; %d fine quads per arc\n",
                args.input.c_str(), shape.rows, shape.cols, args.options.segments);
    const auto start = std::chrono::steady_clock::now();
    Frame frame;
    if (!args.normal.empty()) {
      const Eigen::Vector3d normal = Vector3(args.normal, "--normal");
      if (normal.norm() == 0.0) throw InputError("--normal must not be zero");
      angles = AnglesFromNormal(normal);
      angles.psi = args.psi;
      frame = GridStartFrame(shape, points, angles);
    } else {
      FrameAngles first = DefaultGridAngles(shape, points);
      first.psi = args.psi;
      fairing = FairGridFrame(shape, points, first, args.max_iterations);
      angles = fairing.angles;
      frame = fairing.frame;
      std::printf(
          "frame at vertex 0 by 000 eq. 5 (sum of 1/R^2 over the arcs, Ceres line-search BFGS): "
          "%.6g -> %.6g in %d iterations\n",
          fairing.initial_energy, fairing.final_energy, fairing.iterations);
    }
    const CyclidicNet net = MakeCyclidicNet(shape, points, frame);
    int face = -1;
    const double closure = MaxFaceFrameClosure(net, &face);
    if (closure > args.closure_tolerance) {
      char text[200];
      std::snprintf(text, sizeof(text),
                    "%s: face %d is not circular: the frames carried around it miss by %.3g deg "
                    "(tolerance %.1e); make the mesh circular first (gproj planarize --circular)",
                    args.input.c_str(), face, closure, args.closure_tolerance);
      throw InputError(text);
    }
    surface = MeshCyclidicSurface(net, args.options);
    NamedValues measures = surface.measures;
    measures.push_back({"smoothness_energy", GridNetEnergy(net)});
    const NamedValues fine = MeasureCircularMesh(surface.mesh);
    measures.push_back({"fine_max_concyclicity", ValueOf(fine, "max_concyclicity")});
    const double tangent = ValueOf(measures, "max_tangent_angle_deg");
    report = ConstructionReport(
        args.normal.empty() ? "ceres-bfgs" : "none",
        {{"smoothness_energy", args.normal.empty() ? fairing.initial_energy : GridNetEnergy(net)}},
        measures, tangent <= args.tangent_tolerance,
        std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count());
    report.iterations = fairing.iterations;
    report.termination =
        args.normal.empty() ? "frame by eq. 5: " + fairing.message : "frame from --normal";
  } catch (const InputError& e) {
    std::cerr << "gproj cyclidic: " << e.what() << "\n";
    return kExitInputError;
  }
  const NamedValues& m = report.final;
  std::printf(
      "%g Dupin cyclide patches, %zu fine quads (circular to %.1e: curvature-line quads); "
      "tangent planes across shared arcs agree to %.1e deg; frames close around every face to "
      "%.1e deg\n",
      ValueOf(m, "patches"), surface.mesh.n_faces(), ValueOf(m, "fine_max_concyclicity"),
      ValueOf(m, "max_tangent_angle_deg"), ValueOf(m, "max_face_frame_closure_deg"));
  const Eigen::Vector3d n = NormalOf(angles);
  nlohmann::json extra = {{"input", args.input}};
  extra["frame"] = {{"lambda", angles.lambda}, {"theta", angles.theta}, {"psi", angles.psi}};
  extra["frame"]["normal"] = {n.x(), n.y(), n.z()};
  extra["fine_mesh"] = {{"rows", surface.fine_shape.rows}, {"cols", surface.fine_shape.cols}};
  char title[160];
  std::snprintf(title, sizeof(title),
                "Smooth cyclidic surface (000 §2.2), %g Dupin cyclide patches",
                ValueOf(m, "patches"));
  return WriteAndConclude("cyclidic", report, surface.mesh, title, args.outputs, extra,
                          "max_tangent_angle_deg", args.tangent_tolerance);
}

}  // namespace

void RegisterCyclidicCommand(CLI::App* app, int* exit_code) {
  auto args = std::make_shared<CyclidicArgs>();
  CLI::App* cmd = app->add_subcommand(
      "cyclidic",
      "Smooth cyclidic surface of a circular quad mesh in grid order (000 §2.1-2.2): a frame at "
      "vertex 0, carried to every vertex by mirror images across the edges, makes the mesh a "
      "cyclidic net; every quad carries a Dupin cyclide patch (both families of curvature lines "
      "circles), the patches join with common tangent planes, and the surface is written as a "
      "fine mesh along its curvature lines. The frame minimises 000 eq. 5 unless --normal is "
      "given. Exit codes as for planarize (3: the tangent planes disagree beyond "
      "--tangent-tolerance).");
  cmd->add_option("input", args->input, "Circular quad mesh in grid order (OBJ/OFF/PLY)")
      ->required();
  cmd->add_option("-o,--output", args->outputs.mesh, "Fine mesh of the smooth surface")->required();
  cmd->add_option("--normal", args->normal,
                  "Normal of the frame at vertex 0 (default: the frame minimising 000 eq. 5)")
      ->check(Finite())
      ->delimiter(',');
  cmd->add_option("--psi", args->psi,
                  "Turn (radians) of the frame's first tangent about the normal (the start of "
                  "the minimisation without --normal)")
      ->check(Finite())
      ->capture_default_str();
  cmd->add_option("--segments", args->options.segments, "Fine quads along every arc")
      ->check(Within(1, 1000))
      ->capture_default_str();
  cmd->add_option("--max-iterations", args->max_iterations, "BFGS iterations for the frame")
      ->check(Within(1, 100000))
      ->capture_default_str();
  cmd->add_option("--closure-tolerance", args->closure_tolerance,
                  "Largest angle (degrees) by which frames carried around a face may miss "
                  "themselves (0 for circular faces)")
      ->check(Positive())
      ->capture_default_str();
  cmd->add_option("--tangent-tolerance", args->tangent_tolerance,
                  "Largest angle (degrees) between the tangent planes of two patches along their "
                  "common arc for exit 0")
      ->check(Positive())
      ->capture_default_str();
  cmd->add_option("--report", args->outputs.report, "Write a JSON report");
  cmd->add_option("--picture", args->outputs.picture,
                  "Write a shaded SVG picture of the smooth surface");
  cmd->callback([args, exit_code]() { *exit_code = RunCyclidic(*args); });
}

}  // namespace gproj
