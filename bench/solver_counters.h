#pragma once
// Benchmark counters from a solver summary: sizes and the mean per-iteration time of each phase.

#include <benchmark/benchmark.h>

#include "gproj/solver/guided_projection.h"

namespace gproj {

struct PhaseMeans {
  double assembly = 0.0, factorization = 0.0, solve = 0.0;  // seconds per iteration
};

// Sets variables, factored, nnz_J, nnz_L, analysis_ms, assembly_ms, factor_ms, solve_ms.
inline PhaseMeans SetSolverCounters(const SolverSummary& summary, benchmark::State* state) {
  PhaseMeans m;
  const int steps = summary.num_steps();
  for (int k = 1; k <= steps; ++k) {
    m.assembly += summary.iterations[k].assembly_seconds / steps;
    m.factorization += summary.iterations[k].factorization_seconds / steps;
    m.solve += summary.iterations[k].solve_seconds / steps;
  }
  state->counters["variables"] = summary.num_variables;
  state->counters["factored"] = summary.num_variables - summary.eliminated_variables;
  state->counters["nnz_J"] = static_cast<double>(summary.jacobian_nonzeros);
  state->counters["nnz_L"] = static_cast<double>(summary.factor_nonzeros);
  state->counters["analysis_ms"] = 1e3 * summary.analysis_seconds;
  state->counters["assembly_ms"] = 1e3 * m.assembly;
  state->counters["factor_ms"] = 1e3 * m.factorization;
  state->counters["solve_ms"] = 1e3 * m.solve;
  return m;
}

}  // namespace gproj
