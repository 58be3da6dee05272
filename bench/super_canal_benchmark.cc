// Combescure transformations of n × n-face circular grids (a surface of revolution).
//   BM_CombescurePropagation/n  000 eq. 4, linear time (input checks and mesh copy included)
//   BM_CombescureGP/n           the same by guided projection on edge-parallelism rows
//                               (problem setup, analysis and factorisations included)
#include <benchmark/benchmark.h>

#include <cmath>

#include "geometry/parametric_grid.h"
#include "problems/combescure.h"

namespace gproj {
namespace {

struct Setup {
  PolyMesh mesh;
  GridShape shape;
  CombescureLengths lengths;
};

Setup MakeSetup(int n) {
  ParametricGridOptions o;
  o.nu = o.nv = n + 1;
  Setup s;
  s.mesh = MakeParametricGrid(RevolutionSurface, o);
  s.shape = DetectGridShape(s.mesh);
  s.lengths = ReferenceLengths(s.mesh, s.shape);
  for (size_t j = 0; j < s.lengths.row.size(); ++j)
    s.lengths.row[j] *= 1.0 + 0.3 * std::sin(6.0 * j / n);
  return s;
}

void BM_CombescurePropagation(benchmark::State& state) {
  const Setup s = MakeSetup(static_cast<int>(state.range(0)));
  for (auto _ : state)
    benchmark::DoNotOptimize(CombescureByPropagation(s.mesh, s.shape, s.lengths).n_vertices());
  state.counters["faces"] = s.shape.rows * s.shape.cols;
}
BENCHMARK(BM_CombescurePropagation)->Arg(100)->Arg(1000)->Unit(benchmark::kMillisecond);

void BM_CombescureGP(benchmark::State& state) {
  const Setup s = MakeSetup(static_cast<int>(state.range(0)));
  int iterations = 0;
  for (auto _ : state) {
    Problem problem = MakeCombescureProblem(s.mesh, s.shape, s.lengths);
    const SolverSummary summary = Solve(CombescureSolverDefaults(), &problem);
    iterations = summary.num_steps();
    benchmark::DoNotOptimize(problem.x().data());
  }
  state.counters["faces"] = s.shape.rows * s.shape.cols;
  state.counters["iterations"] = iterations;
}
BENCHMARK(BM_CombescureGP)->Arg(100)->Arg(200)->Unit(benchmark::kMillisecond);

}  // namespace
}  // namespace gproj
