// Benchmarks of PQ planarisation on noisy doubly curved grids of n × n vertices.
//   BM_PlanarizationIteration/n/s   guided-projection iterations (s = 1: normals eliminated by
//                                   a Schur complement, 0: direct), split into
//                                   update+assembly / numeric factorisation / solve; the
//                                   factorisation's rate (factor_gflops, from CHOLMOD's flop
//                                   count) next to dense dgemm's in the same run (dgemm_gflops;
//                                   the BLAS library is in the context line "blas")
//   BM_PlanarizationOrdering/n/o    the same with the fill-reducing ordering o (0 auto, 1 AMD,
//                                   2 METIS, 3 NESDIS): analysis time, fill, flops
//   BM_PlanarizeToTolerance/n/s/e   a full solve to max planarity ≤ 10^-e (s = 0: gproj, 1: Ceres):
//                                   seconds, iterations, time in numeric factorisations
//                                   (over_factor), Ceres over gproj, peak memory per quad
//   BM_PlanarizeStepControl/n/p/c/e a full solve of an n × n non-conjugate saddle grid with noise
//                                   p% of the spacing
//                                   to 10^-e with step control c (0 damping, 1 dogleg):
//                                   iterations, numeric factorisations, trial points,
//                                   factorisation-equivalents including the analysis
//   BM_PlanarizeWarmResolve/n       a planarised n × n grid, one inner vertex moved by 5% of an
//                                   edge, re-solved from the last result (Resolve) to 1e-6:
//                                   iterations, milliseconds per iteration, the whole re-solve
//   BM_PlanarizeLocalGlobal/n/e/m   gproj against a prefactored local–global planariser
//                                   (ShapeOp's method; m > 0: Anderson-accelerated with depth
//                                   m, Peng et al. 2018) to max planarity ≤ 10^-e
#include <benchmark/benchmark.h>

#include <chrono>
#include <cmath>
#include <fstream>
#include <map>
#include <string>
#include <utility>

#include "dense_rate.h"
#include "gproj/geometry/mesh/quad_grid.h"
#include "gproj/geometry/mesh/scale_free.h"
#include "gproj/problems/pq/pq_planarization.h"
#include "local_global_planarizer.h"
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

// A harder grid: a saddle with a twist and a wave, whose grid lines are far from conjugate,
// with noise `noise` of the spacing (the runs that reject steps).
PolyMesh NonConjugateGrid(int n, double noise) {
  QuadGridOptions grid;
  grid.nu = grid.nv = n;
  grid.a = 0.3, grid.b = -0.2, grid.c = 0.1, grid.wave = 0.05;
  grid.noise = noise;
  grid.seed = 7;
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
  pq::PQPlanarizationOptions options;
  options.solver.max_iterations = 4;
  options.tolerance = 1e-300;
  SolverSummary summary;
  double wall = 0.0;
  for (auto _ : state) {
    pq::PQPlanarization pq(mesh, options);
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
  pq::PQPlanarizationOptions options;
  options.solver.max_iterations = 2;
  options.solver.ordering = ordering;
  options.tolerance = 1e-300;
  SolverSummary summary;
  for (auto _ : state) {
    pq::PQPlanarization pq(mesh, options);
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

// Peak resident memory since the last ResetPeakMemory, in bytes (Linux: VmHWM; 0 elsewhere).
void ResetPeakMemory() {
  std::ofstream clear("/proc/self/clear_refs");
  clear << "5";
}
double PeakMemoryBytes() {
  std::ifstream status("/proc/self/status");
  std::string line;
  while (std::getline(status, line))
    if (line.rfind("VmHWM:", 0) == 0) return 1024.0 * std::stod(line.substr(6));
  return 0.0;
}

// gproj's seconds to the tolerance per grid size, for the Ceres rows' ratio (ArgsProduct runs
// gproj before Ceres for each size).
std::map<std::pair<int, int>, double>& GprojSeconds() {
  static std::map<std::pair<int, int>, double> seconds;
  return seconds;
}

// A whole run to max planarity ≤ 10^-e (problem set-up, analysis and every iteration), next to
// the factorisation floor: over_factor is the run's time in numeric factorisations of the same
// problem. The Ceres rows give ceres_over_gproj when the gproj row of that size ran first.
void BM_PlanarizeToTolerance(benchmark::State& state) {
  const int n = static_cast<int>(state.range(0));
  const bool use_ceres = state.range(1) == 1;
  const int exponent = static_cast<int>(state.range(2));
  const PolyMesh mesh = NoisyGrid(n);
  pq::PQPlanarizationOptions options;
  options.tolerance = std::pow(10.0, -exponent);
  options.solver.max_iterations = use_ceres ? 500 : 50;
  double reached = 0.0, iterations = 0.0, seconds = 0.0;
  SolverSummary summary;
  ResetPeakMemory();
  for (auto _ : state) {
    const auto t = Clock::now();
    pq::PQPlanarization pq(mesh, options);
    const RunReport report = use_ceres ? pq.RunCeres(options.solver.max_iterations) : pq.Run();
    seconds = Since(t);
    iterations = report.iterations;
    summary = report.summary;
    reached = pq.Measures().max_planarity;
  }
  state.counters["seconds"] = seconds;
  state.counters["max_planarity"] = reached;
  state.counters["iterations"] = iterations;
  state.counters["quads"] = static_cast<double>(mesh.n_faces());
  state.counters["peak_bytes_per_quad"] = PeakMemoryBytes() / mesh.n_faces();
  if (use_ceres) {
    const auto gproj = GprojSeconds().find({n, exponent});
    if (gproj != GprojSeconds().end()) state.counters["ceres_over_gproj"] = seconds / gproj->second;
  } else {
    GprojSeconds()[{n, exponent}] = seconds;
    const PhaseMeans m = SetSolverCounters(summary, &state);
    state.counters["over_factor"] = seconds / m.factorization;
  }
  if (reached > options.tolerance) state.SkipWithError("tolerance not reached");
  state.SetLabel(use_ceres ? "ceres" : "gproj");
}
BENCHMARK(BM_PlanarizeToTolerance)
    ->ArgsProduct({{51, 101, 201}, {0, 1}, {6}})
    ->Args({201, 0, 9})
    ->Iterations(1)
    ->Unit(benchmark::kSecond);

// What a rejected step costs under each step control: damping refactorises per rejection, the
// dogleg keeps the iteration's factor. factor_equivalents = numeric factorisations + the
// analysis time over the mean factorisation time.
void BM_PlanarizeStepControl(benchmark::State& state) {
  const int n = static_cast<int>(state.range(0));
  const PolyMesh mesh = NonConjugateGrid(n, 0.01 * static_cast<double>(state.range(1)));
  pq::PQPlanarizationOptions options;
  options.solver.step_control = state.range(2) == 1 ? StepControl::kDogleg : StepControl::kDamping;
  options.tolerance = std::pow(10.0, -static_cast<double>(state.range(3)));
  double seconds = 0.0, reached = 0.0;
  SolverSummary summary;
  for (auto _ : state) {
    const auto t = Clock::now();
    pq::PQPlanarization pq(mesh, options);
    summary = pq.Run().summary;
    seconds = Since(t);
    reached = pq.Measures().max_planarity;
  }
  int factorizations = 0, trials = 0;
  double factor_seconds = 0.0;
  for (const IterationRecord& r : summary.iterations) {
    factorizations += r.factorizations;
    trials += r.trials;
    factor_seconds += r.factorization_seconds;
  }
  state.counters["seconds"] = seconds;
  state.counters["max_planarity"] = reached;
  state.counters["iterations"] = summary.num_steps();
  state.counters["factorizations"] = factorizations;
  state.counters["trials"] = trials;
  state.counters["factor_equivalents"] =
      factorizations +
      (factorizations > 0 ? summary.analysis_seconds / (factor_seconds / factorizations) : 0.0);
  state.counters["quads"] = static_cast<double>(mesh.n_faces());
  if (reached > options.tolerance) state.SkipWithError("tolerance not reached");
  state.SetLabel(StepControlName(options.solver.step_control));
}
BENCHMARK(BM_PlanarizeStepControl)
    ->ArgsProduct({{41, 81, 201}, {5, 8}, {0, 1}, {3, 6}})
    ->Iterations(1)
    ->Unit(benchmark::kSecond);

// The cost of a designer's drag: after a cold run to 1e-6, each benchmark iteration moves one
// inner vertex by 5% of the mean edge (alternately up and back) and re-solves warm.
void BM_PlanarizeWarmResolve(benchmark::State& state) {
  const int n = static_cast<int>(state.range(0));
  pq::PQPlanarizationOptions options;
  options.tolerance = 1e-6;
  pq::PQPlanarization pq(NoisyGrid(n), options);
  if (!pq.Run().converged) state.SkipWithError("the cold run did not converge");
  const PolyMesh start = pq.Result();
  const int v = (n / 2) * n + n / 3;
  const auto p = start.point(start.vertex_handle(v));
  const Eigen::Vector3d origin(p[0], p[1], p[2]);
  const double offset = 0.05 * MeanEdgeLength(start);
  double iterations = 0.0, seconds = 0.0, converged = 0.0, runs = 0.0;
  for (auto _ : state) {
    const double sign = static_cast<int>(runs) % 2 == 0 ? 1.0 : 0.0;
    const auto t = Clock::now();
    const RunReport report = pq.Resolve({v}, {origin + sign * offset * Eigen::Vector3d::UnitZ()});
    seconds += Since(t);
    iterations += report.iterations;
    converged += report.converged ? 1.0 : 0.0;
    runs += 1.0;
  }
  state.counters["iterations"] = iterations / runs;
  state.counters["resolve_ms"] = 1e3 * seconds / runs;
  state.counters["iteration_ms"] = iterations > 0.0 ? 1e3 * seconds / iterations : 0.0;
  state.counters["converged_fraction"] = converged / runs;
  state.counters["quads"] = static_cast<double>((n - 1) * (n - 1));
}
BENCHMARK(BM_PlanarizeWarmResolve)->Arg(41)->Arg(81)->Unit(benchmark::kMillisecond);

// Max vertex displacement from `reference` / the reference's bounding-box diagonal.
double MaxDisplacement(const Eigen::MatrixX3d& v, const Eigen::MatrixX3d& reference) {
  const double diagonal = (reference.colwise().maxCoeff() - reference.colwise().minCoeff()).norm();
  return (v - reference).rowwise().norm().maxCoeff() / diagonal;
}

// gproj against a prefactored local–global planariser (ShapeOp's method; see
// bench/local_global_planarizer.h) on the same noisy grid, to the same max planarity 10^-e.
// The local–global run tries the closeness weights 10^-1 … 10^-8 (relative to the planes'
// weight 1), each until the planarity is reached, stops improving (less than 1% over 500
// iterations) or takes longer than the best weight so far or than 30 s; the fastest weight that
// reaches the tolerance is reported: lg_seconds (set-up, factorisation and iterations),
// lg_iterations, lg_closeness, lg_displacement, next to gproj's whole run (gproj_seconds,
// gproj_displacement) and lg_over_gproj. When no weight reaches it, lg_reached = 0,
// lg_lowest_planarity is the best any weight reached and lg_over_gproj is 30 s over gproj's
// time.
void BM_PlanarizeLocalGlobal(benchmark::State& state) {
  const int n = static_cast<int>(state.range(0));
  const int exponent = static_cast<int>(state.range(1));
  const int depth = static_cast<int>(state.range(2));
  const double tolerance = std::pow(10.0, -exponent);
  const PolyMesh mesh = NoisyGrid(n);
  Eigen::MatrixX3d reference(mesh.n_vertices(), 3);
  for (const auto vh : mesh.vertices())
    reference.row(vh.idx()) << mesh.point(vh)[0], mesh.point(vh)[1], mesh.point(vh)[2];
  constexpr double kBudget = 30.0;
  double gproj_seconds = 0.0, gproj_reached = 0.0, gproj_displacement = 0.0;
  double best = kBudget, best_weight = 0.0, best_iterations = 0.0, best_displacement = 0.0;
  double best_rejected = 0.0;
  double lowest = HUGE_VAL;  // the lowest planarity any weight reached
  bool reached = false;
  for (auto _ : state) {
    pq::PQPlanarizationOptions options;
    options.tolerance = tolerance;
    auto t = Clock::now();
    pq::PQPlanarization pq(mesh, options);
    pq.Run();
    gproj_seconds = Since(t);
    const PlanarityMeasures m = pq.Measures();
    gproj_reached = m.max_planarity;
    gproj_displacement = m.max_displacement;
    for (double weight : {1e-1, 1e-2, 1e-3, 1e-4, 1e-5, 1e-6, 1e-7, 1e-8}) {
      t = Clock::now();
      LocalGlobalPlanarizer lg(mesh, weight, depth);
      // The stall test compares the lowest planarity so far (Anderson's is not monotone).
      double planarity = lg.MaxPlanarity(), lowest_here = planarity, checkpoint = planarity;
      int iterations = 0;
      while (planarity > tolerance && Since(t) < best) {
        lg.Iterate();
        planarity = lg.MaxPlanarity();
        lowest_here = std::min(lowest_here, planarity);
        if (++iterations % 500 == 0) {
          if (lowest_here > 0.99 * checkpoint) break;  // stalled at this weight's fixed point
          checkpoint = lowest_here;
        }
      }
      const double seconds = Since(t);
      lowest = std::min(lowest, planarity);
      if (planarity <= tolerance && seconds < best) {
        reached = true;
        best = seconds;
        best_weight = weight;
        best_iterations = iterations;
        best_displacement = MaxDisplacement(lg.vertices(), reference);
        best_rejected = lg.rejected();
      }
    }
  }
  state.counters["quads"] = static_cast<double>(mesh.n_faces());
  state.counters["gproj_seconds"] = gproj_seconds;
  state.counters["gproj_max_planarity"] = gproj_reached;
  state.counters["gproj_displacement"] = gproj_displacement;
  state.counters["lg_reached"] = reached ? 1.0 : 0.0;
  state.counters["lg_seconds"] = best;
  state.counters["lg_iterations"] = best_iterations;
  state.counters["lg_closeness"] = best_weight;
  state.counters["lg_displacement"] = best_displacement;
  state.counters["lg_over_gproj"] = best / gproj_seconds;
  state.counters["lg_lowest_planarity"] = lowest;
  state.counters["lg_anderson_depth"] = depth;
  state.counters["lg_rejected"] = best_rejected;  // Anderson points not kept
  if (gproj_reached > tolerance) state.SkipWithError("gproj did not reach the tolerance");
  state.SetLabel(std::string(depth > 0 ? "Anderson " : "") +
                 (reached ? "local-global reached" : "local-global not within 30 s"));
}
BENCHMARK(BM_PlanarizeLocalGlobal)
    ->ArgsProduct({{41, 81}, {3, 6}, {0, 6}})
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
