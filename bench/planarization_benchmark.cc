// Benchmarks of PQ planarisation on noisy doubly curved grids of n × n vertices.
//   BM_PlanarizationIteration/n     one guided-projection iteration, split into
//                                   update+assembly / numeric factorisation / solve
//   BM_PlanarizeToTolerance/n/0|1   a full solve to max planarity ≤ 1e-6 (0: gproj, 1: Ceres)
#include <benchmark/benchmark.h>

#include <chrono>

#include "geometry/quad_grid.h"
#include "problems/pq_planarization.h"
#include "solver/linearized_system.h"
#include "solver/sparse_cholesky.h"

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

void BM_PlanarizationIteration(benchmark::State& state) {
  const int n = static_cast<int>(state.range(0));
  PQPlanarizationOptions options;
  PQPlanarization pq(NoisyGrid(n), options);
  Problem& problem = pq.problem();
  LinearizedSystem system(&problem);
  auto cholesky = CreateSparseCholesky(LinearSolverType::kCholmod, 0);
  std::string why;
  const auto t_analyze = Clock::now();
  if (!cholesky->Analyze(system.a(), &why)) state.SkipWithError(why.c_str());
  const double analysis = Since(t_analyze);
  Eigen::VectorXd rhs(problem.layout().num_variables()), step(rhs.size());
  double assembly = 0.0, factorization = 0.0, solve = 0.0;
  for (auto _ : state) {
    auto t = Clock::now();
    system.Assemble(problem.x(), options.fairness_weight, 1.0, &why);
    system.MultiplyAr(&rhs);
    rhs = -rhs;
    assembly += Since(t);
    t = Clock::now();
    if (!cholesky->Factorize(system.a(), options.epsilon * options.epsilon, &why))
      state.SkipWithError(why.c_str());
    factorization += Since(t);
    t = Clock::now();
    cholesky->Solve(rhs.data(), step.data(), &why);
    solve += Since(t);
    benchmark::DoNotOptimize(step.data());
  }
  const double iterations = static_cast<double>(state.iterations());
  state.counters["variables"] = problem.layout().num_variables();
  state.counters["nnz_J"] = system.a().nnz();
  state.counters["nnz_L"] = static_cast<double>(cholesky->FactorNonZeros());
  state.counters["analysis_ms"] = 1e3 * analysis;
  state.counters["assembly_ms"] = 1e3 * assembly / iterations;
  state.counters["factor_ms"] = 1e3 * factorization / iterations;
  state.counters["solve_ms"] = 1e3 * solve / iterations;
  state.counters["total_over_factor_solve"] =
      (assembly + factorization + solve) / (factorization + solve);
}
BENCHMARK(BM_PlanarizationIteration)->Arg(51)->Arg(101)->Arg(201)->Unit(benchmark::kMillisecond);

void BM_PlanarizeToTolerance(benchmark::State& state) {
  const int n = static_cast<int>(state.range(0));
  const bool use_ceres = state.range(1) == 1;
  const PolyMesh mesh = NoisyGrid(n);
  PQPlanarizationOptions options;
  options.tolerance = 1e-6;
  options.max_iterations = use_ceres ? 500 : 50;
  double reached = 0.0, iterations = 0.0;
  for (auto _ : state) {
    PQPlanarization pq(mesh, options);
    if (use_ceres) {
      const ceres::Solver::Summary s = pq.SolveWithCeres(options.max_iterations);
      iterations = s.iterations.empty() ? 0 : s.iterations.back().iteration;
    } else {
      iterations = pq.Solve().num_steps();
    }
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

BENCHMARK_MAIN();
