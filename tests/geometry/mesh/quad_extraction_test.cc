#include "gproj/geometry/mesh/quad_extraction.h"

#include <gtest/gtest.h>

#include <Eigen/Geometry>
#include <cmath>
#include <cstdio>
#include <random>

#include "triangulated_surface_util.h"

namespace gproj {
namespace {

// The unit square as an n × n grid of cells, each split along a random diagonal.
PolyMesh SquareTriangles(int n, unsigned seed) {
  std::vector<Eigen::Vector2d> uv;
  return Triangulate([](double x, double y) { return Eigen::Vector3d(x, y, 0.0); }, 0, 1, 0, 1, n,
                     &uv, seed, 0.0);
}

Eigen::Matrix2d QuarterTurn() {
  Eigen::Matrix2d r;
  r << 0, -1, 1, 0;
  return r;
}

// The map (x, y) / h, with the faces right of x = ½ in a chart turned by a quarter turn and
// moved by an integer translation, and the transitions across x = ½ set accordingly.
IntegerGridMap SquareMap(const PolyMesh& mesh, double h, bool seam) {
  IntegerGridMap map;
  const Eigen::Vector2d shift(3, -2);
  for (auto f : mesh.faces()) {
    std::array<Eigen::Vector2d, 3> uv;
    double cx = 0.0;
    int k = 0;
    for (auto v : mesh.fv_range(f)) {
      uv[k++] = Eigen::Vector2d(mesh.point(v)[0], mesh.point(v)[1]) / h;
      cx += mesh.point(v)[0] / 3.0;
    }
    if (seam && cx > 0.5)
      for (auto& x : uv) x = QuarterTurn() * x + shift;
    map.corner_uv.push_back(uv);
  }
  map.halfedge_rotation.assign(mesh.n_halfedges(), 0);
  if (seam)
    for (auto h : mesh.halfedges()) {
      if (mesh.is_boundary(mesh.edge_handle(h))) continue;
      const double x0 = mesh.point(mesh.from_vertex_handle(h))[0];
      const double x1 = mesh.point(mesh.to_vertex_handle(h))[0];
      if (x0 != 0.5 || x1 != 0.5) continue;
      double cx = 0.0;
      for (auto v : mesh.fv_range(mesh.face_handle(h))) cx += mesh.point(v)[0] / 3.0;
      map.halfedge_rotation[h.idx()] = cx < 0.5 ? 1 : 3;
    }
  return map;
}

void ExpectUnitGrid(const QuadExtraction& q, double h, int cells) {
  EXPECT_EQ(q.quads.n_faces(), static_cast<size_t>(cells * cells));
  EXPECT_EQ(q.quads.n_vertices(), static_cast<size_t>((cells + 1) * (cells + 1)));
  EXPECT_EQ(q.folded_triangles, 0);
  for (auto f : q.quads.faces()) {
    ASSERT_EQ(q.quads.valence(f), 4u);
    std::vector<Eigen::Vector3d> p;
    for (auto v : q.quads.fv_range(f)) p.emplace_back(q.quads.point(v).data());
    for (int k = 0; k < 4; ++k) EXPECT_NEAR((p[(k + 1) % 4] - p[k]).norm(), h, 1e-9);
    EXPECT_GT((p[1] - p[0]).cross(p[2] - p[1]).z(), 0.0);  // counter-clockwise, as the input
  }
  for (auto v : q.quads.vertices())
    if (!q.quads.is_boundary(v)) EXPECT_EQ(q.quads.valence(v), 4u);
  EXPECT_EQ(q.edges.size(), static_cast<size_t>(2 * cells * (cells + 1)));
}

TEST(QuadExtractionTest, GridOfASquareMap) {
  const PolyMesh mesh = SquareTriangles(10, 3);
  ExpectUnitGrid(ExtractQuads(mesh, SquareMap(mesh, 0.125, false)), 0.125, 8);
  ExpectUnitGrid(ExtractQuads(mesh, SquareMap(mesh, 0.05, false)), 0.05, 20);
}

// The same grid through a seam whose charts differ by a quarter turn and a translation: the
// iso-lines are traced across it by the transitions.
TEST(QuadExtractionTest, GridAcrossASeam) {
  const PolyMesh mesh = SquareTriangles(10, 5);
  ExpectUnitGrid(ExtractQuads(mesh, SquareMap(mesh, 0.125, true)), 0.125, 8);
  ExpectUnitGrid(ExtractQuads(mesh, SquareMap(mesh, 0.05, true)), 0.05, 20);
}

TEST(QuadExtractionTest, RefusesAMapOfAnotherMesh) {
  const PolyMesh mesh = SquareTriangles(4, 1);
  IntegerGridMap map = SquareMap(mesh, 0.25, false);
  map.corner_uv.pop_back();
  EXPECT_THROW(ExtractQuads(mesh, map), InputError);
}

}  // namespace
}  // namespace gproj
