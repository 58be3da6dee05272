#include "gproj/problems/circular/canal_from_curves.h"

#include <gtest/gtest.h>

#include <Eigen/Geometry>
#include <cmath>
#include <cstdio>

namespace gproj::circular {
namespace {

double Measure(const CanalFromCurves& c, const char* name) { return ValueOf(c.measures, name); }

// A cylinder of radius r about the z-axis: curve 1 a ruling (a line of curvature), curve 2
// another ruling at angle α, the normal at P_0 radial. Every sphere is centred on the axis with
// radius r exactly (the closed form of eq. 6 here); consecutive spheres meet in circles of
// radius √(r² − (Δz / 2)²) halfway between them; the mesh's quads are circular.
TEST(CanalFromCurvesTest, CylinderFromTwoRulings) {
  const double r = 2.0, alpha = 1.1;
  std::vector<Eigen::Vector3d> ruling, other;
  for (int k = 0; k <= 10; ++k) ruling.emplace_back(r, 0.0, 0.3 * k);
  other = {Eigen::Vector3d(r * std::cos(alpha), r * std::sin(alpha), -1.0),
           Eigen::Vector3d(r * std::cos(alpha), r * std::sin(alpha), 5.0)};
  CanalFromCurvesOptions o;
  o.segments = 8;
  const CanalFromCurves c = FitCanalToCurves(ruling, other, Eigen::Vector3d(1, 0, 0), o);
  ASSERT_EQ(c.centres.size(), 11u);
  for (size_t k = 0; k < c.centres.size(); ++k) {
    EXPECT_LT(c.centres[k].head<2>().norm(), 1e-12) << k;
    EXPECT_NEAR(c.radii[k], r, 1e-12) << k;
  }
  for (size_t k = 0; k < c.circles.size(); ++k) {
    EXPECT_NEAR(c.circles[k].radius, std::sqrt(r * r - 0.15 * 0.15), 1e-12);
    EXPECT_NEAR(c.circles[k].centre.z(), 0.3 * k + 0.15, 1e-12);
  }
  EXPECT_LT(Measure(c, "max_sphere_fit"), 1e-12);
  EXPECT_LT(Measure(c, "max_concyclicity"), 1e-10);
  EXPECT_LT(Measure(c, "max_planarity"), 1e-10);
  EXPECT_EQ(c.mesh.n_faces(), 9u * 8u);  // 10 circles, 9 rows of quads
  // The mesh spans the quarter of the circles between the two rulings (angle α).
  const auto first = c.mesh.point(c.mesh.vertex_handle(0));
  const auto last = c.mesh.point(c.mesh.vertex_handle(8));
  EXPECT_NEAR(std::atan2(last[1], last[0]) - std::atan2(first[1], first[0]), alpha, 1e-9);
}

// A torus (core radius 3, tube radius 1): curve 1 its outer equator, curve 2 its top circle
// (a polyline of 2000 points), the normal radial. The centres land on the core circle and the
// radii at the tube radius, up to the polyline's chord error (1e-6 here).
TEST(CanalFromCurvesTest, TorusFromTwoParallels) {
  std::vector<Eigen::Vector3d> equator, top;
  for (int k = 0; k <= 12; ++k) {
    const double phi = 0.08 * k;
    equator.emplace_back(4.0 * std::cos(phi), 4.0 * std::sin(phi), 0.0);
  }
  for (int k = 0; k <= 2000; ++k) {
    const double phi = -0.5 + 2.0 * k / 2000.0;
    top.emplace_back(3.0 * std::cos(phi), 3.0 * std::sin(phi), 1.0);
  }
  const CanalFromCurves c = FitCanalToCurves(equator, top, Eigen::Vector3d(1, 0, 0), {});
  for (size_t k = 0; k < c.centres.size(); ++k) {
    EXPECT_NEAR(c.centres[k].head<2>().norm(), 3.0, 2e-6) << k;
    EXPECT_NEAR(c.centres[k].z(), 0.0, 1e-12) << k;
    EXPECT_NEAR(c.radii[k], 1.0, 2e-6) << k;
  }
  EXPECT_LT(Measure(c, "max_sphere_fit"), 1e-9);
  EXPECT_LT(Measure(c, "max_concyclicity"), 1e-10);
}

// Two generated space curves, no symmetry: every sphere is equidistant from P_k and the second
// curve, the mesh is circular, and it runs from the first curve towards the second.
std::vector<Eigen::Vector3d> FirstCurve(int n) {
  std::vector<Eigen::Vector3d> first;
  for (int k = 0; k <= n; ++k) {
    const double t = static_cast<double>(k) / n;
    first.emplace_back(4.0 * t, 0.6 * std::sin(2.0 * t), 0.3 * t * t);
  }
  return first;
}

std::vector<Eigen::Vector3d> SecondCurve() {
  std::vector<Eigen::Vector3d> second;
  for (int k = 0; k <= 4000; ++k) {
    const double t = -0.1 + 1.2 * k / 4000.0;
    second.emplace_back(4.0 * t, 1.5 + 0.2 * t, 0.8 + 0.4 * std::cos(3.0 * t));
  }
  return second;
}

TEST(CanalFromCurvesTest, GeneratedCurvesGiveACircularMesh) {
  const std::vector<Eigen::Vector3d> first = FirstCurve(16), second = SecondCurve();
  const CanalFromCurves c = FitCanalToCurves(first, second, Eigen::Vector3d(0, 0.3, 1.0), {});
  std::printf("sphere fit %.2e, concyclicity %.2e, planarity %.2e, curve 1 %.3g, curve 2 %.3g\n",
              Measure(c, "max_sphere_fit"), Measure(c, "max_concyclicity"),
              Measure(c, "max_planarity"), Measure(c, "max_curve1_distance"),
              Measure(c, "max_curve2_distance"));
  EXPECT_LT(Measure(c, "max_sphere_fit"), 1e-9);
  EXPECT_LT(Measure(c, "max_concyclicity"), 1e-10);
  EXPECT_LT(Measure(c, "max_planarity"), 1e-10);
  // Consecutive normal lines meet (a developable of normals): coplanar with the segment.
  for (size_t k = 0; k + 1 < first.size(); ++k)
    EXPECT_LT(std::abs((first[k + 1] - first[k]).dot(c.normals[k].cross(c.normals[k + 1]))), 1e-12);
  EXPECT_LT(Measure(c, "max_curve1_distance"), 0.05);
}

// The surface passes the second curve ever more closely as the line of curvature is refined:
// the contact points of the spheres with curve 2 approach the circles (which lie half a step
// before and after each sphere).
TEST(CanalFromCurvesTest, RefiningTheLineOfCurvatureBringsTheSurfaceToTheSecondCurve) {
  double previous = HUGE_VAL;
  for (int n : {16, 32, 64, 128}) {
    const CanalFromCurves c =
        FitCanalToCurves(FirstCurve(n), SecondCurve(), Eigen::Vector3d(0, 0.3, 1.0), {});
    const double d = Measure(c, "max_curve2_distance");
    std::printf("%d segments: curve 2 from the circles %.3g, curve 1 %.3g\n", n, d,
                Measure(c, "max_curve1_distance"));
    EXPECT_LT(d, 0.7 * previous) << n;
    previous = d;
  }
}

TEST(CanalFromCurvesTest, BadInputsAreNamed) {
  const std::vector<Eigen::Vector3d> line = {{0, 0, 0}, {1, 0, 0}, {2, 0, 0}};
  const std::vector<Eigen::Vector3d> other = {{0, 1, 1}, {2, 1, 1}};
  auto message = [&](const std::vector<Eigen::Vector3d>& a, const Eigen::Vector3d& n) {
    try {
      FitCanalToCurves(a, other, n, {});
    } catch (const InputError& e) {
      return std::string(e.what());
    }
    return std::string();
  };
  EXPECT_NE(message(line, Eigen::Vector3d(1, 0, 0)).find("runs along the curve"),
            std::string::npos);
  EXPECT_NE(message({{0, 0, 0}, {1, 0, 0}}, Eigen::Vector3d(0, 0, 1)).find("at least 3"),
            std::string::npos);
  EXPECT_NE(message({{0, 0, 0}, {0, 0, 0}, {1, 0, 0}}, Eigen::Vector3d(0, 0, 1)).find("coincide"),
            std::string::npos);
  // A second curve through a point of the first: a sphere of radius 0.
  try {
    FitCanalToCurves(line, line, Eigen::Vector3d(0, 0, 1), {});
    ADD_FAILURE() << "accepted touching curves";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("must not touch"), std::string::npos) << e.what();
  }
}

// Computed at unit scale: the cylinder's construction far from the origin and at 1e200 times
// the size gives the same spheres, scaled.
TEST(CanalFromCurvesTest, ScaleAndPositionDoNotMatter) {
  for (const auto& [scale, shift] : {std::pair{1e200, 0.0}, std::pair{1.0, 1e9}}) {
    std::vector<Eigen::Vector3d> ruling, other;
    for (int k = 0; k <= 10; ++k) ruling.push_back(Eigen::Vector3d(2.0, 0.0, 0.3 * k) * scale);
    other = {Eigen::Vector3d(2 * std::cos(1.1), 2 * std::sin(1.1), -1.0) * scale,
             Eigen::Vector3d(2 * std::cos(1.1), 2 * std::sin(1.1), 5.0) * scale};
    for (auto* curve : {&ruling, &other})
      for (Eigen::Vector3d& p : *curve) p.z() += shift;
    const CanalFromCurves c = FitCanalToCurves(ruling, other, Eigen::Vector3d(1e308, 0, 0), {});
    for (double r : c.radii) EXPECT_NEAR(r / scale, 2.0, 1e-9) << scale;
    EXPECT_LT(Measure(c, "max_concyclicity"), 1e-10) << scale;
  }
}

}  // namespace
}  // namespace gproj::circular
