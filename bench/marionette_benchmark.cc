// Marionette lifts of n × n-face grids with a jittered plan view (002 §3.1 reports 3 ms for
// 10,000 faces).
//   BM_MarionetteLift/n     direct propagation from two guide curves (linear time)
//   BM_MarionetteLiftGP/n   the same lift as one guided-projection iteration (setup included)
#include <benchmark/benchmark.h>

#include <cmath>

#include "gproj/geometry/mesh/quad_grid.h"
#include "gproj/problems/marionette/marionette.h"

namespace gproj {
namespace {

struct Setup {
  marionette::MarionettePlan plan;
  Eigen::VectorXd row, column;
};

Setup MakeSetup(int n) {
  QuadGridOptions o;
  o.nu = o.nv = n + 1;
  o.noise = 0.1;
  Setup s{marionette::MakeMarionettePlan(MakeQuadGrid(o)), Eigen::VectorXd(n + 1),
          Eigen::VectorXd(n + 1)};
  for (int k = 0; k <= n; ++k) {
    s.row[k] = 0.3 * std::sin(6.0 * k / n);
    s.column[k] = 0.2 * std::cos(4.0 * k / n) - 0.2;
  }
  s.column[0] = s.row[0];
  return s;
}

void BM_MarionetteLift(benchmark::State& state) {
  const Setup s = MakeSetup(static_cast<int>(state.range(0)));
  for (auto _ : state)
    benchmark::DoNotOptimize(marionette::LiftMarionette(s.plan, s.row, s.column).data());
  state.counters["faces"] = s.plan.rows * s.plan.cols;
}
BENCHMARK(BM_MarionetteLift)->Arg(100)->Arg(1000)->Unit(benchmark::kMillisecond);

void BM_MarionetteLiftGP(benchmark::State& state) {
  const Setup s = MakeSetup(static_cast<int>(state.range(0)));
  std::vector<marionette::MarionetteTarget> guides;
  for (int j = 0; j <= s.plan.cols; ++j) guides.push_back({s.plan.Vertex(0, j), s.row[j]});
  for (int i = 1; i <= s.plan.rows; ++i) guides.push_back({s.plan.Vertex(i, 0), s.column[i]});
  for (auto _ : state) {
    Problem problem = marionette::MakeMarionetteProblem(s.plan, guides, {}, 1.0, 0.0);
    Solve(marionette::MarionetteSolverOptions(), &problem);
    benchmark::DoNotOptimize(problem.x().data());
  }
  state.counters["faces"] = s.plan.rows * s.plan.cols;
}
BENCHMARK(BM_MarionetteLiftGP)->Arg(100)->Arg(1000)->Iterations(3)->Unit(benchmark::kMillisecond);

}  // namespace
}  // namespace gproj
