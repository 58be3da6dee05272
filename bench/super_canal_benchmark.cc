// Combescure transformations of n × n-face circular grids (a surface of revolution).
//   BM_CombescurePropagation/n  000 eq. 4, linear time (input checks and mesh copy included)
//   BM_CombescureGP/n           the same by guided projection on edge-parallelism rows
//                               (problem setup, analysis and factorisations included)
//   BM_CyclidicSurface/n/s      the smooth cyclidic surface (000 §2.2) of the n × n grid: s fine
//                               quads per arc, the tangent-plane measure included
//   BM_CyclidicFrameFairing/n   the frame at vertex 0 minimising 000 eq. 5 (Ceres BFGS)
#include <benchmark/benchmark.h>

#include <cmath>

#include "gproj/geometry/mesh/parametric_grid.h"
#include "gproj/problems/circular/combescure.h"
#include "gproj/problems/circular/cyclidic_surface.h"

namespace gproj {
namespace {

struct Setup {
  PolyMesh mesh;
  GridShape shape;
  circular::CombescureLengths lengths;
};

Setup MakeSetup(int n) {
  ParametricGridOptions o;
  o.nu = o.nv = n + 1;
  Setup s;
  s.mesh = MakeParametricGrid(RevolutionSurface, o);
  s.shape = DetectGridShape(s.mesh);
  s.lengths = circular::ReferenceLengths(s.mesh, s.shape);
  for (size_t j = 0; j < s.lengths.row.size(); ++j)
    s.lengths.row[j] *= 1.0 + 0.3 * std::sin(6.0 * j / n);
  return s;
}

void BM_CombescurePropagation(benchmark::State& state) {
  const Setup s = MakeSetup(static_cast<int>(state.range(0)));
  for (auto _ : state)
    benchmark::DoNotOptimize(
        circular::CombescureByPropagation(s.mesh, s.shape, s.lengths).n_vertices());
  state.counters["faces"] = s.shape.rows * s.shape.cols;
}
BENCHMARK(BM_CombescurePropagation)->Arg(100)->Arg(1000)->Unit(benchmark::kMillisecond);

void BM_CombescureGP(benchmark::State& state) {
  const Setup s = MakeSetup(static_cast<int>(state.range(0)));
  int iterations = 0;
  for (auto _ : state) {
    Problem problem = circular::MakeCombescureProblem(s.mesh, s.shape, s.lengths);
    const SolverSummary summary = Solve(circular::CombescureSolverDefaults(), &problem);
    iterations = summary.num_steps();
    benchmark::DoNotOptimize(problem.x().data());
  }
  state.counters["faces"] = s.shape.rows * s.shape.cols;
  state.counters["iterations"] = iterations;
}
BENCHMARK(BM_CombescureGP)->Arg(100)->Arg(200)->Unit(benchmark::kMillisecond);

std::vector<Eigen::Vector3d> Points(const PolyMesh& mesh) {
  std::vector<Eigen::Vector3d> points;
  for (auto v : mesh.vertices()) {
    const auto& p = mesh.point(v);
    points.emplace_back(p[0], p[1], p[2]);
  }
  return points;
}

void BM_CyclidicSurface(benchmark::State& state) {
  const Setup s = MakeSetup(static_cast<int>(state.range(0)));
  const std::vector<Eigen::Vector3d> points = Points(s.mesh);
  const circular::CyclidicNet net = circular::MakeCyclidicNet(
      s.shape, points,
      circular::GridStartFrame(s.shape, points, circular::DefaultGridAngles(s.shape, points)));
  circular::CyclidicSurfaceOptions options;
  options.segments = static_cast<int>(state.range(1));
  size_t quads = 0;
  for (auto _ : state) quads = circular::MeshCyclidicSurface(net, options).mesh.n_faces();
  state.counters["patches"] = s.shape.rows * s.shape.cols;
  state.counters["fine_quads"] = static_cast<double>(quads);
}
BENCHMARK(BM_CyclidicSurface)
    ->Args({20, 8})
    ->Args({100, 8})
    ->Args({20, 32})
    ->Unit(benchmark::kMillisecond);

void BM_CyclidicFrameFairing(benchmark::State& state) {
  const Setup s = MakeSetup(static_cast<int>(state.range(0)));
  const std::vector<Eigen::Vector3d> points = Points(s.mesh);
  int iterations = 0;
  for (auto _ : state)
    iterations =
        circular::FairGridFrame(s.shape, points, circular::DefaultGridAngles(s.shape, points))
            .iterations;
  state.counters["edges"] = 2 * s.shape.rows * (s.shape.cols + 1);
  state.counters["iterations"] = iterations;
}
BENCHMARK(BM_CyclidicFrameFairing)->Arg(20)->Arg(100)->Unit(benchmark::kMillisecond);

}  // namespace
}  // namespace gproj
