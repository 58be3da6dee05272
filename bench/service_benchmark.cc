// Benchmarks of the HTTP service's run path (RunTable: a request parsed as the server parses it,
// queued, run on a worker, its events recorded), without the network.
//   BM_ServiceDragResolve/n/s a planarize run on a noisy n × n grid to 1e-6, then the re-solves a
//                             drag in the web app sends: one inner vertex moved by 5% of the mean
//                             edge (alternately 5% and 2.5% up), re-solved from that result to
//                             1e-3, submitted and awaited as POST /api/runs/{id}/resolve does:
//                             milliseconds per re-solve (submit to end), iterations. s = 0: the
//                             grid over the elliptic paraboloid z = 0.3x² + 0.2y²; s = 1: over
//                             the saddle z = 0.5x² − 0.4y² + 0.3xy (grid lines not conjugate)
//   BM_ServiceFirstRun/n      the cold run of the same request to 1e-6
#include <benchmark/benchmark.h>

#include <chrono>
#include <string>

#include "gproj/geometry/mesh/quad_grid.h"
#include "gproj/geometry/mesh/scale_free.h"
#include "gproj/service/run_table.h"

namespace gproj::service {
namespace {

using Clock = std::chrono::steady_clock;

nlohmann::json GridRequest(int n, int shape = 0) {
  QuadGridOptions grid;
  grid.nu = grid.nv = n;
  if (shape == 1) {
    grid.a = 0.5;
    grid.b = -0.4;
    grid.c = 0.3;
  }
  grid.noise = 0.05;
  grid.seed = 1;
  return {{"problem", "planarize"},
          {"inputs", {{"mesh", MeshJson(MakeQuadGrid(grid))}}},
          {"options", {{"tolerance", 1e-6}}}};
}

// Submits and waits; the run's description.
nlohmann::json RunToEnd(RunTable* table, RunRequest request, const std::string& parent = "") {
  const std::string id = table->Submit(std::move(request), parent);
  table->Wait(id, std::chrono::hours(1));
  return *table->Describe(id, true);
}

void BM_ServiceFirstRun(benchmark::State& state) {
  const int n = static_cast<int>(state.range(0));
  RunTable table({});
  const nlohmann::json body = GridRequest(n);
  double seconds = 0.0, iterations = 0.0, runs = 0.0;
  for (auto _ : state) {
    const auto t = Clock::now();
    const nlohmann::json run =
        RunToEnd(&table, ParseRunRequest(body, Registry::Builtin(), RequestLimits{}));
    seconds += std::chrono::duration<double>(Clock::now() - t).count();
    if (run.at("status") != "converged") state.SkipWithError("the run did not converge");
    iterations += run.at("report").at("iterations").get<double>();
    runs += 1.0;
  }
  state.counters["run_ms"] = 1e3 * seconds / runs;
  state.counters["iterations"] = iterations / runs;
  state.counters["quads"] = static_cast<double>((n - 1) * (n - 1));
}
BENCHMARK(BM_ServiceFirstRun)->Arg(41)->Unit(benchmark::kMillisecond);

void BM_ServiceDragResolve(benchmark::State& state) {
  const int n = static_cast<int>(state.range(0));
  RunTable table({});
  const nlohmann::json body = GridRequest(n, static_cast<int>(state.range(1)));
  const std::string first =
      table.Submit(ParseRunRequest(body, Registry::Builtin(), RequestLimits{}));
  table.Wait(first, std::chrono::hours(1));
  const auto base = table.Finished(first);
  if (!base || base->state != RunState::kConverged) {
    state.SkipWithError("the first run did not converge");
    return;
  }
  const PolyMesh& start = base->result.meshes.at("output");
  const int v = (n / 2) * n + n / 3;
  const auto p = start.point(start.vertex_handle(v));
  const double offset = 0.05 * MeanEdgeLength(start);
  double seconds = 0.0, iterations = 0.0, converged = 0.0, runs = 0.0;
  for (auto _ : state) {
    const double z = p[2] + (static_cast<int>(runs) % 2 == 0 ? offset : 0.5 * offset);
    const nlohmann::json edit = {{"moved", {{{"vertex", v}, {"to", {p[0], p[1], z}}}}},
                                 {"options", {{"tolerance", 1e-3}}}};
    const auto t = Clock::now();
    const nlohmann::json run = RunToEnd(&table, ResolveRequest(*base, edit), first);
    seconds += std::chrono::duration<double>(Clock::now() - t).count();
    iterations += run.at("report").at("iterations").get<double>();
    converged += run.at("status") == "converged" ? 1.0 : 0.0;
    runs += 1.0;
  }
  state.counters["resolve_ms"] = 1e3 * seconds / runs;
  state.counters["iterations"] = iterations / runs;
  state.counters["converged_fraction"] = converged / runs;
  state.counters["quads"] = static_cast<double>((n - 1) * (n - 1));
}
BENCHMARK(BM_ServiceDragResolve)
    ->Args({41, 0})
    ->Args({41, 1})
    ->Args({81, 0})
    ->Unit(benchmark::kMillisecond);

}  // namespace
}  // namespace gproj::service
