#include "gproj/geometry/mesh/quad_grid.h"

#include <cmath>
#include <random>
#include <string>
#include <vector>

namespace gproj {

PolyMesh MakeQuadGrid(const QuadGridOptions& o) {
  PolyMesh mesh;
  std::mt19937 rng(o.seed);
  std::uniform_real_distribution<double> jitter(-1.0, 1.0);
  const double h = 2.0 / (std::max(o.nu, o.nv) - 1);
  std::vector<PolyMesh::VertexHandle> v;
  v.reserve(static_cast<size_t>(o.nu) * o.nv);
  for (int i = 0; i < o.nu; ++i) {
    for (int j = 0; j < o.nv; ++j) {
      const double x = -1.0 + 2.0 * i / (o.nu - 1);
      const double y = -1.0 + 2.0 * j / (o.nv - 1);
      PolyMesh::Point p(x, y,
                        o.a * x * x + o.b * y * y + o.c * x * y +
                            o.wave * std::sin(M_PI * x) * std::sin(M_PI * y));
      for (int c = 0; c < 3; ++c) p[c] += o.noise * h * jitter(rng);
      v.push_back(mesh.add_vertex(p));
    }
  }
  for (int i = 0; i + 1 < o.nu; ++i)
    for (int j = 0; j + 1 < o.nv; ++j)
      mesh.add_face(
          {v[i * o.nv + j], v[(i + 1) * o.nv + j], v[(i + 1) * o.nv + j + 1], v[i * o.nv + j + 1]});
  return mesh;
}

}  // namespace gproj

namespace gproj {
namespace {

// Whether face f of `mesh` is the grid face (i, j) of `shape`, up to rotation and reversal.
bool IsGridFace(const PolyMesh& mesh, PolyMesh::FaceHandle f, const GridShape& shape) {
  const int i = f.idx() / shape.cols, j = f.idx() % shape.cols;
  const int expected[4] = {shape.Vertex(i, j), shape.Vertex(i + 1, j), shape.Vertex(i + 1, j + 1),
                           shape.Vertex(i, j + 1)};
  int got[4], k = 0;
  for (auto v : mesh.fv_range(f)) {
    if (k == 4) return false;
    got[k++] = v.idx();
  }
  if (k != 4) return false;
  for (int r = 0; r < 4; ++r) {
    bool same = true, reversed = true;
    for (int t = 0; t < 4; ++t) {
      same = same && got[(r + t) % 4] == expected[t];
      reversed = reversed && got[(r + 4 - t) % 4] == expected[t];
    }
    if (same || reversed) return true;
  }
  return false;
}

}  // namespace

GridShape DetectGridShape(const PolyMesh& mesh, const std::string& path) {
  const std::string prefix = path.empty() ? "" : path + ": ";
  // (N + 1)(M + 1) = V and N M = F give N + M = V − F − 1.
  const long v = static_cast<long>(mesh.n_vertices()), f = static_cast<long>(mesh.n_faces());
  const long sum = v - f - 1;
  const double disc = static_cast<double>(sum * sum - 4 * f);
  const long n = disc >= 0 ? std::lround((sum + std::sqrt(disc)) / 2) : -1;
  if (f == 0 || n <= 0 || n * (sum - n) != f)
    throw InputError(prefix + "not a regular quad grid (" + std::to_string(v) + " vertices, " +
                     std::to_string(f) + " faces)");
  int bad_face = -1;
  for (long rows : {n, sum - n}) {
    GridShape shape;
    shape.rows = static_cast<int>(rows);
    shape.cols = static_cast<int>(sum - rows);
    bad_face = -1;
    for (auto fh : mesh.faces())
      if (!IsGridFace(mesh, fh, shape)) {
        bad_face = fh.idx();
        break;
      }
    if (bad_face < 0) return shape;
  }
  throw InputError(prefix + "face " + std::to_string(bad_face) +
                   " is not in grid order: vertex (i, j) must have index i * (cols + 1) + j and "
                   "face (i, j) index i * cols + j");
}

}  // namespace gproj
