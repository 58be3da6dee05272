#include "geometry/quad_grid.h"

#include <random>
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
      PolyMesh::Point p(x, y, o.a * x * x + o.b * y * y + o.c * x * y);
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
