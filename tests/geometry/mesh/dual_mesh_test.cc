// The dual polygon mesh of generated triangle meshes (triangular lattices over surfaces of
// positive, negative, zero and parabolic curvature) and the polygon measures it is judged by.
#include "gproj/geometry/mesh/dual_mesh.h"

#include <gtest/gtest.h>

#include <Eigen/Geometry>
#include <algorithm>
#include <array>
#include <cmath>
#include <functional>
#include <set>

#include "gproj/common/input_error.h"
#include "gproj/geometry/mesh/polygon_shape.h"
#include "gproj/geometry/mesh/quad_shape.h"

namespace gproj {
namespace {

using Height = std::function<double(double, double)>;

// A triangular lattice of n × n vertices (rows shifted by half a spacing, so that every interior
// vertex has valence 6) of spacing h over z = height(x, y).
PolyMesh Lattice(int n, double h, const Height& height) {
  PolyMesh mesh;
  std::vector<PolyMesh::VertexHandle> v;
  for (int j = 0; j < n; ++j)
    for (int i = 0; i < n; ++i) {
      const double x = (i + 0.5 * j - 0.75 * n) * h, y = j * h * std::sqrt(3.0) / 2 - 0.4 * n * h;
      v.push_back(mesh.add_vertex(PolyMesh::Point(x, y, height(x, y))));
    }
  for (int j = 0; j + 1 < n; ++j)
    for (int i = 0; i + 1 < n; ++i) {
      const auto a = v[j * n + i], b = v[j * n + i + 1], c = v[(j + 1) * n + i],
                 d = v[(j + 1) * n + i + 1];
      mesh.add_face(a, b, c);
      mesh.add_face(b, d, c);
    }
  return mesh;
}

int InteriorVertices(const PolyMesh& mesh) {
  int n = 0;
  for (auto v : mesh.vertices()) n += mesh.is_boundary(v) ? 0 : 1;
  return n;
}

double Area(const PolyMesh& mesh) {
  double area = 0.0;
  for (auto f : mesh.faces()) {
    const std::vector<Eigen::Vector3d> p = FacePoints(mesh, f);
    Eigen::Vector3d a = Eigen::Vector3d::Zero();
    for (size_t i = 0; i < p.size(); ++i) a += p[i].cross(p[(i + 1) % p.size()]);
    area += 0.5 * a.norm();
  }
  return area;
}

Eigen::Vector3d UpNormalAt(const Height& height, double x, double y) {
  const double e = 1e-6;
  const double zx = (height(x + e, y) - height(x - e, y)) / (2 * e);
  const double zy = (height(x, y + e) - height(x, y - e)) / (2 * e);
  return Eigen::Vector3d(-zx, -zy, 1.0).normalized();
}

// Convex and negatively curved, not quadratic (on an isotropic quadratic bowl the centroid
// dual of a regular lattice is planar already).
const Height kBowl = [](double x, double y) { return std::sqrt(4.0 - x * x - y * y); };
const Height kSaddle = [](double x, double y) {
  return 0.3 * x * x - 0.15 * y * y + 0.05 * x * x * x;
};
const Height kTrough = [](double x, double) { return 0.4 * x * x; };  // a parabolic cylinder
const Height kFlat = [](double, double) { return 0.0; };

// Interior vertices of valence 6 become hexagons, one face per interior vertex, oriented as the
// triangles are (their normals point up as the input's do).
TEST(DualMeshTest, OneFacePerInteriorVertexOrientedAsTheInput) {
  const PolyMesh mesh = Lattice(12, 0.1, kBowl);
  const PolyMesh dual = DualMesh(mesh, {});
  EXPECT_EQ(static_cast<int>(dual.n_faces()), InteriorVertices(mesh));
  const PolygonMeshSummary s = SummarizePolygons(dual);
  ASSERT_GE(s.faces_by_corners.size(), 7u);
  EXPECT_GT(s.faces_by_corners[6], 0);
  int counted = 0;
  for (int n : s.faces_by_corners) counted += n;
  EXPECT_EQ(counted, static_cast<int>(dual.n_faces()));
  for (auto f : dual.faces()) {
    const std::vector<Eigen::Vector3d> p = FacePoints(dual, f);
    Eigen::Vector3d centre = Eigen::Vector3d::Zero();
    for (const auto& q : p) centre += q / p.size();
    EXPECT_GT(PolygonNormal(p).dot(UpNormalAt(kBowl, centre.x(), centre.y())), 0.9)
        << "face " << f.idx();
  }
  // Every dual vertex is a triangle's centroid.
  std::vector<Eigen::Vector3d> centroids;
  for (auto f : mesh.faces()) {
    Eigen::Vector3d c = Eigen::Vector3d::Zero();
    for (const auto& q : FacePoints(mesh, f)) c += q / 3.0;
    centroids.push_back(c);
  }
  for (auto v : dual.vertices()) {
    const auto& q = dual.point(v);
    double nearest = INFINITY;
    for (const Eigen::Vector3d& c : centroids)
      nearest = std::min(nearest, (c - Eigen::Vector3d(q[0], q[1], q[2])).norm());
    EXPECT_LT(nearest, 1e-12) << "vertex " << v.idx();
  }
}

// Kept boundary faces tile the triangle mesh's region exactly: in the plane the dual's area is
// the input's, and its border runs along the input's.
TEST(DualMeshTest, KeptBoundaryFacesTileTheInputsRegion) {
  const PolyMesh mesh = Lattice(9, 0.25, kFlat);
  DualOptions options;
  options.boundary = DualBoundary::kKeep;
  DualStats stats;
  const PolyMesh dual = DualMesh(mesh, options, &stats);
  EXPECT_EQ(dual.n_faces(), mesh.n_vertices());
  EXPECT_EQ(stats.boundary_faces, static_cast<int>(mesh.n_vertices()) - InteriorVertices(mesh));
  EXPECT_NEAR(Area(dual), Area(mesh), 1e-12 * Area(mesh));
  for (auto f : dual.faces()) EXPECT_GT(PolygonNormal(FacePoints(dual, f)).z(), 0.99);
  // A manifold mesh with one border.
  std::set<int> border;
  for (auto h : dual.halfedges())
    if (dual.is_boundary(h)) border.insert(dual.to_vertex_handle(h).idx());
  int loops = 0;
  std::vector<bool> seen(dual.n_halfedges(), false);
  for (auto h : dual.halfedges()) {
    if (!dual.is_boundary(h) || seen[h.idx()]) continue;
    ++loops;
    for (auto g = h; !seen[g.idx()]; g = dual.next_halfedge_handle(g)) seen[g.idx()] = true;
  }
  EXPECT_EQ(loops, 1);
  // The lattice's four corners are corners of the dual; where the boundary runs straight the
  // boundary vertices are left out (no 180° corners), and every face is convex.
  int corners = 0;
  for (auto v : mesh.vertices()) {
    if (!mesh.is_boundary(v) || mesh.valence(v) > 3) continue;
    ++corners;
    const auto& p = mesh.point(v);
    bool found = false;
    for (int b : border) found = found || (dual.point(dual.vertex_handle(b)) - p).norm() == 0.0;
    EXPECT_TRUE(found) << "corner " << v.idx();
  }
  EXPECT_EQ(corners, 4);
  EXPECT_EQ(SummarizePolygons(dual).non_convex, 0);
}

// Where the tangent planes meet, every dual vertex around a vertex lies on its tangent plane:
// on a bowl (K > 0) the faces are planar and convex; on a saddle (K < 0) the faces whose
// triangles' planes all meet near them are planar, but some are not convex, and where the
// planes meet far away (along the asymptotic directions) the vertex stays at the centroid.
TEST(DualMeshTest, TangentPlaneStartIsPlanarConvexOnABowlAndNotOnASaddle) {
  DualOptions tangent;
  tangent.start = DualStart::kTangentPlanes;
  DualStats stats;
  const PolyMesh bowl = Lattice(16, 0.08, kBowl);
  const PolygonMeshSummary bowl_centroids = SummarizePolygons(DualMesh(bowl, {}));
  const PolygonMeshSummary bowl_planes = SummarizePolygons(DualMesh(bowl, tangent, &stats));
  EXPECT_EQ(stats.tangent_plane_vertices, static_cast<int>(bowl.n_faces()));
  EXPECT_EQ(stats.rank_deficient, 0);
  EXPECT_GT(bowl_centroids.max_planarity, 1e-4);
  EXPECT_LT(bowl_planes.max_planarity, 1e-12);
  EXPECT_EQ(bowl_centroids.non_convex, 0);
  EXPECT_EQ(bowl_planes.non_convex, 0);

  const PolyMesh saddle = Lattice(16, 0.08, kSaddle);
  const PolyMesh dual = DualMesh(saddle, tangent, &stats);
  const PolygonMeshSummary saddle_planes = SummarizePolygons(dual);
  EXPECT_EQ(stats.tangent_plane_vertices + stats.held_within_reach,
            static_cast<int>(saddle.n_faces()));
  EXPECT_GT(saddle_planes.non_convex, 0);
  // Along the boundary, where the normals are one-sided, some planes meet too far away; the
  // faces there are not planar, but flatter than the centroids'.
  EXPECT_GT(stats.held_within_reach, 0);
  EXPECT_LT(saddle_planes.max_planarity,
            0.5 * SummarizePolygons(DualMesh(saddle, {})).max_planarity);
}

// On a parabolic cylinder the three planes share a line (the ruling) inside, and the dual vertex
// is its point nearest the centroid; along the boundary, where the normals are one-sided, they
// meet far away. On a plane the planes coincide and the point nearest the centroid is the
// centroid.
TEST(DualMeshTest, TangentPlanesThatShareALineOrCoincide) {
  DualOptions tangent;
  tangent.start = DualStart::kTangentPlanes;
  DualStats stats;
  const PolyMesh trough = Lattice(12, 0.1, kTrough);
  const PolygonMeshSummary s = SummarizePolygons(DualMesh(trough, tangent, &stats));
  const PolygonMeshSummary c = SummarizePolygons(DualMesh(trough, {}));
  EXPECT_GT(stats.rank_deficient, 0);     // inside: the planes share the ruling
  EXPECT_GT(stats.held_within_reach, 0);  // along the boundary: they meet far away
  EXPECT_LT(s.max_planarity, c.max_planarity);
  const PolyMesh flat = Lattice(8, 0.1, kFlat);
  const PolyMesh at_planes = DualMesh(flat, tangent, &stats), at_centroids = DualMesh(flat, {});
  EXPECT_EQ(stats.rank_deficient, static_cast<int>(flat.n_faces()));
  ASSERT_EQ(at_planes.n_vertices(), at_centroids.n_vertices());
  for (auto v : at_planes.vertices())
    EXPECT_LT((at_planes.point(v) - at_centroids.point(v)).norm(), 1e-12);
}

// On a sphere, the tangent planes of a triangle's vertices meet above its circumcentre, and the
// two right triangles of a split square (nearly) share theirs: their dual vertices would
// (nearly) coincide. Those stay at their centroids, so no dual edge has (nearly) no length.
TEST(DualMeshTest, TangentPlanesMeetingInOnePointLeaveNoZeroLengthEdge) {
  PolyMesh mesh;
  const int n = 10;
  std::vector<PolyMesh::VertexHandle> v;
  for (int i = 0; i <= n; ++i)
    for (int j = 0; j <= n; ++j) {
      const double x = -0.5 + static_cast<double>(i) / n, y = -0.5 + static_cast<double>(j) / n;
      v.push_back(mesh.add_vertex(PolyMesh::Point(x, y, kBowl(x, y))));
    }
  for (int i = 0; i < n; ++i)
    for (int j = 0; j < n; ++j) {
      const int a = i * (n + 1) + j, b = a + n + 1;
      mesh.add_face(v[a], v[b], v[b + 1]);
      mesh.add_face(v[a], v[b + 1], v[a + 1]);
    }
  DualOptions tangent;
  tangent.start = DualStart::kTangentPlanes;
  DualStats stats;
  const PolyMesh dual = DualMesh(mesh, tangent, &stats);
  EXPECT_GT(stats.coincident, 0);
  double shortest = INFINITY;
  for (auto e : dual.edges()) shortest = std::min(shortest, dual.calc_edge_length(e));
  EXPECT_GT(shortest, 0.005 / n);
}

// Inputs it cannot take: a face that is not a triangle (named), no interior vertex.
TEST(DualMeshTest, RefusesNonTrianglesAndMeshesWithoutInteriorVertices) {
  PolyMesh quad;
  std::vector<PolyMesh::VertexHandle> v;
  for (int i = 0; i < 4; ++i) v.push_back(quad.add_vertex(PolyMesh::Point(i % 2, i / 2, 0)));
  quad.add_face(v[0], v[1], v[3], v[2]);
  try {
    DualMesh(quad, {});
    ADD_FAILURE() << "a quad was accepted";
  } catch (const InputError& e) {
    EXPECT_STREQ(e.what(), "face 0 has 4 vertices; the dual is taken of a triangle mesh");
  }
  PolyMesh strip = Lattice(2, 1.0, kFlat);  // two triangles, all vertices on the boundary
  try {
    DualMesh(strip, {});
    ADD_FAILURE() << "a dual without faces was returned";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("no interior vertex"), std::string::npos) << e.what();
  }
  DualOptions keep;
  keep.boundary = DualBoundary::kKeep;
  EXPECT_EQ(DualMesh(strip, keep).n_faces(), 4u);
}

// The polygon measures: a quad's are quad_shape.h's; a skew hexagon's planarity is twice its
// corners' largest distance from their plane; a reflex corner makes it non-convex.
TEST(PolygonShapeTest, PlanarityAndConvexityOfPolygons) {
  std::vector<Eigen::Vector3d> hexagon;
  for (int i = 0; i < 6; ++i)
    hexagon.emplace_back(std::cos(i * M_PI / 3), std::sin(i * M_PI / 3), i % 2 ? 0.01 : -0.01);
  PolygonShape s = MeasurePolygonShape(hexagon);
  EXPECT_NEAR(s.planarity, 0.02, 1e-12);
  EXPECT_TRUE(s.convex);
  EXPECT_NEAR(s.min_angle_deg, 120.0, 0.1);
  EXPECT_GT(PolygonNormal(hexagon).z(), 0.99);  // counter-clockwise seen from +z
  std::reverse(hexagon.begin(), hexagon.end());
  EXPECT_LT(PolygonNormal(hexagon).z(), -0.99);
  // A dart: one corner pushed in past the centre.
  std::vector<Eigen::Vector3d> dart = {{0, 0, 0}, {2, 0, 0}, {2, 2, 0}, {1, 0.5, 0}, {0, 2, 0}};
  s = MeasurePolygonShape(dart);
  EXPECT_FALSE(s.convex);
  EXPECT_EQ(s.planarity, 0.0);
  EXPECT_GT(s.min_angle_deg, 0.0);
  const std::vector<Eigen::Vector3d> quad = {{0, 0, 0}, {1, 0, 0.1}, {1, 1, 0}, {0, 1, 0.1}};
  EXPECT_EQ(MeasurePolygonShape(quad).planarity,
            DiagonalDistance(quad[0], quad[1], quad[2], quad[3]));
  EXPECT_EQ(FaceCountsText({0, 0, 0, 2, 1, 0, 12}), "12 hexagons, 1 quad, 2 triangles");
}

}  // namespace
}  // namespace gproj
