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
  double tangent_tolerance = 1e-4;  // degrees
  CyclidicMeshOptions options;
};

int RunCyclidic(const CyclidicArgs& args) {
  CyclidicMeshResult r;
  RunReport report;
  try {
    args.outputs.Check({{"input", args.input}});
    CyclidicMeshOptions options = args.options;
    if (!args.normal.empty()) {
      const Eigen::Vector3d normal = Vector3(args.normal, "--normal");
      if (normal.norm() == 0.0) throw InputError("--normal must not be zero");
      options.given_frame = true;
      options.angles = AnglesFromNormal(normal);
      options.angles.psi = args.options.angles.psi;
    }
    const PolyMesh mesh = ReadMesh(args.input);
    std::printf("gproj cyclidic: %s: %zu faces; %d fine quads per arc; frame at vertex 0 %s\n",
                args.input.c_str(), mesh.n_faces(), options.surface.segments,
                options.given_frame ? "from --normal"
                                    : "by 000 eq. 5 (sum of 1/R^2 over the arcs, Ceres BFGS)");
    const auto start = std::chrono::steady_clock::now();
    r = CyclidicSurfaceOfMesh(mesh, options, args.input);
    report = CyclidicRunReport(
        r, args.tangent_tolerance,
        std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count());
  } catch (const InputError& e) {
    std::cerr << "gproj cyclidic: " << e.what() << "\n";
    return kExitInputError;
  }
  const NamedValues& m = report.final;
  std::printf("eq. 5 of the net: %.6g -> %.6g\n", ValueOf(report.initial, "smoothness_energy"),
              ValueOf(m, "smoothness_energy"));
  std::printf(
      "%g Dupin cyclide patches, %zu fine quads (circular to %.1e: curvature-line quads); "
      "tangent planes across shared arcs agree to %.1e deg; frames close around every face to "
      "%.1e deg\n",
      ValueOf(m, "patches"), r.surface.mesh.n_faces(), ValueOf(m, "fine_max_concyclicity"),
      ValueOf(m, "max_tangent_angle_deg"), ValueOf(m, "max_face_frame_closure_deg"));
  nlohmann::json extra = CyclidicJson(r);
  extra["input"] = args.input;
  char title[160];
  std::snprintf(title, sizeof(title),
                "Smooth cyclidic surface (000 §2.2), %g Dupin cyclide patches",
                ValueOf(m, "patches"));
  return WriteAndConclude("cyclidic", report, r.surface.mesh, title, args.outputs, extra, "", 0.0);
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
      "given. Exit codes as for planarize (3: the surface folds or pinches, or the tangent planes "
      "disagree beyond --tangent-tolerance; the result is written).");
  cmd->add_option("input", args->input, "Circular quad mesh in grid order (OBJ/OFF/PLY)")
      ->required();
  cmd->add_option("-o,--output", args->outputs.mesh, "Fine mesh of the smooth surface")->required();
  cmd->add_option("--normal", args->normal,
                  "Normal of the frame at vertex 0 (default: the frame minimising 000 eq. 5)")
      ->check(Finite())
      ->delimiter(',');
  cmd->add_option("--psi", args->options.angles.psi,
                  "Turn (radians) of the frame's first tangent about the normal (the start of "
                  "the minimisation without --normal)")
      ->check(Finite())
      ->capture_default_str();
  cmd->add_option("--segments", args->options.surface.segments, "Fine quads along every arc")
      ->check(Within(1, 1000))
      ->capture_default_str();
  cmd->add_option("--max-iterations", args->options.max_iterations, "BFGS iterations for the frame")
      ->check(Within(1, 100000))
      ->capture_default_str();
  cmd->add_option("--closure-tolerance", args->options.closure_tolerance,
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
