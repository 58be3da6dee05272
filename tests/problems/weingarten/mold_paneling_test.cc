#include "gproj/problems/weingarten/mold_paneling.h"

#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>

#include "gproj/common/input_error.h"

namespace gproj::weingarten {
namespace {

constexpr double kPi = 3.14159265358979323846;

// A quarter of a cylinder of radius 1 (axis z), parameters (angle, height) over [0, 1]².
BSplineSurface Cylinder() {
  return FitBSpline(
      [](double u, double v) {
        const double a = 0.5 * kPi * u;
        return Eigen::Vector3d(std::cos(a), std::sin(a), 1.5 * v);
      },
      4, 4, 12, 12, 6);
}

// A cap of the unit sphere around the north pole, |x|, |y| ≤ 0.5.
BSplineSurface SphereCap() {
  return FitBSpline(
      [](double u, double v) {
        const double x = u - 0.5, y = v - 0.5;
        return Eigen::Vector3d(x, y, std::sqrt(1.0 - x * x - y * y));
      },
      4, 4, 12, 12, 6);
}

PanelingOptions Grid(int n, int molds) {
  PanelingOptions o;
  o.panels_u = o.panels_v = n;
  o.molds = molds;
  return o;
}

TEST(MoldShapeTest, HeightAndSlopeOfTheCubic) {
  MoldShape mold;
  mold.scale = 2.0;
  mold.coefficients << 1, 2, 3, 4, 5, 6, 7, 8, 9, 10;
  const double x = 0.6, y = -0.4, X = x / 2, Y = y / 2;
  const double f = 1 + 2 * X + 3 * Y + 4 * X * X + 5 * X * Y + 6 * Y * Y + 7 * X * X * X +
                   8 * X * X * Y + 9 * X * Y * Y + 10 * Y * Y * Y;
  const double fx = (2 + 8 * X + 5 * Y + 21 * X * X + 16 * X * Y + 9 * Y * Y) / 2;
  const double fy = (3 + 5 * X + 12 * Y + 8 * X * X + 18 * X * Y + 30 * Y * Y) / 2;
  const Eigen::Vector3d h = mold.HeightAndSlope(x, y);
  EXPECT_NEAR(h[0], f, 1e-12);
  EXPECT_NEAR(h[1], fx, 1e-12);
  EXPECT_NEAR(h[2], fy, 1e-12);
  EXPECT_NEAR(mold.Height(x, y), f, 1e-12);
}

// Congruent panels share a mold: every panel of a cylinder (panels along its rulings) and every
// panel of a sphere fits one mold, so with a single mold the seams stay closed; a freeform
// surface with a single mold opens them more than ten times as wide.
TEST(PanelingTest, CongruentPanelsShareOneMoldWithClosedSeams) {
  for (const BSplineSurface& s : {Cylinder(), SphereCap()}) {
    const Paneling p = PanelSurface(s, Grid(6, 1));
    EXPECT_EQ(p.num_molds, 1);
    EXPECT_LT(p.seams.max_gap, 2e-4);
    EXPECT_LT(p.seams.max_kink_deg, 0.1);
    EXPECT_LT(p.max_deviation, 2e-4);  // every panel lies on the design surface
  }
  const Paneling freeform = PanelSurface(MakeWavyBSpline(10, 10, 4), Grid(6, 1));
  EXPECT_GT(freeform.seams.max_gap, 10 * 2e-4);
  EXPECT_GT(freeform.seams.max_kink_deg, 10 * 0.1);
}

// The curvatures at the panel centres are the surface's: the cylinder has H = ±½, K = 0, the
// sphere H = ±1, K = 1 (up to the fit of the B-spline).
TEST(PanelingTest, PanelCurvaturesAreTheSurfaces) {
  const Paneling c = PanelSurface(Cylinder(), Grid(4, 1));
  const Paneling s = PanelSurface(SphereCap(), Grid(4, 1));
  for (int i = 0; i < 16; ++i) {
    EXPECT_NEAR(std::abs(c.h[i]), 0.5, 1e-3);
    EXPECT_NEAR(c.k[i], 0.0, 1e-3);
    EXPECT_NEAR(std::abs(s.h[i]), 1.0, 1e-3);
    EXPECT_NEAR(s.k[i], 1.0, 2e-3);
  }
}

// Seam points: m per side shared by two panels; the clustering never uses more molds than
// asked; one mold per panel fits each panel on its own and closes the seams of a freeform
// surface far better than one mold for all.
TEST(PanelingTest, SeamsMoldsAndOneMoldPerPanel) {
  const BSplineSurface s = MakeWavyBSpline(10, 10, 4);
  PanelingOptions o = Grid(5, 7);
  o.panels_v = 4;
  const Paneling p = PanelSurface(s, o);
  EXPECT_EQ(p.seams.gaps.size(), static_cast<size_t>(o.points_per_side * (4 * 4 + 5 * 3)));
  EXPECT_EQ(p.seams.kinks_deg.size(), p.seams.gaps.size());
  EXPECT_LE(p.num_molds, 7);
  EXPECT_GE(p.num_molds, 1);
  ASSERT_EQ(p.mold_of_panel.size(), 20u);
  for (int m : p.mold_of_panel) EXPECT_LT(m, p.num_molds);
  const Paneling one = PanelSurface(s, Grid(5, 1));
  const Paneling each = PanelSurface(s, Grid(5, 25));
  EXPECT_EQ(each.num_molds, 25);
  EXPECT_LT(each.fitted_seams.max_gap, 0.2 * one.fitted_seams.max_gap);
  EXPECT_LT(each.fitted_seams.max_kink_deg, 0.2 * one.fitted_seams.max_kink_deg);
  EXPECT_LT(each.seams.mean_gap, 0.2 * one.seams.mean_gap);
  EXPECT_LT(each.seams.mean_kink_deg, 0.2 * one.seams.mean_kink_deg);
}

// Positioning the panels together (Fig. 13c) closes the seams that fitting each panel to its
// own design panel leaves: on a freeform surface with few molds the mean gap and kink fall, and
// the panels stay close to the design surface (their distance from it is measured).
TEST(PanelingTest, SeamPositioningLowersGapsAndKinks) {
  const BSplineSurface s = MakeWavyBSpline(10, 10, 4);
  for (int molds : {4, 12}) {
    const Paneling p = PanelSurface(s, Grid(8, molds));
    EXPECT_LT(p.seams.mean_gap, 0.9 * p.fitted_seams.mean_gap) << molds;
    EXPECT_LT(p.seams.mean_kink_deg, 0.8 * p.fitted_seams.mean_kink_deg) << molds;
    PanelingOptions fixed = Grid(8, molds);
    fixed.seam_positioning = false;
    const Paneling unmoved = PanelSurface(s, fixed);
    EXPECT_EQ(unmoved.seams.mean_gap, unmoved.fitted_seams.mean_gap);
    EXPECT_DOUBLE_EQ(unmoved.fitted_seams.mean_gap, p.fitted_seams.mean_gap);
    std::printf(
        "%d molds: panels off the design surface by mean %.3g max %.3g (unmoved %.3g, "
        "%.3g); seams mean gap %.3g\n",
        molds, p.mean_deviation, p.max_deviation, unmoved.mean_deviation, unmoved.max_deviation,
        p.seams.mean_gap);
    EXPECT_GT(p.mean_deviation, 0.0);
    // Closing the seams moves the panels off the design surface, within bounds (measured: the
    // mean about doubles, 5e-4 -> 9e-4 with 4 molds; the max grows 1.4-2.2x).
    EXPECT_LT(p.mean_deviation, 2.5 * unmoved.mean_deviation) << molds;
    EXPECT_LT(p.max_deviation, 2.5 * unmoved.max_deviation) << molds;
  }
}

// The placed panel lies on the design surface up to the fit: every mold point of a panel's
// sample is close to the sample itself when the panel has its own mold.
TEST(PanelingTest, PanelMeshFollowsTheSurface) {
  const BSplineSurface s = MakeWavyBSpline(10, 10, 4);
  const Paneling p = PanelSurface(s, Grid(4, 16));
  std::vector<int> panel_of_face;
  const PolyMesh mesh = PanelMesh(s, p, 3, &panel_of_face);
  EXPECT_EQ(mesh.n_faces(), 16u * 9u);
  EXPECT_EQ(panel_of_face.size(), mesh.n_faces());
  const PolyMesh reference = SampleSurfaceMesh(s, 40, 40);
  for (const auto vh : mesh.vertices()) {
    const auto& q = mesh.point(vh);
    double nearest = 1e300;
    for (const auto rh : reference.vertices())
      nearest = std::min(nearest, (reference.point(rh) - q).norm());
    EXPECT_LT(nearest, 0.05) << vh.idx();
  }
}

TEST(PanelingTest, MoldsForToleranceMeetsItWithFewerMoldsThanPanels) {
  const BSplineSurface s = MakeWavyBSpline(10, 10, 4);
  const PanelingOptions o = Grid(6, 1);
  const Paneling one = PanelSurface(s, o);
  const Paneling each = PanelSurface(s, Grid(6, 36));
  // A tolerance between one mold for all and one mold per panel.
  const double gap = std::sqrt(one.seams.max_gap * each.seams.max_gap);
  const double kink = std::sqrt(one.seams.max_kink_deg * each.seams.max_kink_deg);
  Paneling reached;
  const int molds = MoldsForTolerance(s, o, gap, kink, &reached);
  ASSERT_GT(molds, 1);
  EXPECT_LE(molds, 36);
  EXPECT_EQ(reached.num_molds, molds);
  EXPECT_LE(reached.seams.max_gap, gap);
  EXPECT_LE(reached.seams.max_kink_deg, kink);
  EXPECT_EQ(MoldsForTolerance(s, o, 1e-12, 1e-12), -1);
}

TEST(PanelingTest, InvalidOptionsAreNamed) {
  const BSplineSurface s = MakeWavyBSpline(6, 6, 3);
  PanelingOptions o = Grid(0, 1);
  EXPECT_THROW(PanelSurface(s, o), InputError);
  o = Grid(3, 0);
  EXPECT_THROW(PanelSurface(s, o), InputError);
  o = Grid(3, 1);
  o.points_per_side = 2;
  try {
    PanelSurface(s, o);
    FAIL();
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("points per panel side"), std::string::npos);
  }
}

}  // namespace
}  // namespace gproj::weingarten
