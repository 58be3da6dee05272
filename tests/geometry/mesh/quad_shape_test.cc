#include "gproj/geometry/mesh/quad_shape.h"

#include <gtest/gtest.h>

#include <algorithm>

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

TEST(QuadShapeTest, ThinSkewQuadCrossingItselfInItsBestFitPlaneIsNotConvex) {
  // Long and thin, twisted: every corner sine is positive in the diagonals' plane (0.46, 0.003,
  // 0.095, 0.54), but seen along the best-fit plane's normal (3.9° from the diagonals') the
  // corner at v1 turns the other way, so laid flat the quad crosses itself.
  const V p[4] = {V(-1.3, 0.5, -0.6), V(4.5, 0.7, 0.3), V(4.9, 0.7, 0.4), V(-0.4, 1.0, -0.3)};
  double sines[4];
  QuadCornerSines(p[0].data(), p[1].data(), p[2].data(), p[3].data(), sines);
  for (double sine : sines) EXPECT_GT(sine, 0.0);
  EXPECT_FALSE(MeasureQuadShape(p[0], p[1], p[2], p[3]).convex);
  // The same quad in the other orientation, and moved and scaled: the same answer.
  EXPECT_FALSE(MeasureQuadShape(p[3], p[2], p[1], p[0]).convex);
  const V shift(1e3, -2e3, 5e2);
  EXPECT_FALSE(MeasureQuadShape(1e-4 * p[0] + shift, 1e-4 * p[1] + shift, 1e-4 * p[2] + shift,
                                1e-4 * p[3] + shift)
                   .convex);
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
