// Benchmarks of the A-net and H-net problems on jittered 3%-of-edge grids along the asymptotic
// lines of Enneper's surface (n × n vertices), the exact grid as reference surface.
//   BM_ANetIteration/n   guided-projection iterations of the A-net step, split per phase
//   BM_HNet/n            the whole H-net run (A-net step, then weight/vertex rounds)
#include <benchmark/benchmark.h>

#include <chrono>

#include "gproj/geometry/mesh/parametric_grid.h"
#include "gproj/problems/nets/hnet.h"
#include "solver_counters.h"

namespace gproj {
namespace {

PolyMesh Enneper(int n, double jitter) {
  ParametricGridOptions o;
  o.nu = o.nv = n;
  o.jitter = jitter;
  o.seed = 7;
  return MakeParametricGrid(AsymptoticSurface("enneper"), o);
}

void BM_ANetIteration(benchmark::State& state) {
  const int n = static_cast<int>(state.range(0));
  const PolyMesh exact = Enneper(n, 0.0), mesh = Enneper(n, 0.03);
  nets::ANetOptions options;
  options.solver.max_iterations = 4;
  options.tolerance = 1e-300;
  SolverSummary summary;
  for (auto _ : state) {
    nets::ANet anet(mesh, &exact, options);
    summary = anet.Run().summary;
  }
  SetSolverCounters(summary, &state);
}
BENCHMARK(BM_ANetIteration)->Arg(41)->Arg(161)->Iterations(1)->Unit(benchmark::kMillisecond);

void BM_HNet(benchmark::State& state) {
  const int n = static_cast<int>(state.range(0));
  const PolyMesh exact = Enneper(n, 0.0), mesh = Enneper(n, 0.03);
  nets::HNetSummary summary;
  for (auto _ : state) {
    nets::HNet hnet(mesh, &exact, nets::HNetOptions());
    summary = hnet.Run();
  }
  int round_iterations = 0;
  double round_seconds = 0.0;
  for (const nets::HNetRound& r : summary.rounds) {
    round_iterations += r.solver_iterations;
    round_seconds += r.seconds;
  }
  state.counters["variables"] = summary.report.variables;
  state.counters["anet_iterations"] = summary.report.summary.num_steps();
  state.counters["rounds"] = static_cast<double>(summary.rounds.size());
  state.counters["vertex_update_iterations"] = round_iterations;
  state.counters["ms_per_vertex_update_iteration"] =
      round_iterations > 0 ? 1e3 * round_seconds / round_iterations : 0.0;
  state.counters["max_angle_deg"] =
      summary.rounds.empty() ? -1 : summary.rounds.back().max_tangent_angle_deg;
  if (!summary.report.converged) state.SkipWithError(summary.report.termination.c_str());
}
BENCHMARK(BM_HNet)->Arg(41)->Arg(161)->Iterations(1)->Unit(benchmark::kSecond);

}  // namespace
}  // namespace gproj
