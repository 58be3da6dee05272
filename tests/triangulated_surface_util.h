#pragma once
// Irregular triangle meshes of parametric surfaces, for tests of curvature fields and remeshing.

#include <Eigen/Core>
#include <cmath>
#include <functional>
#include <random>
#include <vector>

#include "gproj/geometry/io/mesh_io.h"

namespace gproj {

using Surface = std::function<Eigen::Vector3d(double, double)>;

// The cell (a, b, c, d), counter-clockwise, as two triangles split along a–c or b–d.
inline void AddCell(PolyMesh::VertexHandle a, PolyMesh::VertexHandle b, PolyMesh::VertexHandle c,
                    PolyMesh::VertexHandle d, bool along_ac, PolyMesh* mesh) {
  if (along_ac) {
    mesh->add_face({a, b, c});
    mesh->add_face({a, c, d});
  } else {
    mesh->add_face({a, b, d});
    mesh->add_face({b, c, d});
  }
}

// An irregular triangle mesh of f over [u0, u1] × [v0, v1]: an n × n grid whose inner
// parameters are jittered by up to `jitter` of a cell, each cell split along a random diagonal.
// *uv receives every vertex's parameters.
inline PolyMesh Triangulate(const Surface& f, double u0, double u1, double v0, double v1, int n,
                            std::vector<Eigen::Vector2d>* uv, unsigned seed = 7,
                            double jitter_fraction = 0.3) {
  std::mt19937 random(seed);
  std::uniform_real_distribution<double> jitter(-jitter_fraction, jitter_fraction);
  PolyMesh mesh;
  std::vector<PolyMesh::VertexHandle> v;
  const double du = (u1 - u0) / n, dv = (v1 - v0) / n;
  for (int i = 0; i <= n; ++i)
    for (int j = 0; j <= n; ++j) {
      const bool inner = i > 0 && i < n && j > 0 && j < n;
      const double u = u0 + (i + (inner ? jitter(random) : 0.0)) * du;
      const double w = v0 + (j + (inner ? jitter(random) : 0.0)) * dv;
      uv->emplace_back(u, w);
      const Eigen::Vector3d p = f(u, w);
      v.push_back(mesh.add_vertex(PolyMesh::Point(p.x(), p.y(), p.z())));
    }
  std::bernoulli_distribution diagonal(0.5);
  for (int i = 0; i < n; ++i)
    for (int j = 0; j < n; ++j)
      AddCell(v[i * (n + 1) + j], v[(i + 1) * (n + 1) + j], v[(i + 1) * (n + 1) + j + 1],
              v[i * (n + 1) + j + 1], diagonal(random), &mesh);
  return mesh;
}

// An irregular triangle mesh of f, periodic in u over [0, 2π) (and in v over [v0, v1) when
// periodic_v): an nu × nv grid jittered by up to 0.3 of a cell, each cell split along a random
// diagonal. An annulus, or a torus.
inline PolyMesh TriangulatePeriodic(const Surface& f, int nu, int nv, double v0, double v1,
                                    unsigned seed, bool periodic_v = false) {
  std::mt19937 random(seed);
  std::uniform_real_distribution<double> jitter(-0.3, 0.3);
  PolyMesh mesh;
  const int rows = periodic_v ? nv : nv + 1;
  std::vector<PolyMesh::VertexHandle> v;
  for (int i = 0; i < nu; ++i)
    for (int j = 0; j < rows; ++j) {
      const bool inner = periodic_v || (j > 0 && j < nv);
      const double u = (i + jitter(random)) * 2 * M_PI / nu;
      const double w = v0 + (j + (inner ? jitter(random) : 0.0)) * (v1 - v0) / nv;
      const Eigen::Vector3d p = f(u, w);
      v.push_back(mesh.add_vertex(PolyMesh::Point(p.x(), p.y(), p.z())));
    }
  auto at = [&](int i, int j) { return v[(i % nu) * rows + (j % rows)]; };
  std::bernoulli_distribution diagonal(0.5);
  for (int i = 0; i < nu; ++i)
    for (int j = 0; j < nv; ++j)
      AddCell(at(i, j), at(i + 1, j), at(i + 1, j + 1), at(i, j + 1), diagonal(random), &mesh);
  return mesh;
}

}  // namespace gproj
