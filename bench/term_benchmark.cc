// Assembly of quad planarity on an n × n-vertex grid, per guided-projection iteration:
//   BM_QuadPlanarityAssembly/n/0   a hand-written Jacobian (the family as gproj had it before
//                                  terms; kept here as the baseline)
//   BM_QuadPlanarityAssembly/n/1   automatic derivatives per evaluation (ceres::Jet)
//   BM_QuadPlanarityAssembly/n/2   QuadPlanarity: the term declared quadratic (coefficients
//                                  read off once per solve)
// Each iteration is one LinearizedSystem::Assemble: update, evaluation, scatter into A.
#include <benchmark/benchmark.h>

#include <algorithm>
#include <array>
#include <memory>
#include <random>

#include "gproj/constraints/quad_planarity.h"
#include "gproj/solver/internal/linearized_system.h"

namespace gproj {
namespace {

// Quad planarity with its Jacobian written out by hand.
class HandWrittenQuadPlanarity : public ConstraintFamily {
 public:
  HandWrittenQuadPlanarity() : ConstraintFamily("planarity", 5) {}
  int Add(const std::array<int, 5>& items) { return AddElement(items.data(), 5); }
  void EvaluateElement(int, const double* x, double* phi, double* jac) const override {
    constexpr int kDim = 15;
    std::fill(jac, jac + 5 * kDim, 0.0);
    const double* n = x;
    for (int j = 0; j < 4; ++j) {
      const double* a = x + 3 + 3 * j;
      const double* b = x + 3 + 3 * ((j + 1) % 4);
      double* row = jac + j * kDim;
      phi[j] = 0.0;
      for (int c = 0; c < 3; ++c) {
        phi[j] += n[c] * (b[c] - a[c]);
        row[c] = b[c] - a[c];
        row[3 + 3 * j + c] = -n[c];
        row[3 + 3 * ((j + 1) % 4) + c] = n[c];
      }
    }
    phi[4] = n[0] * n[0] + n[1] * n[1] + n[2] * n[2] - 1.0;
    for (int c = 0; c < 3; ++c) jac[4 * kDim + c] = 2.0 * n[c];
  }
  bool RowTouches(int, int row, int local) const override {
    if (local < 3) return true;
    if (row == 4) return false;
    const int vertex = (local - 3) / 3;
    return vertex == row || vertex == (row + 1) % 4;
  }
};

template <typename Family>
void AddQuads(int n, Problem* problem, Family* family) {
  const VariableLayout& layout = problem->layout();
  for (int i = 0; i + 1 < n; ++i)
    for (int j = 0; j + 1 < n; ++j)
      family->Add({layout.Item(1, i * (n - 1) + j), layout.Item(0, i * n + j),
                   layout.Item(0, i * n + j + 1), layout.Item(0, (i + 1) * n + j + 1),
                   layout.Item(0, (i + 1) * n + j)});
}

void BM_QuadPlanarityAssembly(benchmark::State& state) {
  const int n = static_cast<int>(state.range(0));
  const int form = static_cast<int>(state.range(1));
  Problem problem;
  problem.layout().AddBlock("vertices", n * n, 3);
  problem.layout().AddBlock("normals", (n - 1) * (n - 1), 3, /*eliminable=*/true);
  problem.ResizeToLayout();
  std::mt19937 rng(1);
  std::uniform_real_distribution<double> noise(-0.05, 0.05);
  for (int i = 0; i < n; ++i)
    for (int j = 0; j < n; ++j)
      problem.x().segment<3>(3 * (i * n + j)) << i + noise(rng), j + noise(rng), noise(rng);
  problem.x().tail(3 * (n - 1) * (n - 1)).setZero();
  for (int f = 0; f < (n - 1) * (n - 1); ++f) problem.x()[3 * n * n + 3 * f + 2] = 1.0;
  if (form == 0)
    AddQuads(n, &problem, problem.AddFamily<HandWrittenQuadPlanarity>());
  else if (form == 1)
    AddQuads(n, &problem,
             problem.AddFamily<QuadPlanarityTerm>("planarity", QuadPlanarityResidual{}));
  else
    AddQuads(n, &problem, problem.AddFamily<QuadPlanarity>());
  LinearizedSystem system(&problem);
  std::string why;
  for (auto _ : state) {
    if (!system.Assemble(problem.x(), 0.1, 1.0, &why)) state.SkipWithError(why.c_str());
    benchmark::DoNotOptimize(system.a().values.data());
  }
  state.counters["quads"] = (n - 1) * (n - 1);
  state.counters["nnz_J"] = system.a().nnz();
  state.SetLabel(form == 0 ? "hand-written" : form == 1 ? "automatic" : "automatic, quadratic");
}
BENCHMARK(BM_QuadPlanarityAssembly)
    ->ArgsProduct({{51, 201}, {0, 1, 2}})
    ->Unit(benchmark::kMillisecond);

}  // namespace
}  // namespace gproj
