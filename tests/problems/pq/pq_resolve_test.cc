// Warm re-solves (MeshProblem::Resolve): a designer moves or pins vertices of a planarised mesh
// and the same problem re-solves from its last result, reusing the set-up and the analysis.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>

#include "gproj/common/input_error.h"
#include "gproj/geometry/mesh/quad_grid.h"
#include "gproj/geometry/mesh/scale_free.h"
#include "gproj/problems/pq/pq_planarization.h"

namespace gproj::pq {
namespace {

Eigen::Vector3d PointOf(const PolyMesh& mesh, int v) {
  const auto p = mesh.point(mesh.vertex_handle(v));
  return {p[0], p[1], p[2]};
}

// A noisy 41 × 41 grid (1,600 quads) of a saddle-like height field, planarised, then one inner
// vertex moved by 5% of the mean edge across the surface and off the grid's diagonal.
TEST(PQResolveTest, OneMovedVertexResolvesInTwoIterationsFromTheLastResult) {
  QuadGridOptions grid;
  grid.nu = grid.nv = 41;
  grid.noise = 0.05;
  grid.seed = 11;
  grid.a = 0.3, grid.b = -0.25, grid.c = 0.1;
  const PolyMesh mesh = MakeQuadGrid(grid);
  PQPlanarizationOptions options;
  options.tolerance = 1e-6;
  PQPlanarization pq(mesh, options);
  const RunReport cold = pq.Run();
  ASSERT_TRUE(cold.converged) << cold.summary.FullReport();
  EXPECT_FALSE(cold.summary.analysis_reused);
  const PolyMesh before = pq.Result();
  const double edge = MeanEdgeLength(before);

  const int v = 20 * 41 + 17;
  const Eigen::Vector3d moved = PointOf(before, v) + 0.05 * edge * Eigen::Vector3d(0.3, 0.2, 0.93);
  const RunReport warm = pq.Resolve({v}, {moved});
  ASSERT_TRUE(warm.converged) << warm.summary.FullReport();
  EXPECT_TRUE(warm.summary.analysis_reused);
  EXPECT_EQ(warm.summary.analysis_seconds, 0.0);
  EXPECT_LE(warm.iterations, 2) << warm.summary.FullReport();
  const PolyMesh after = pq.Result();
  EXPECT_EQ(PointOf(after, v), moved);  // held exactly where it was put
  const PlanarityMeasures m = MeasurePlanarity(after, mesh);
  EXPECT_LE(m.max_planarity, options.tolerance);
  EXPECT_EQ(m.shape.non_convex, 0);
  // The rest follows: nothing moves by more than the edit, beyond five edges from it by less
  // than half of it (a PQ mesh passes an edit on along its grid lines: measured 0.46 of the
  // edit at most there, 0.87 next to it).
  double nearest = 0.0, far = 0.0;
  for (int u = 0; u < static_cast<int>(after.n_vertices()); ++u) {
    if (u == v) continue;
    const double shift = (PointOf(after, u) - PointOf(before, u)).norm();
    const double distance = (PointOf(before, u) - PointOf(before, v)).norm();
    (distance < 5.0 * edge ? nearest : far) =
        std::max(distance < 5.0 * edge ? nearest : far, shift);
  }
  EXPECT_LT(nearest, 0.05 * edge);
  EXPECT_LT(far, 0.5 * 0.05 * edge);
  std::printf("warm re-solve: %d iterations, max shift near %.3g, far %.3g (of the edit)\n",
              warm.iterations, nearest / (0.05 * edge), far / (0.05 * edge));

  // Pinning a vertex where it is: nothing to do, converged at once.
  const RunReport pinned = pq.Resolve({5}, {PointOf(after, 5)});
  EXPECT_TRUE(pinned.converged);
  EXPECT_EQ(pinned.iterations, 0);
  EXPECT_EQ(pq.held_vertices(), (std::vector<int>{5, v}));
}

TEST(PQResolveTest, BadEditsAreRefusedAndChangeNothing) {
  QuadGridOptions grid;
  grid.nu = grid.nv = 6;
  grid.noise = 0.05;
  const PolyMesh mesh = MakeQuadGrid(grid);
  PQPlanarization pq(mesh, PQPlanarizationOptions());
  const Eigen::VectorXd x = pq.problem().x();
  auto refuses = [&](const std::vector<int>& ids, const std::vector<Eigen::Vector3d>& positions,
                     const std::string& text) {
    try {
      pq.Resolve(ids, positions);
      ADD_FAILURE() << "accepted: " << text;
    } catch (const InputError& e) {
      EXPECT_NE(std::string(e.what()).find(text), std::string::npos) << e.what();
    }
    EXPECT_EQ(pq.problem().x(), x);
    EXPECT_TRUE(pq.held_vertices().empty());
  };
  refuses({36}, {Eigen::Vector3d::Zero()}, "vertex 36 is out of range (the mesh has 36 vertices)");
  refuses({3, 3}, {Eigen::Vector3d::Zero(), Eigen::Vector3d::Zero()}, "vertex 3 is given twice");
  refuses({2}, {Eigen::Vector3d(NAN, 0, 0)}, "the position of vertex 2 is not finite");
  refuses({1, 2}, {Eigen::Vector3d::Zero()}, "2 vertex ids but 1 positions");
}

}  // namespace
}  // namespace gproj::pq
