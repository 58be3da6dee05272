// `gproj grid`: writes a noisy doubly curved quad grid, the test input of the benchmarks.
#include <functional>
#include <iostream>
#include <memory>
#include <string>

#include "apps/commands.h"
#include "geometry/parametric_grid.h"
#include "geometry/quad_grid.h"

namespace gproj {

void RegisterGridCommand(CLI::App* app, int* exit_code) {
  struct Args {
    std::string output;
    std::string surface = "paraboloid";
    QuadGridOptions grid;
  };
  auto args = std::make_shared<Args>();
  args->grid.noise = 0.05;
  CLI::App* cmd = app->add_subcommand("grid",
                                      "Write a quad grid over [-1,1]^2 on z = a x^2 + b y^2 + c x "
                                      "y + wave sin(pi x) sin(pi y) with every vertex moved "
                                      "by uniform noise (a test input for planarize)");
  cmd->add_option("-o,--output", args->output, "Mesh to write (.obj, .off or .ply)")->required();
  cmd->add_option("--surface", args->surface,
                  "paraboloid (z = a x^2 + b y^2 + c x y + wave sin(pi x) sin(pi y)), an "
                  "asymptotic net: hypar, hyperboloid, "
                  "enneper, or a circular net: revolution (meridians and parallels of a surface of "
                  "revolution; parameters over [-1,1]^2)")
      ->check(CLI::IsMember({"paraboloid", "hypar", "hyperboloid", "enneper", "revolution"}))
      ->capture_default_str();
  cmd->add_option("--nu", args->grid.nu, "Vertices along u")
      ->check(Within(2, 100000))
      ->capture_default_str();
  cmd->add_option("--nv", args->grid.nv, "Vertices along v")
      ->check(Within(2, 100000))
      ->capture_default_str();
  cmd->add_option("--a", args->grid.a, "Coefficient of x^2")
      ->check(Finite())
      ->capture_default_str();
  cmd->add_option("--b", args->grid.b, "Coefficient of y^2")
      ->check(Finite())
      ->capture_default_str();
  cmd->add_option("--c", args->grid.c, "Coefficient of x y")
      ->check(Finite())
      ->capture_default_str();
  cmd->add_option("--wave", args->grid.wave, "Coefficient of sin(pi x) sin(pi y) (paraboloid)")
      ->check(Finite())
      ->capture_default_str();
  cmd->add_option(
         "--noise", args->grid.noise,
         "Noise amplitude as a fraction of the grid spacing (mean edge for asymptotic nets)")
      ->check(NonNegative())
      ->capture_default_str();
  cmd->add_option("--seed", args->grid.seed, "Random seed")->capture_default_str();
  cmd->callback([args, exit_code]() {
    try {
      CheckMeshOutputPath("--output", args->output);
      // An OpenMesh vertex with its quad and halfedges, and the text written, take about 400 B.
      CheckMemory(
          "--nu " + std::to_string(args->grid.nu) + " --nv " + std::to_string(args->grid.nv),
          400.0 * args->grid.nu * args->grid.nv);
      if (args->surface == "paraboloid") {
        WriteMeshAtomically(MakeQuadGrid(args->grid), args->output);
      } else {
        ParametricGridOptions o;
        o.nu = args->grid.nu;
        o.nv = args->grid.nv;
        o.jitter = args->grid.noise;
        o.seed = args->grid.seed;
        const auto surface = args->surface == "revolution"
                                 ? std::function<Eigen::Vector3d(double, double)>(RevolutionSurface)
                                 : AsymptoticSurface(args->surface);
        WriteMeshAtomically(MakeParametricGrid(surface, o), args->output);
      }
      std::cout << "wrote " << args->output << ": " << args->grid.nu << " x " << args->grid.nv
                << " vertices, noise " << args->grid.noise << " of the spacing\n";
      *exit_code = kExitOk;
    } catch (const InputError& e) {
      std::cerr << "gproj grid: " << e.what() << "\n";
      *exit_code = kExitInputError;
    }
  });
}

}  // namespace gproj
