// Benchmarks of PQ planarisation on noisy doubly curved grids of n × n vertices.
//   BM_PlanarizationIteration/n/s   guided-projection iterations (s = 1: normals eliminated by
//                                   a Schur complement, 0: direct), split into
//                                   update+assembly / numeric factorisation / solve; the
//                                   factorisation's rate (factor_gflops, from CHOLMOD's flop
//                                   count) next to dense dgemm's in the same run (dgemm_gflops;
//                                   the BLAS library is in the context line "blas")
//   BM_PlanarizationOrdering/n/o    the same with the fill-reducing ordering o (0 auto, 1 AMD,
//                                   2 METIS, 3 NESDIS): analysis time, fill, flops
//   BM_PlanarizeToTolerance/n/0|1   a full solve to max planarity ≤ 1e-6 (0: gproj, 1: Ceres)
#include <benchmark/benchmark.h>

#include <chrono>

#include "dense_rate.h"
#include "geometry/quad_grid.h"
#include "problems/pq_planarization.h"
#include "solver_counters.h"

namespace gproj {
namespace {

using Clock = std::chrono::steady_clock;

PolyMesh NoisyGrid(int n) {
  QuadGridOptions grid;
  grid.nu = grid.nv = n;
  grid.noise = 0.05;
  grid.seed = 1;
  return MakeQuadGrid(grid);
}

double Since(Clock::time_point t) {
  return std::chrono::duration<double>(Clock::now() - t).count();
}

// Runs the real solver for a few iterations and reports the mean per-iteration split from its
// records (what a user's run costs), plus the one-off symbolic analysis.
void BM_PlanarizationIteration(benchmark::State& state) {
  const int n = static_cast<int>(state.range(0));
  const bool eliminate = state.range(1) == 1;
  const PolyMesh mesh = NoisyGrid(n);
  PQPlanarizationOptions options;
  options.solver.max_iterations = 4;
  options.tolerance = 1e-300;
  SolverSummary summary;
  double wall = 0.0;
  for (auto _ : state) {
    PQPlanarization pq(mesh, options);
    SolverOptions solver_options = options.solver;
    solver_options.eliminate_auxiliaries = eliminate;
    const auto t = Clock::now();
    summary = Solve(solver_options, &pq.problem());
    wall = Since(t);
  }
  const PhaseMeans m = SetSolverCounters(summary, &state);
  const int steps = summary.num_steps();
  const double iteration = (wall - summary.analysis_seconds) / steps;
  state.counters["iteration_ms"] = 1e3 * iteration;
  state.counters["iteration_over_factor_solve"] = iteration / (m.factorization + m.solve);
  state.counters["factor_gflops"] = summary.factor_flops / m.factorization / 1e9;
  static const double dgemm = DgemmGflops();  // once per run
  state.counters["dgemm_gflops"] = dgemm;
  state.counters["factor_over_dgemm"] = summary.factor_flops / m.factorization / 1e9 / dgemm;
  state.SetLabel(eliminate ? "schur" : "direct");
}
BENCHMARK(BM_PlanarizationIteration)
    ->ArgsProduct({{51, 101, 201}, {1, 0}})
    ->Iterations(1)
    ->Unit(benchmark::kMillisecond);

void BM_PlanarizationOrdering(benchmark::State& state) {
  const int n = static_cast<int>(state.range(0));
  const auto ordering = static_cast<FillOrdering>(state.range(1));
  const PolyMesh mesh = NoisyGrid(n);
  PQPlanarizationOptions options;
  options.solver.max_iterations = 2;
  options.solver.ordering = ordering;
  options.tolerance = 1e-300;
  SolverSummary summary;
  for (auto _ : state) {
    PQPlanarization pq(mesh, options);
    summary = Solve(options.solver, &pq.problem());
  }
  const PhaseMeans m = SetSolverCounters(summary, &state);
  state.counters["factor_gflop"] = summary.factor_flops / 1e9;
  state.counters["factor_gflops"] = summary.factor_flops / m.factorization / 1e9;
  state.SetLabel(FillOrderingName(ordering));
}
BENCHMARK(BM_PlanarizationOrdering)
    ->ArgsProduct({{101, 201}, {0, 1, 2, 3}})
    ->Iterations(1)
    ->Unit(benchmark::kMillisecond);

void BM_PlanarizeToTolerance(benchmark::State& state) {
  const int n = static_cast<int>(state.range(0));
  const bool use_ceres = state.range(1) == 1;
  const PolyMesh mesh = NoisyGrid(n);
  PQPlanarizationOptions options;
  options.tolerance = 1e-6;
  options.solver.max_iterations = use_ceres ? 500 : 50;
  double reached = 0.0, iterations = 0.0;
  for (auto _ : state) {
    PQPlanarization pq(mesh, options);
    iterations =
        use_ceres ? pq.RunCeres(options.solver.max_iterations).iterations : pq.Run().iterations;
    reached = pq.Measures().max_planarity;
  }
  state.counters["max_planarity"] = reached;
  state.counters["iterations"] = iterations;
  if (reached > options.tolerance) state.SkipWithError("tolerance 1e-6 not reached");
  state.SetLabel(use_ceres ? "ceres" : "gproj");
}
BENCHMARK(BM_PlanarizeToTolerance)
    ->ArgsProduct({{51, 101, 201}, {0, 1}})
    ->Iterations(1)
    ->Unit(benchmark::kSecond);

}  // namespace
}  // namespace gproj

int main(int argc, char** argv) {
  benchmark::AddCustomContext("blas", gproj::BlasLibrary());
  benchmark::Initialize(&argc, argv);
  if (benchmark::ReportUnrecognizedArguments(argc, argv)) return 1;
  benchmark::RunSpecifiedBenchmarks();
  benchmark::Shutdown();
  return 0;
}
