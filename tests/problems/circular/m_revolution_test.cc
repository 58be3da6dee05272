#include "gproj/problems/circular/m_revolution.h"

#include <gtest/gtest.h>

#include <Eigen/Geometry>
#include <cmath>
#include <cstdio>

#include "gproj/problems/circular/circular_mesh.h"
#include "gproj/problems/run/report_json.h"

namespace gproj::circular {
namespace {

// The inversion of a known surface of revolution (axis the x-axis, meridian y = 1 + 0.3 sin x in
// the plane z = 0) gives the designer's curve and P2, P3; the one-step construction must find
// that inversion centre among its roots and rebuild the same surface: every vertex, inverted
// back, at distance r(x) from the axis.
TEST(MRevolutionTest, RebuildsTheInversionOfAKnownSurfaceOfRevolution) {
  const Eigen::Vector3d centre(0.7, 2.5, 0.0);
  const double ratio = 3.0;
  auto r = [](double x) { return 1.0 + 0.3 * std::sin(x); };
  std::vector<Eigen::Vector3d> curve;
  const int n = 12;
  for (int i = 0; i <= n; ++i) {
    const double x = 2.0 * i / n;
    curve.push_back(Invert(Eigen::Vector3d(x, r(x), 0.0), centre, ratio));
  }
  const Eigen::Vector3d p2 = Invert(Eigen::Vector3d(0.0, -r(0.0), 0.0), centre, ratio);
  const Eigen::Vector3d p3 = Invert(Eigen::Vector3d(2.0, -r(2.0), 0.0), centre, ratio);
  MRevolutionOptions options;
  options.t = r(0.0) / r(2.0);
  bool found = false;
  for (int root = 0; root < 2 && !found; ++root) {
    options.root = root;
    MRevolutionSurface s;
    try {
      s = BuildMRevolutionSurface(curve, p2, p3, options);
    } catch (const InputError&) {
      continue;
    }
    if ((s.choice.centre - centre).norm() > 1e-9) continue;
    found = true;
    for (auto v : s.mesh.vertices()) {
      const Eigen::Vector3d q = Invert(Eigen::Vector3d(s.mesh.point(v).data()), centre, ratio);
      EXPECT_NEAR(std::hypot(q.y(), q.z()), r(q.x()), 1e-10) << v.idx();
    }
    EXPECT_LT(s.curve_roundtrip, 1e-12);
    EXPECT_LT(s.far_meridian_miss, 1e-10);
  }
  EXPECT_TRUE(found) << "the known inversion centre is not among the roots";
}

// What a designer draws (000 Fig. 19): a wavy planar curve from P1 to P4 and two points on the
// circle through P1 and P4. The result is a circular mesh through the curve's own points
// (f⁻¹ ∘ f = id), its far meridian through P2 and P3, its arches planar and perpendicular to
// the drawing plane; the same for both roots and several t.
TEST(MRevolutionTest, DesignerInputGivesACircularMeshThroughTheCurveAndThePoints) {
  // The circle: centre (0, 0, 0), radius 2, in the plane z = 0; P1, P4 at angles 200°, 340°.
  auto on_circle = [](double degrees) {
    const double a = degrees * M_PI / 180.0;
    return Eigen::Vector3d(2.0 * std::cos(a), 2.0 * std::sin(a), 0.0);
  };
  const Eigen::Vector3d p1 = on_circle(200), p4 = on_circle(340);
  std::vector<Eigen::Vector3d> curve;
  for (int i = 0; i <= 20; ++i) {
    const double s = i / 20.0;
    const Eigen::Vector3d base = (1 - s) * p1 + s * p4;
    curve.push_back(
        base +
        Eigen::Vector3d(0.0, 0.25 * std::sin(M_PI * s) + 0.05 * std::sin(3 * M_PI * s), 0.0));
  }
  int built = 0;
  for (const double t : {0.6, 1.0, 1.7})
    for (int root = 0; root < 2; ++root) {
      MRevolutionOptions options;
      options.t = t;
      options.root = root;
      options.arch_segments = 12;
      MRevolutionSurface s;
      try {
        s = BuildMRevolutionSurface(curve, on_circle(110), on_circle(60), options);
      } catch (const InputError& e) {
        std::printf("t = %g root %d: %s\n", t, root, e.what());
        continue;
      }
      ++built;
      const NamedValues m = MeasureCircularMesh(s.mesh);
      std::printf(
          "t = %g root %d: %zu quads, concyclicity %.1e, planarity %.1e, round trip %.1e, "
          "P2/P3 %.1e, arches %.1e\n",
          t, root, s.mesh.n_faces(), ValueOf(m, "max_concyclicity"), ValueOf(m, "max_planarity"),
          s.curve_roundtrip, s.far_meridian_miss, s.arch_planarity);
      EXPECT_LT(ValueOf(m, "max_concyclicity"), 1e-10);
      EXPECT_LT(ValueOf(m, "max_planarity"), 1e-10);
      EXPECT_LT(s.curve_roundtrip, 1e-12);
      EXPECT_LT(s.far_meridian_miss, 1e-10);
      EXPECT_LT(s.arch_planarity, 1e-10);
      // The curve is the first meridian, point for point; arches stand perpendicular to z = 0.
      for (size_t i = 0; i < curve.size(); ++i) {
        const int first = static_cast<int>(i) * 13;
        EXPECT_EQ(Eigen::Vector3d(s.mesh.point(s.mesh.vertex_handle(first)).data()), curve[i]);
        const Eigen::Vector3d a(s.mesh.point(s.mesh.vertex_handle(first)).data());
        const Eigen::Vector3d b(s.mesh.point(s.mesh.vertex_handle(first + 6)).data());
        const Eigen::Vector3d e(s.mesh.point(s.mesh.vertex_handle(first + 12)).data());
        EXPECT_NEAR(std::abs((b - a).cross(e - a).normalized().z()), 0.0, 1e-9);
        EXPECT_GT(b.z(), 0.0);  // the arches rise towards +z
      }
    }
  EXPECT_GE(built, 4);
}

TEST(MRevolutionTest, RefusesWhatHasNoSolution) {
  std::vector<Eigen::Vector3d> curve = {{-1, 0, 0}, {0, 0.3, 0}, {1, 0, 0}};
  MRevolutionOptions options;
  // P2 off the circle through P1, P4 and P3.
  try {
    BuildMRevolutionSurface(curve, Eigen::Vector3d(-0.5, 3, 0), Eigen::Vector3d(0.6, 0.8, 0),
                            options);
    ADD_FAILURE() << "not concyclic";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("must lie on one circle"), std::string::npos) << e.what();
  }
  // A curve out of the plane.
  curve[1].z() = 0.2;
  try {
    BuildMRevolutionSurface(curve, Eigen::Vector3d(-0.6, 0.8, 0), Eigen::Vector3d(0.6, 0.8, 0),
                            options);
    ADD_FAILURE() << "out of plane";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("curve point 1"), std::string::npos) << e.what();
  }
  // Coinciding points, an up direction in the drawing plane, a mesh too large to hold.
  curve[1].z() = 0.0;
  const Eigen::Vector3d p2(-0.6, 0.8, 0), p3(0.6, 0.8, 0);
  try {
    BuildMRevolutionSurface(curve, p3, p3, options);
    ADD_FAILURE() << "P2 = P3";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("P2 and P3 coincide"), std::string::npos) << e.what();
  }
  MRevolutionOptions sideways = options;
  sideways.up = Eigen::Vector3d(1, 0, 0);
  try {
    BuildMRevolutionSurface(curve, p2, p3, sideways);
    ADD_FAILURE() << "up in the plane";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("`up` lies in the drawing plane"), std::string::npos)
        << e.what();
  }
  sideways.up = Eigen::Vector3d(0, 0, -1);
  const MRevolutionSurface down = BuildMRevolutionSurface(curve, p2, p3, sideways);
  EXPECT_LT(down.mesh.point(down.mesh.vertex_handle(8)).data()[2], 0.0);  // arches go down
  MRevolutionOptions huge = options;
  huge.arch_segments = 100000;
  std::vector<Eigen::Vector3d> long_curve;
  for (int i = 0; i <= 1000; ++i) {
    const double a = M_PI * (1.0 + i / 1000.0);
    long_curve.emplace_back(std::cos(a), 0.3 * std::sin(a), 0.0);
  }
  EXPECT_THROW(BuildMRevolutionSurface(long_curve, p2, p3, huge), InputError);
  options.t = -1;
  EXPECT_THROW(BuildMRevolutionSurface(curve, Eigen::Vector3d(-0.6, 0.8, 0),
                                       Eigen::Vector3d(0.6, 0.8, 0), options),
               InputError);
  EXPECT_THROW(BuildMRevolutionSurface({curve[0]}, curve[1], curve[2], MRevolutionOptions{}),
               InputError);
}

}  // namespace
}  // namespace gproj::circular
