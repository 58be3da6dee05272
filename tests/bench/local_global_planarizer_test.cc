// The benchmarks' local–global baseline (bench/local_global_planarizer.h): a baseline that is
// slow by a bug would flatter gproj, so its iteration and its Anderson acceleration are checked.
#include "local_global_planarizer.h"

#include <gtest/gtest.h>

#include <Eigen/Eigenvalues>

#include "gproj/geometry/mesh/quad_grid.h"

namespace gproj {
namespace {

PolyMesh NoisyGrid(int n) {
  QuadGridOptions grid;
  grid.nu = grid.nv = n;
  grid.noise = 0.05;
  grid.seed = 3;
  return MakeQuadGrid(grid);
}

// The objective recomputed here: closeness plus, per quad, the squared distances of its
// mean-centred corners to their least-squares plane (the smallest eigenvalue of their scatter).
double Energy(const PolyMesh& mesh, const Eigen::MatrixX3d& v, double closeness) {
  double energy = 0.0;
  for (const auto vh : mesh.vertices()) {
    const auto& p = mesh.point(vh);
    energy += closeness * (v.row(vh.idx()) - Eigen::RowVector3d(p[0], p[1], p[2])).squaredNorm();
  }
  for (const auto fh : mesh.faces()) {
    Eigen::Matrix<double, 4, 3> q;
    int k = 0;
    for (const auto vh : mesh.fv_range(fh)) q.row(k++) = v.row(vh.idx());
    q.rowwise() -= q.colwise().mean();
    energy += Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d>(q.transpose() * q).eigenvalues()[0];
  }
  return energy;
}

// Iterations until the max planarity is ≤ tolerance (limit + 1 when not reached), checking that
// the energy never rises.
int IterationsTo(LocalGlobalPlanarizer* lg, double tolerance, int limit) {
  double energy = lg->Energy();
  for (int k = 0; k < limit; ++k) {
    if (lg->MaxPlanarity() <= tolerance) return k;
    lg->Iterate();
    EXPECT_LE(lg->Energy(), energy * (1.0 + 1e-12)) << "iteration " << k;
    energy = lg->Energy();
  }
  return lg->MaxPlanarity() <= tolerance ? limit : limit + 1;
}

TEST(LocalGlobalPlanarizerTest, AndersonReachesTheToleranceInFewerIterations) {
  const PolyMesh mesh = NoisyGrid(21);
  LocalGlobalPlanarizer plain(mesh, 1e-4), anderson(mesh, 1e-4, 6);
  const double start = plain.MaxPlanarity();
  EXPECT_GT(start, 1e-2);
  const int plain_iterations = IterationsTo(&plain, 1e-3, 2000);
  const int anderson_iterations = IterationsTo(&anderson, 1e-3, 2000);
  ASSERT_LE(plain_iterations, 2000);
  EXPECT_LT(anderson_iterations, plain_iterations / 2) << plain_iterations << " plain iterations";
  EXPECT_GT(anderson.accepted(), 0);
  EXPECT_NEAR(anderson.Energy(), Energy(mesh, anderson.vertices(), 1e-4), 1e-9 * anderson.Energy());
  EXPECT_NEAR(plain.Energy(), Energy(mesh, plain.vertices(), 1e-4), 1e-9 * plain.Energy());
  // Run on, Anderson ends at an energy no higher than plain iterations 20 times as many.
  for (int k = 0; k < 10000; ++k) plain.Iterate();
  for (int k = 0; k < 500; ++k) anderson.Iterate();
  EXPECT_LE(anderson.Energy(), plain.Energy() * (1.0 + 1e-9));
}

// At a weight where plain iterations converge fast, both reach the same fixed point.
TEST(LocalGlobalPlanarizerTest, AndersonAndPlainIterationsMeetAtTheFixedPoint) {
  const PolyMesh mesh = NoisyGrid(15);
  LocalGlobalPlanarizer plain(mesh, 1e-1), anderson(mesh, 1e-1, 6);
  for (int k = 0; k < 3000; ++k) plain.Iterate();
  for (int k = 0; k < 300; ++k) anderson.Iterate();
  const double diagonal =
      (plain.vertices().colwise().maxCoeff() - plain.vertices().colwise().minCoeff()).norm();
  EXPECT_LT((plain.vertices() - anderson.vertices()).rowwise().norm().maxCoeff(), 1e-8 * diagonal);
  EXPECT_NEAR(anderson.Energy(), plain.Energy(), 1e-9 * plain.Energy());
  EXPECT_GT(plain.MaxPlanarity(), 1e-6);  // the closeness keeps the fixed point off planarity
}

}  // namespace
}  // namespace gproj
