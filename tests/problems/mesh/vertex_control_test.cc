#include "gproj/problems/mesh/vertex_control.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <fstream>

#include "gproj/geometry/mesh/quad_grid.h"
#include "gproj/problems/pq/pq_planarization.h"

namespace gproj {
namespace {

PolyMesh NoisyParaboloid(int n) {
  QuadGridOptions g;
  g.nu = g.nv = n;
  g.noise = 0.05;
  return MakeQuadGrid(g);
}

// Distance from p to the closed polyline through `loop`'s vertices of `mesh`.
double DistanceToLoop(const PolyMesh& mesh, const std::vector<int>& loop,
                      const Eigen::Vector3d& p) {
  double best = HUGE_VAL;
  for (size_t i = 0; i < loop.size(); ++i) {
    const Eigen::Vector3d a = ToEigen(mesh.point(mesh.vertex_handle(loop[i])));
    const Eigen::Vector3d b = ToEigen(mesh.point(mesh.vertex_handle(loop[(i + 1) % loop.size()])));
    const double t = std::clamp((p - a).dot(b - a) / (b - a).squaredNorm(), 0.0, 1.0);
    best = std::min(best, (a + t * (b - a) - p).norm());
  }
  return best;
}

TEST(VertexControlTest, FixedVerticesDoNotMoveAtAll) {
  const PolyMesh mesh = NoisyParaboloid(21);
  pq::PQPlanarizationOptions options;
  options.vertices.fixed = {0, 20, 220, 440};  // three corners and the centre
  pq::PQPlanarization pq(mesh, options);
  ASSERT_TRUE(pq.Run().converged);
  const PolyMesh out = pq.Result();
  for (int v : options.vertices.fixed)
    for (int c = 0; c < 3; ++c)
      EXPECT_EQ(out.point(out.vertex_handle(v))[c], mesh.point(mesh.vertex_handle(v))[c]) << v;
  EXPECT_GT(MaxDisplacement(out, mesh), 1e-4);  // the others did move
}

TEST(VertexControlTest, FixedBoundaryStaysAndTheInsideBecomesPlanar) {
  const PolyMesh mesh = NoisyParaboloid(21);
  pq::PQPlanarizationOptions options;
  options.vertices.fix_boundary = true;
  options.solver.max_iterations = 50;
  pq::PQPlanarization pq(mesh, options);
  ASSERT_TRUE(pq.Run().converged);
  const PolyMesh out = pq.Result();
  int boundary = 0;
  for (auto v : mesh.vertices()) {
    if (!mesh.is_boundary(v)) continue;
    ++boundary;
    EXPECT_EQ(out.point(v), mesh.point(v)) << v.idx();
  }
  EXPECT_EQ(boundary, 80);
  EXPECT_LE(pq.Measures().max_planarity, 1e-9);
  EXPECT_EQ(pq.Measures().shape.non_convex, 0);
}

// Boundary vertices glide along the input's boundary, the grid's four corners are held; on a
// conjugate-looking grid and on a twisted one whose grid lines are the rulings (far from
// conjugate, where a closest-point retraction after each step used to stall at 7e-3).
TEST(VertexControlTest, GlidingBoundaryVerticesSlideAlongTheInputBoundary) {
  for (double twist : {0.0, 0.3}) {
    QuadGridOptions grid;
    grid.nu = grid.nv = 41;
    grid.noise = 0.05;
    grid.c = twist;
    const PolyMesh mesh = MakeQuadGrid(grid);
    pq::PQPlanarizationOptions options;
    options.vertices.glide_boundary = true;
    pq::PQPlanarization pq(mesh, options);
    const RunReport report = pq.Run();
    ASSERT_TRUE(report.converged) << twist << " " << report.termination;
    EXPECT_LE(pq.Measures().max_planarity, 1e-9);
    EXPECT_EQ(pq.Measures().shape.non_convex, 0);
    EXPECT_LE(ValueOf(report.final, "max_glide_distance"), 1e-9);
    const PolyMesh out = pq.Result();
    const std::vector<std::vector<int>> loops = BoundaryLoops(mesh);
    ASSERT_EQ(loops.size(), 1u);
    EXPECT_EQ(loops[0].size(), 160u);
    const double diagonal = 2.0 * std::sqrt(2.0);  // about; the bound is far below any slip
    double worst = 0.0, slid = 0.0;
    for (int v : loops[0]) {
      const Eigen::Vector3d p = ToEigen(out.point(out.vertex_handle(v)));
      worst = std::max(worst, DistanceToLoop(mesh, loops[0], p));
      slid = std::max(slid, (p - ToEigen(mesh.point(mesh.vertex_handle(v)))).norm());
    }
    EXPECT_LE(worst / diagonal, 1e-9) << twist;
    EXPECT_GT(slid, 1e-5) << twist;  // they did slide
    for (int corner : {0, 40, 1640, 1680})
      EXPECT_EQ(out.point(out.vertex_handle(corner)), mesh.point(mesh.vertex_handle(corner)));
  }
}

TEST(VertexControlTest, BoundaryLoopsAreCutAtTheirCorners) {
  QuadGridOptions grid;
  grid.nu = 5, grid.nv = 4;
  grid.noise = 0.0;
  const PolyMesh mesh = MakeQuadGrid(grid);
  const std::vector<std::vector<int>> loops = BoundaryLoops(mesh);
  ASSERT_EQ(loops.size(), 1u);
  const std::vector<std::vector<int>> paths = SplitAtCorners(mesh, loops[0]);
  ASSERT_EQ(paths.size(), 4u);  // the grid's corners, each in one face
  std::vector<int> lengths;
  for (const std::vector<int>& path : paths) {
    lengths.push_back(static_cast<int>(path.size()));
    for (int end : {path.front(), path.back()}) {
      int faces = 0;
      for (auto f = mesh.cvf_begin(mesh.vertex_handle(end)); f.is_valid(); ++f) ++faces;
      EXPECT_EQ(faces, 1) << end;
    }
  }
  std::sort(lengths.begin(), lengths.end());
  EXPECT_EQ(lengths, (std::vector<int>{4, 4, 5, 5}));

  // A ring of quads around a hole: its loops turn by 360/16 = 22.5 degrees at every vertex
  // and have no vertex in one face only, so they come back whole and closed.
  PolyMesh ring;
  std::vector<PolyMesh::VertexHandle> inner, outer;
  for (int i = 0; i < 16; ++i) {
    const double a = 2.0 * M_PI * i / 16;
    inner.push_back(ring.add_vertex({std::cos(a), std::sin(a), 0.0}));
    outer.push_back(ring.add_vertex({2 * std::cos(a), 2 * std::sin(a), 0.0}));
  }
  for (int i = 0; i < 16; ++i)
    ring.add_face({inner[i], outer[i], outer[(i + 1) % 16], inner[(i + 1) % 16]});
  for (const std::vector<int>& loop : BoundaryLoops(ring)) {
    const std::vector<std::vector<int>> whole = SplitAtCorners(ring, loop);
    ASSERT_EQ(whole.size(), 1u);
    EXPECT_EQ(whole[0].size(), 17u);
    EXPECT_EQ(whole[0].front(), whole[0].back());
  }
}

TEST(VertexControlTest, ReferenceSurfacePullsVerticesOntoIt) {
  // The noise-free surface, finely meshed, as the reference of a noisy coarse grid.
  QuadGridOptions fine;
  fine.nu = fine.nv = 81;
  const PolyMesh reference = MakeQuadGrid(fine);
  const PolyMesh mesh = NoisyParaboloid(21);
  auto height_error = [](const PolyMesh& m) {  // |z − (0.3 x² + 0.2 y²)|, mean
    double sum = 0.0;
    for (auto v : m.vertices()) {
      const auto p = m.point(v);
      sum += std::abs(p[2] - (0.3 * p[0] * p[0] + 0.2 * p[1] * p[1]));
    }
    return sum / m.n_vertices();
  };
  pq::PQPlanarization with(mesh, pq::PQPlanarizationOptions(), &reference);
  ASSERT_TRUE(with.Run().converged);
  pq::PQPlanarization without(mesh, pq::PQPlanarizationOptions());
  ASSERT_TRUE(without.Run().converged);
  EXPECT_LT(height_error(with.Result()), 0.5 * height_error(mesh));
  EXPECT_LT(height_error(with.Result()), 0.5 * height_error(without.Result()));
  ASSERT_NE(with.problem().FindFamily("surface_tangent"), nullptr);
  EXPECT_EQ(with.problem().FindFamily("closeness"), nullptr);
}

TEST(VertexControlTest, VertexIdFilesAreReadWithCommentsAndCheckedPerLine) {
  const auto dir = std::filesystem::temp_directory_path() / "gproj_vertex_ids";
  std::filesystem::create_directories(dir);
  const std::string good = (dir / "good.txt").string(), bad = (dir / "bad.txt").string();
  std::ofstream(good) << "# corners\n0 5\n\n7 # and one more\n";
  std::ofstream(bad) << "1\n2 x\n";
  EXPECT_EQ(ReadVertexIds(good, 8), (std::vector<int>{0, 5, 7}));
  try {
    ReadVertexIds(bad, 8);
    FAIL() << "a bad id was accepted";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("bad.txt:2"), std::string::npos) << e.what();
  }
  EXPECT_THROW(ReadVertexIds(good, 6), InputError);  // 7 is out of range
  std::filesystem::remove_all(dir);
  VertexControlOptions both;
  both.fix_boundary = both.glide_boundary = true;
  std::string why;
  EXPECT_FALSE(both.IsValid(&why));
}

}  // namespace
}  // namespace gproj
