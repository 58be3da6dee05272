// Curvature direction fields of triangle meshes (004 §3.1): an n × n grid of the monkey saddle,
// each cell split in two (2 n² triangles: n = 100 gives 20k, n = 317 about 200k).
//   BM_DirectionField/n   jet fit at every vertex, asymptotic pair, singularity indices
//   BM_SmoothField/n      the smoothing solve (Knöppel et al. 2013) on the fitted field
//   BM_IntegerGridMap/n   the field-aligned seamless map of the remeshing (frames, cuts, two
//                         CHOLMOD solves), quads of 3 mean edges
//   BM_QuadExtraction/n   the quads traced along the map's integer iso-lines
#include <benchmark/benchmark.h>

#include "gproj/geometry/mesh/curvature_field.h"
#include "gproj/problems/remesh/quad_remeshing.h"

namespace gproj {
namespace {

PolyMesh MonkeySaddle(int n) {
  PolyMesh mesh;
  std::vector<PolyMesh::VertexHandle> v;
  for (int i = 0; i <= n; ++i)
    for (int j = 0; j <= n; ++j) {
      const double x = -1.0 + 2.0 * i / n, y = -1.0 + 2.0 * j / n;
      v.push_back(mesh.add_vertex(PolyMesh::Point(x, y, x * x * x - 3 * x * y * y)));
    }
  for (int i = 0; i < n; ++i)
    for (int j = 0; j < n; ++j) {
      const int a = i * (n + 1) + j, b = a + n + 1;
      mesh.add_face(v[a], v[b], v[b + 1]);
      mesh.add_face(v[a], v[b + 1], v[a + 1]);
    }
  return mesh;
}

void BM_DirectionField(benchmark::State& state) {
  const PolyMesh mesh = MonkeySaddle(static_cast<int>(state.range(0)));
  size_t singularities = 0;
  for (auto _ : state)
    singularities = EstimateDirectionField(mesh, DirectionKind::kAsymptotic).singularities.size();
  state.counters["triangles"] = static_cast<double>(mesh.n_faces());
  state.counters["singularities"] = static_cast<double>(singularities);
}
BENCHMARK(BM_DirectionField)->Arg(100)->Arg(317)->Iterations(1)->Unit(benchmark::kSecond);

void BM_SmoothField(benchmark::State& state) {
  const PolyMesh mesh = MonkeySaddle(static_cast<int>(state.range(0)));
  const std::vector<VertexCurvature> fit = FitVertexCurvatures(mesh);
  for (auto _ : state) benchmark::DoNotOptimize(SmoothPrincipalField(mesh, fit, 1.0).size());
  state.counters["triangles"] = static_cast<double>(mesh.n_faces());
}
BENCHMARK(BM_SmoothField)->Arg(100)->Arg(317)->Iterations(1)->Unit(benchmark::kSecond);

void BM_IntegerGridMap(benchmark::State& state) {
  const PolyMesh mesh = MonkeySaddle(static_cast<int>(state.range(0)));
  const remesh::QuadRemeshOptions options;
  const DirectionField field =
      EstimateDirectionField(mesh, options.directions, options.fit, options.smoothing);
  int folded = 0;
  for (auto _ : state) folded = remesh::ParametrizeAlongField(mesh, field, options).folded_faces;
  state.counters["triangles"] = static_cast<double>(mesh.n_faces());
  state.counters["folded"] = folded;
}
BENCHMARK(BM_IntegerGridMap)->Arg(100)->Arg(317)->Iterations(1)->Unit(benchmark::kSecond);

void BM_QuadExtraction(benchmark::State& state) {
  const PolyMesh mesh = MonkeySaddle(static_cast<int>(state.range(0)));
  const remesh::QuadRemeshOptions options;
  const DirectionField field =
      EstimateDirectionField(mesh, options.directions, options.fit, options.smoothing);
  const remesh::FieldParametrization map = remesh::ParametrizeAlongField(mesh, field, options);
  size_t quads = 0;
  for (auto _ : state) quads = ExtractQuads(mesh, map.map).quads.n_faces();
  state.counters["triangles"] = static_cast<double>(mesh.n_faces());
  state.counters["quads"] = static_cast<double>(quads);
}
BENCHMARK(BM_QuadExtraction)->Arg(100)->Arg(317)->Iterations(1)->Unit(benchmark::kSecond);

}  // namespace
}  // namespace gproj
