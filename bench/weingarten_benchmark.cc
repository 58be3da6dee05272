// One guided-projection iteration of the Weingarten problem at every size of 003 Table 2
// (control points × samples, bi-degree, geodesic parallel auxiliaries for Figs. 4c and 9c),
// on a freeform surface of that size. The paper's Python implementation took the seconds per
// iteration in `paper_s` (i7-10750H); `iteration_s` is gproj's mean over 3 iterations
// (assembly + factorisation + solve; the one-off symbolic analysis is in analysis_ms).
//   BM_WeingartenIteration/<row of Table 2>
// The Fig. 3 solve (preset fig3, the fixed relation H = −0.1 on the surface, monotone steps with
// the auxiliaries reset after each step) at Table 2's Fig. 3 size, with the 12 auxiliaries per
// sample (/1) and with the control points as the only unknowns (/0): 5 iterations, the
// per-iteration time includes the merit assembly and any rejected steps.
//   BM_WeingartenFig3Iteration/<auxiliaries>
#include <benchmark/benchmark.h>

#include "bench/solver_counters.h"
#include "gproj/problems/weingarten/weingarten.h"
#include "gproj/problems/weingarten/weingarten_options.h"

namespace gproj {
namespace {

struct TableRow {
  const char* figure;
  int nu, nv, degree, su, sv;
  bool geodesic;
  int paper_variables;
  double paper_seconds;
};

constexpr TableRow kTable2[] = {
    {"1", 14, 14, 4, 28, 28, false, 9996, 3.32},
    {"2", 18, 18, 4, 36, 36, false, 16525, 5.71},
    {"3", 25, 25, 4, 50, 50, false, 31875, 52.04},
    {"4b", 20, 18, 4, 40, 36, false, 18360, 10.89},
    {"4c", 16, 10, 5, 32, 20, true, 13280, 1.71},
    {"6e", 25, 18, 4, 50, 36, false, 26406, 14.15},
    {"6b", 10, 8, 4, 20, 16, false, 5616, 0.32},
    {"6c", 14, 10, 4, 28, 20, false, 9060, 0.83},
    {"6d", 18, 14, 4, 36, 28, false, 15540, 3.26},
    {"7", 6, 8, 4, 18, 24, false, 2448, 0.39},
    {"8b", 16, 20, 3, 48, 60, false, 35520, 15.71},
    {"8c", 16, 20, 4, 48, 60, false, 35520, 15.82},
    {"9b", 8, 10, 4, 16, 20, false, 4080, 0.44},
    {"9c", 8, 10, 4, 16, 20, true, 6640, 0.47},
    {"10a", 35, 12, 4, 70, 24, false, 21420, 17.36},
    {"10b", 40, 12, 4, 80, 24, false, 24480, 25.56},
    {"10c", 40, 15, 4, 80, 30, false, 33480, 57.27},
    {"13top", 16, 20, 4, 32, 40, false, 16320, 8.40},
    {"13bot", 20, 30, 4, 40, 60, false, 30600, 48.25},
    {"12", 10, 10, 4, 20, 20, false, 5100, 0.59},
};

void BM_WeingartenIteration(benchmark::State& state) {
  const TableRow& row = kTable2[state.range(0)];
  state.SetLabel(std::string("Fig. ") + row.figure);
  weingarten::WeingartenOptions o = weingarten::WeingartenPreset(row.geodesic ? "fig4c" : "fig1");
  o.samples_u = row.su;
  o.samples_v = row.sv;
  o.solver.max_iterations = 3;
  SolverSummary summary;
  for (auto _ : state) {
    weingarten::WeingartenProblem problem(MakeWavyBSpline(row.nu, row.nv, row.degree), o);
    summary = problem.Run().summary;
  }
  const PhaseMeans m = SetSolverCounters(summary, &state);
  state.counters["iteration_s"] = m.assembly + m.factorization + m.solve;
  state.counters["paper_s"] = row.paper_seconds;
  state.counters["paper_variables"] = row.paper_variables;
}
BENCHMARK(BM_WeingartenIteration)
    ->DenseRange(0, sizeof(kTable2) / sizeof(kTable2[0]) - 1)
    ->Iterations(1)
    ->Unit(benchmark::kSecond);

void BM_WeingartenFig3Iteration(benchmark::State& state) {
  const BSplineSurface bump = MakeBumpBSpline(25);
  weingarten::WeingartenOptions o = weingarten::WeingartenPreset("fig3");
  o.fixed_linear_relation = true;
  o.linear_coefficients = Eigen::Vector3d(1.0, 0.0, 0.1);
  o.curvature_auxiliaries = state.range(0) != 0;
  o.solver.max_iterations = 5;
  SolverSummary summary;
  for (auto _ : state) {
    weingarten::WeingartenProblem problem(bump, o);
    summary = problem.Run().summary;
  }
  state.SetLabel(o.curvature_auxiliaries ? "Fig. 3, auxiliaries" : "Fig. 3, control points only");
  const PhaseMeans m = SetSolverCounters(summary, &state);
  state.counters["iteration_s"] = m.assembly + m.factorization + m.solve;
  state.counters["paper_s"] = 52.04;
}
BENCHMARK(BM_WeingartenFig3Iteration)->Arg(1)->Arg(0)->Iterations(1)->Unit(benchmark::kSecond);

}  // namespace
}  // namespace gproj
