// `grid` in the registry: a noisy quad grid over a doubly curved surface or an asymptotic or
// circular net, the test input of the problems and the benchmarks (a generator: no inputs).
#include <cstdio>
#include <functional>

#include "gproj/geometry/mesh/parametric_grid.h"
#include "gproj/geometry/mesh/quad_grid.h"
#include "gproj/problems/run/builtin_problems.h"
#include "gproj/problems/run/construction.h"

namespace gproj {
namespace {

struct GridSettings {
  std::string surface = "paraboloid";
  bool diagonal = false;
  QuadGridOptions grid = [] {
    QuadGridOptions g;
    g.noise = 0.05;
    return g;
  }();
};

const OptionSchema<GridSettings>& Schema() {
  static const OptionSchema<GridSettings> schema = [] {
    using S = GridSettings;
    OptionSchema<S> s;
    s.Field<std::string>("surface", OptionType::kChoice,
                         "paraboloid (z = a x^2 + b y^2 + c x y + wave sin(pi x) sin(pi y) over "
                         "[-1,1]^2), an asymptotic net: hypar, hyperboloid, enneper, or a "
                         "circular net: revolution (meridians and parallels of a surface of "
                         "revolution)",
                         [](S& x) -> std::string& { return x.surface; })
        .Choices({"paraboloid", "hypar", "hyperboloid", "enneper", "revolution"});
    s.Field<int>("nu", OptionType::kInt, "Vertices along u (vertex (i, j) is i * nv + j)",
                 [](S& x) -> int& { return x.grid.nu; })
        .Range(2, 100000);
    s.Field<int>("nv", OptionType::kInt, "Vertices along v", [](S& x) -> int& {
       return x.grid.nv;
     }).Range(2, 100000);
    const auto coefficient = [&s](const char* name, const char* doc, double QuadGridOptions::*m) {
      s.Field<double>(name, OptionType::kNumber, doc, [m](S& x) -> double& {
         return x.grid.*m;
       }).Range(-1e6, 1e6);
    };
    coefficient("a", "Coefficient of x^2 (paraboloid)", &QuadGridOptions::a);
    coefficient("b", "Coefficient of y^2 (paraboloid)", &QuadGridOptions::b);
    coefficient("c", "Coefficient of x y (paraboloid)", &QuadGridOptions::c);
    coefficient("wave", "Coefficient of sin(pi x) sin(pi y) (paraboloid)", &QuadGridOptions::wave);
    s.Field<double>("noise", OptionType::kNumber,
                    "Noise amplitude as a fraction of the grid spacing (of the mean edge for the "
                    "nets)",
                    [](S& x) -> double& { return x.grid.noise; })
        .Range(0.0, 1e6);
    s.Field<bool>("diagonal", OptionType::kBool,
                  "The lattice turned by 45 degrees, so that the quads' diagonals (not their "
                  "edges) follow the asymptotic lines of the nets (an input for anet --net "
                  "diagonal) or the x and y lines of the paraboloid (conjugate for c = wave = 0: "
                  "an input for planarize --net diagonal); not for revolution",
                  [](S& x) -> bool& { return x.diagonal; });
    s.Custom("seed", OptionType::kInt, "Random seed", 1, [](const nlohmann::json& v, S* x) {
       x->grid.seed = v.get<uint32_t>();
     }).Range(0, 4294967295.0);
    return s;
  }();
  return schema;
}

RunResult Run(const RunInputs&, const nlohmann::json& values, const RunContext&) {
  const GridSettings s = Schema().Apply(values);
  // An OpenMesh vertex with its quad and halfedges, and the text written, take about 400 B.
  CheckMemory("`nu` " + std::to_string(s.grid.nu) + " `nv` " + std::to_string(s.grid.nv),
              400.0 * s.grid.nu * s.grid.nv);
  const Construction construction(ConstructionMethod::kClosedForm, "test grid");
  const bool asymptotic = s.surface != "paraboloid" && s.surface != "revolution";
  if (s.diagonal && !asymptotic && s.surface != "paraboloid")
    throw InputError(
        "`diagonal` applies to the paraboloid and the asymptotic nets (hypar, hyperboloid, "
        "enneper), not to `surface` " +
        s.surface);
  RunResult result;
  if (s.surface == "paraboloid" && !s.diagonal) {
    result.meshes["output"] = MakeQuadGrid(s.grid);
  } else {
    ParametricGridOptions o;
    o.nu = s.grid.nu;
    o.nv = s.grid.nv;
    o.jitter = s.grid.noise;
    o.seed = s.grid.seed;
    o.diagonal = s.diagonal;
    const QuadGridOptions& g = s.grid;
    std::function<Eigen::Vector3d(double, double)> surface;
    if (s.surface == "revolution")
      surface = RevolutionSurface;
    else if (s.surface == "paraboloid")
      surface = [g](double x, double y) {
        return Eigen::Vector3d(x, y,
                               g.a * x * x + g.b * y * y + g.c * x * y +
                                   g.wave * std::sin(M_PI * x) * std::sin(M_PI * y));
      };
    else
      surface = AsymptoticSurface(s.surface);
    result.meshes["output"] = MakeParametricGrid(surface, o);
  }
  result.report = construction.Finish({}, {}, true);
  char line[160];
  std::snprintf(line, sizeof(line), "%s grid%s: %d x %d vertices, noise %g of the spacing",
                s.surface.c_str(), s.diagonal ? " (diagonals along the net)" : "", s.grid.nu,
                s.grid.nv, s.grid.noise);
  result.Info(line);
  return result;
}

}  // namespace

ProblemSpec GridSpec() {
  ProblemSpec spec;
  spec.name = "grid";
  spec.summary =
      "A quad grid over [-1,1]^2 with every vertex moved by uniform noise: on z = a x^2 + b y^2 "
      "+ c x y + wave sin(pi x) sin(pi y) (a test input for planarize), or an asymptotic net "
      "(hypar, hyperboloid, enneper; for anet and hnet) or a circular net (revolution; for the "
      "circular constructions).";
  spec.outputs = {{"output", OutputKind::kMesh, "the grid", true}};
  spec.options = Schema().specs();
  spec.generator = true;
  spec.run = Run;
  return spec;
}

}  // namespace gproj
