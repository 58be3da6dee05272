// A-nets on the diagonals (anet --net diagonal): each vertex's star made of the corners opposite
// it in its quads, on generated meshes whose diagonals follow the asymptotic lines.
#include <gtest/gtest.h>

#include <Eigen/Geometry>
#include <algorithm>
#include <set>

#include "gproj/geometry/mesh/parametric_grid.h"
#include "gproj/problems/nets/anet.h"
#include "gproj/problems/nets/diagonal_mesh.h"
#include "gproj/problems/nets/hnet.h"
#include "tests/input_error_test_util.h"

namespace gproj::nets {
namespace {

PolyMesh DiagonalGrid(const std::string& surface, int n, double jitter, uint32_t seed = 1) {
  ParametricGridOptions o;
  o.nu = o.nv = n;
  o.jitter = jitter;
  o.seed = seed;
  o.diagonal = true;
  return MakeParametricGrid(AsymptoticSurface(surface), o);
}

// Six quads around vertex 0 (a singular vertex of valence 6).
PolyMesh Fan() {
  PolyMesh fan;
  const auto c = fan.add_vertex({0, 0, 0});
  std::vector<PolyMesh::VertexHandle> ring;
  for (int k = 0; k < 12; ++k) {
    const double a = k * M_PI / 6, r = k % 2 ? 2.0 : 1.0;
    ring.push_back(fan.add_vertex({r * std::cos(a), r * std::sin(a), 0.1 * (k % 3)}));
  }
  for (int k = 0; k < 6; ++k)
    fan.add_face({c, ring[2 * k], ring[2 * k + 1], ring[(2 * k + 2) % 12]});
  return fan;
}

std::set<int> AsSet(const std::vector<int>& v) { return {v.begin(), v.end()}; }

TEST(DiagonalANetTest, StarPointsAreTheOppositeCornersInOrder) {
  ParametricGridOptions o;
  o.nu = o.nv = 5;
  const PolyMesh grid = MakeParametricGrid(AsymptoticSurface("hypar"), o);
  const auto v = [](int i) { return PolyMesh::VertexHandle(i); };
  EXPECT_EQ(AsSet(StarPoints(grid, v(12), NetKind::kEdges)), (std::set<int>{7, 11, 13, 17}));
  const std::vector<int> inner = StarPoints(grid, v(12), NetKind::kDiagonals);
  ASSERT_EQ(AsSet(inner), (std::set<int>{6, 8, 16, 18}));
  // Cyclic: consecutive opposite corners share a row or a column (6, 8, 18, 16 or reversed).
  for (int k = 0; k < 4; ++k) {
    const int a = inner[k], b = inner[(k + 1) % 4];
    EXPECT_TRUE(a / 5 == b / 5 || a % 5 == b % 5) << a << " " << b;
  }
  EXPECT_EQ(AsSet(StarPoints(grid, v(2), NetKind::kDiagonals)), (std::set<int>{6, 8}));
  EXPECT_EQ(StarPoints(grid, v(0), NetKind::kDiagonals), std::vector<int>{6});

  // A singular vertex: six quads around a centre give six opposite corners.
  const PolyMesh fan = Fan();
  const PolyMesh::VertexHandle c(0);
  EXPECT_EQ(AsSet(StarPoints(fan, c, NetKind::kDiagonals)), (std::set<int>{2, 4, 6, 8, 10, 12}));
  EXPECT_EQ(StarPoints(fan, c, NetKind::kEdges).size(), 6u);
}

// On a lattice turned by 45° the diagonal stars of a ruled surface are planar and the edge stars
// are not: the two measures tell the nets apart.
TEST(DiagonalANetTest, TurnedRulingGridsHavePlanarDiagonalStarsOnly) {
  for (const char* surface : {"hypar", "hyperboloid"}) {
    const PolyMesh mesh = DiagonalGrid(surface, 11, 0.0);
    EXPECT_LT(MeasureStarPlanarity(mesh, mesh, NetKind::kDiagonals).max_star_planarity, 1e-13)
        << surface;
    EXPECT_GT(MeasureStarPlanarity(mesh, mesh, NetKind::kEdges).max_star_planarity, 1e-3)
        << surface;
  }
}

class JitteredDiagonalTest : public ::testing::TestWithParam<StarPlanarityForm> {};

TEST_P(JitteredDiagonalTest, BecomesAnANetOnItsDiagonalsWithConvexQuads) {
  const PolyMesh exact = DiagonalGrid("hyperboloid", 15, 0.0);
  const PolyMesh mesh = DiagonalGrid("hyperboloid", 15, 0.05, 4);
  ANetOptions options;
  options.net = NetKind::kDiagonals;
  options.star_form = GetParam();
  ANet anet(mesh, &exact, options);
  EXPECT_GT(anet.Measures().max_star_planarity, 1e-2);
  const RunReport report = anet.Run();
  ASSERT_TRUE(report.converged) << report.summary.FullReport();
  const PolyMesh result = anet.Result();
  const StarPlanarityMeasures m = MeasureStarPlanarity(result, mesh, NetKind::kDiagonals);
  EXPECT_LE(m.max_star_planarity, 1e-9);
  EXPECT_LE(m.max_displacement, 0.01);
  EXPECT_EQ(m.shape.non_convex, 0);
  EXPECT_GT(m.shape.min_angle_deg, 60.0);
  // The edge stars were not asked for, and are not planar.
  EXPECT_GT(MeasureStarPlanarity(result, mesh, NetKind::kEdges).max_star_planarity, 1e-3);
  // The result is written in the input's connectivity.
  ASSERT_EQ(result.n_faces(), mesh.n_faces());
  for (auto f : mesh.faces()) {
    auto a = mesh.cfv_begin(f);
    auto b = result.cfv_begin(f);
    for (int k = 0; k < 4; ++k, ++a, ++b) EXPECT_EQ(a->idx(), b->idx());
  }
}

INSTANTIATE_TEST_SUITE_P(Forms, JitteredDiagonalTest,
                         ::testing::Values(StarPlanarityForm::kNormals, StarPlanarityForm::kQuads),
                         [](const auto& info) {
                           return info.param == StarPlanarityForm::kNormals ? "Normals" : "Quads";
                         });

Eigen::Vector3d FaceNormal(const PolyMesh& mesh, PolyMesh::FaceHandle f) {
  std::vector<Eigen::Vector3d> p;
  for (auto v : mesh.fv_range(f))
    p.emplace_back(mesh.point(v)[0], mesh.point(v)[1], mesh.point(v)[2]);
  return (p[2] - p[0]).cross(p[3] - p[1]);
}

TEST(DiagonalMeshTest, RingsOfTheOtherColourOrientedLikeTheQuads) {
  ParametricGridOptions o;
  o.nu = o.nv = 5;
  const PolyMesh grid = MakeParametricGrid(AsymptoticSurface("hypar"), o);
  const std::vector<int> colour = TwoColourVertices(grid);
  for (int c : {0, 1}) {
    const DiagonalMesh d = MakeDiagonalMesh(grid, c, DiagonalRings::kQuads);
    // Inner vertices (i, j) in 1..3 of the other colour: 4 of colour 1, 5 of colour 0.
    EXPECT_EQ(d.mesh.n_faces(), c == 0 ? 4u : 5u);
    for (int v : d.input_vertices) EXPECT_EQ(colour[v], c);
    for (std::size_t k = 0; k < d.input_vertices.size(); ++k)
      EXPECT_EQ(d.vertex_of[d.input_vertices[k]], static_cast<int>(k));
    // Every face is the ring of an inner vertex w; its normal agrees with the quads' at w.
    for (auto f : d.mesh.faces()) {
      EXPECT_GT(FaceNormal(d.mesh, f).dot(FaceNormal(grid, grid.face_handle(0))), 0.0);
    }
  }
  // A valence-6 vertex's ring is a hexagon: left open when quads are needed, named.
  const PolyMesh fan = Fan();
  EXPECT_EQ(MakeDiagonalMesh(fan, 1, DiagonalRings::kAll).mesh.n_faces(), 1u);
  EXPECT_EQ(MakeDiagonalMesh(fan, 1, DiagonalRings::kAll).mesh.valence(PolyMesh::FaceHandle(0)),
            6u);
  EXPECT_NE(InputErrorOf([&] {
              MakeDiagonalMesh(fan, 1, DiagonalRings::kQuads);
            }).find("the diagonal mesh of colour 1 has no face"),
            std::string::npos);
}

// The H-net of a diagonal mesh of a jittered turned hyperboloid grid: smooth, close to the input.
TEST(DiagonalMeshTest, DiagonalMeshOfATurnedGridExtendsToAnHNet) {
  const PolyMesh mesh = DiagonalGrid("hyperboloid", 13, 0.03, 2);
  const DiagonalMesh d = MakeDiagonalMesh(mesh, 0, DiagonalRings::kQuads);
  HNetOptions options;
  HNet hnet(d.mesh, &mesh, options);
  const HNetSummary summary = hnet.Run();
  ASSERT_TRUE(summary.report.converged) << summary.report.termination;
  EXPECT_LE(MaxTangentPlaneAngle(hnet.mesh(), hnet.weights()), 1e-6);
  EXPECT_LE(summary.max_reference_distance, 5e-3);
  // The edge net of the same mesh is not an H-net near the input.
  EXPECT_GT(MeasureStarPlanarity(mesh, mesh, NetKind::kEdges).max_star_planarity, 1e-2);
}

}  // namespace
}  // namespace gproj::nets
