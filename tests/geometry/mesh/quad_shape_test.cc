#include "gproj/geometry/mesh/quad_shape.h"

#include <gtest/gtest.h>

#include <Eigen/Eigenvalues>
#include <algorithm>
#include <random>

#include "gproj/geometry/mesh/quad_grid.h"

namespace gproj {
namespace {

using V = Eigen::Vector3d;

TEST(QuadShapeTest, UnitSquareIsConvexWithRightAnglesAndNoKink) {
  const QuadShape s = MeasureQuadShape(V(0, 0, 0), V(1, 0, 0), V(1, 1, 0), V(0, 1, 0));
  EXPECT_TRUE(s.convex);
  EXPECT_NEAR(s.min_angle_deg, 90.0, 1e-12);
  EXPECT_NEAR(s.kink_deg, 0.0, 1e-12);
  EXPECT_NEAR(s.diagonal_distance, 0.0, 1e-15);
  double sines[4];
  const V p[4] = {V(0, 0, 0), V(1, 0, 0), V(1, 1, 0), V(0, 1, 0)};
  QuadCornerSines(p[0].data(), p[1].data(), p[2].data(), p[3].data(), sines);
  for (double sine : sines) EXPECT_NEAR(sine, 1.0, 1e-12);
}

TEST(QuadShapeTest, DartAndBowTieAreNotConvex) {
  // A dart: v2 pushed inside the triangle (v0, v1, v3) makes a reflex corner at v2.
  const QuadShape dart = MeasureQuadShape(V(0, 0, 0), V(2, 0, 0), V(0.5, 0.5, 0), V(0, 2, 0));
  EXPECT_FALSE(dart.convex);
  const std::array<double, 4> angles =
      QuadCornerAngles(V(0, 0, 0), V(2, 0, 0), V(0.5, 0.5, 0), V(0, 2, 0));
  EXPECT_NEAR(angles[0] + angles[1] + angles[2] + angles[3], 360.0, 1e-9);
  EXPECT_GT(angles[2], 180.0);
  // A bow-tie: v1 and v2 swapped.
  const QuadShape bow = MeasureQuadShape(V(0, 0, 0), V(1, 1, 0), V(1, 0, 0), V(0, 1, 0));
  EXPECT_FALSE(bow.convex);
}

TEST(QuadShapeTest, KinkAndDiagonalDistanceOfASkewQuad) {
  // Lifting v2 by h: the diagonals' distance is h / √(4 + 2h²) and the triangles fold.
  const double h = 0.2;
  const QuadShape s = MeasureQuadShape(V(0, 0, 0), V(1, 0, 0), V(1, 1, h), V(0, 1, 0));
  EXPECT_TRUE(s.convex);
  EXPECT_NEAR(s.diagonal_distance, h / std::sqrt(4.0 + 2.0 * h * h), 1e-12);
  EXPECT_GT(s.kink_deg, 5.0);
  EXPECT_LT(s.kink_deg, 20.0);
}

// Whether the bilinear patch of a quad keeps its normal within 90° of the centre's, sampled
// on a (k + 1)² grid that includes the corners: the normal x_u × x_v, computed here directly.
bool BilinearPatchUnfolded(const V* p, int k) {
  const V centre_normal = (p[2] - p[0]).cross(p[3] - p[1]);
  for (int i = 0; i <= k; ++i)
    for (int j = 0; j <= k; ++j) {
      const double u = static_cast<double>(i) / k, v = static_cast<double>(j) / k;
      const V xu = (1 - v) * (p[1] - p[0]) + v * (p[2] - p[3]);
      const V xv = (1 - u) * (p[3] - p[0]) + u * (p[2] - p[1]);
      if (!(xu.cross(xv).dot(centre_normal) > 0.0)) return false;
    }
  return true;
}

// The corner-sine test against the bilinear patch sampled independently, on random skew quads
// from nearly planar to strongly twisted.
TEST(QuadShapeTest, ConvexSkewQuadsAreThoseWhoseBilinearPatchDoesNotFold) {
  std::mt19937 random(5);
  std::normal_distribution<double> noise(0.0, 1.0);
  int convex = 0, not_convex = 0;
  for (int trial = 0; trial < 4000; ++trial) {
    const double spread = 0.05 + 0.5 * (trial % 8) / 7.0, lift = 2.0 * spread;
    V p[4] = {V(0, 0, 0), V(1, 0, 0), V(1, 1, 0), V(0, 1, 0)};
    for (V& q : p) q += V(spread * noise(random), spread * noise(random), lift * noise(random));
    const bool measured = MeasureQuadShape(p[0], p[1], p[2], p[3]).convex;
    EXPECT_EQ(measured, BilinearPatchUnfolded(p, 16)) << "trial " << trial;
    (measured ? convex : not_convex) += 1;
  }
  EXPECT_GT(convex, 1000);
  EXPECT_GT(not_convex, 500);
}

// A thin twisted strip: its projection onto its least-squares plane crosses itself, yet its
// bilinear patch is unfolded, and so it is convex; with one corner pulled back across the strip
// the patch folds and the quad is not convex.
TEST(QuadShapeTest, ThinTwistedStripIsConvexUntilItsPatchFolds) {
  const double length = 4.0, width = 0.2, twist = 0.3;  // twist > width / 2
  const V strip[4] = {V(0, 0, twist), V(length, 0, -twist), V(length, width, twist),
                      V(0, width, -twist)};
  EXPECT_TRUE(MeasureQuadShape(strip[0], strip[1], strip[2], strip[3]).convex);
  EXPECT_TRUE(BilinearPatchUnfolded(strip, 32));
  // Its least-squares plane: the smallest spread is across the width, not the twist.
  Eigen::Matrix3d scatter = Eigen::Matrix3d::Zero();
  const V centre = (strip[0] + strip[1] + strip[2] + strip[3]) / 4.0;
  for (const V& q : strip) scatter += (q - centre) * (q - centre).transpose();
  const V fit = Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d>(scatter).eigenvectors().col(0);
  EXPECT_GT(std::abs(fit.y()), 0.99);  // the plane of length and twist
  int positive = 0;
  for (int k = 0; k < 4; ++k)
    positive += (strip[k] - strip[(k + 3) % 4]).cross(strip[(k + 1) % 4] - strip[k]).dot(fit) > 0;
  EXPECT_EQ(positive, 2);  // laid flat in that plane it crosses itself
  // One corner pushed across the strip until its corner normal turns against the centre's.
  const V folded[4] = {strip[0], strip[1], V(length - 3.0, -0.5, twist), strip[3]};
  EXPECT_FALSE(MeasureQuadShape(folded[0], folded[1], folded[2], folded[3]).convex);
  EXPECT_FALSE(BilinearPatchUnfolded(folded, 32));
}

TEST(QuadShapeTest, SummaryAndCornerChangeOfAGrid) {
  QuadGridOptions grid;
  grid.nu = grid.nv = 6;
  const PolyMesh mesh = MakeQuadGrid(grid);
  const QuadShapeSummary s = Summarize(MeasureQuadShapes(mesh));
  EXPECT_EQ(s.non_convex, 0);
  EXPECT_GT(s.min_angle_deg, 80.0);
  EXPECT_EQ(CompareCornerAngles(mesh, mesh).quads_changed, 0);
  PolyMesh moved = mesh;
  moved.set_point(moved.vertex_handle(7),
                  moved.point(moved.vertex_handle(7)) + PolyMesh::Point(0.5, 0.5, 0.0));
  const ShapeChange change = CompareCornerAngles(mesh, moved);
  EXPECT_EQ(change.quads_changed, 4);  // the four quads around vertex 7
  EXPECT_GT(change.max_corner_change_deg, 10.0);
  EXPECT_GT(Summarize(MeasureQuadShapes(moved)).non_convex, 0);
}

}  // namespace
}  // namespace gproj
