#include "gproj/problems/circular/canal_surface.h"

#include <gtest/gtest.h>

#include <Eigen/Geometry>
#include <algorithm>
#include <cmath>
#include <cstdio>

#include "canal_test_util.h"
#include "gproj/geometry/mesh/circle.h"
#include "gproj/problems/mesh/planarity_measures.h"

namespace gproj::circular {
namespace {

CircularStripInput Input(int n = 8) { return BendingStripInput(n); }

// Whether two circles lie on a common sphere: residual of |x − o|² = R² over points of b.
double CoSphericity(const Circle& a, const Circle& b) {
  const Eigen::Vector3d u = b.normal.unitOrthogonal(), w = b.normal.cross(u);
  const Eigen::Vector3d p = b.centre + b.radius * u;
  const Eigen::Vector3d d = a.centre - p;
  const double s = (a.radius * a.radius - d.squaredNorm()) / (2.0 * d.dot(a.normal));
  const Eigen::Vector3d o = a.centre + s * a.normal;
  const double r2 = a.radius * a.radius + s * s;
  double worst = 0.0;
  for (int k = 0; k < 7; ++k) {
    const Eigen::Vector3d q = b.centre + b.radius * (std::cos(0.9 * k) * u + std::sin(0.9 * k) * w);
    worst = std::max(worst, std::abs((q - o).squaredNorm() - r2) / r2);
  }
  return worst;
}

TEST(CanalSurfaceTest, StripHasCircularQuadsAndTheAskedLengths) {
  const CircularStripInput in = Input();
  const CircularStrip strip = BuildCircularStrip(in);
  for (size_t k = 0; k < strip.p.size(); ++k)
    EXPECT_NEAR((strip.q[k] - strip.p[k]).norm(), in.lengths[k], 1e-12);
  const PolyMesh mesh = StripMesh(strip);
  EXPECT_EQ(mesh.n_faces(), 8u);
  EXPECT_LT(MeasureCircularity(mesh).max_concyclicity, 1e-10);
  // The first circle passes through the first point.
  EXPECT_LT(
      DistanceToCircle(
          in.first_point,
          FitCircle(std::array<Eigen::Vector3d, 3>{strip.p[0], strip.p[1], strip.q[0]}.data(), 3)),
      1e-12);
}

TEST(CanalSurfaceTest, FramesCloseAroundQuadsAndCirclesAreCoSpherical) {
  const CircularStrip strip = BuildCircularStrip(Input());
  FrameAngles angles = AnglesFromNormal(Eigen::Vector3d(0.2, -0.5, 1.0));
  angles.psi = 0.3;
  const CyclidicStrip net = MakeCyclidicStrip(strip, angles);
  for (size_t k = 0; k + 1 < strip.p.size(); ++k) {
    // Frame at Q_{k+1} reached through Q_k equals the one reached through P_{k+1}.
    const Eigen::Vector3d e = strip.q[k + 1] - strip.q[k];
    const Eigen::Vector3d n_via_q =
        net.q_frames[k].n - 2 * net.q_frames[k].n.dot(e) / e.squaredNorm() * e;
    EXPECT_LT((n_via_q - net.q_frames[k + 1].n).norm(), 1e-10) << "quad " << k;
    EXPECT_LT(CoSphericity(net.circles[k], net.circles[k + 1]), 1e-10) << "circles " << k;
    EXPECT_LT(DistanceToCircle(strip.q[k], net.circles[k]), 1e-12);
  }
  EXPECT_GT(net.energy, 0.0);
}

TEST(CanalSurfaceTest, MeshBetweenCoSphericalCirclesIsCircular) {
  const CircularStrip strip = BuildCircularStrip(Input());
  const CyclidicStrip net = MakeCyclidicStrip(strip, AnglesFromNormal(Eigen::Vector3d(0, 0, 1)));
  const PolyMesh mesh = MeshCanalSurface(net, 10);
  EXPECT_EQ(mesh.n_vertices(), 9u * 11u);
  EXPECT_LT(MeasureCircularity(mesh).max_concyclicity, 1e-10);
  // Every vertex (k, j) lies on C_k, and column 0 is the input curve.
  for (int k = 0; k <= 8; ++k) {
    const auto& p0 = mesh.point(PolyMesh::VertexHandle(k * 11));
    EXPECT_LT((Eigen::Vector3d(p0[0], p0[1], p0[2]) - strip.p[k]).norm(), 1e-12);
    for (int j = 0; j <= 10; ++j) {
      const auto& p = mesh.point(PolyMesh::VertexHandle(k * 11 + j));
      EXPECT_LT(DistanceToCircle(Eigen::Vector3d(p[0], p[1], p[2]), net.circles[k]), 1e-9);
    }
  }
}

TEST(CanalSurfaceTest, SmoothingLowersTheEnergyWithBfgs) {
  const CircularStripInput in = Input();
  const FrameAngles start = AnglesFromNormal(Eigen::Vector3d(0.2, -0.5, 1.0));
  CanalSmoothingOptions options;
  int calls = 0;
  const CanalSmoothingSummary s =
      SmoothCanalStrip(in, start, options, [&](const RunRecord&) { return ++calls, true; });
  EXPECT_GT(calls, 0);
  EXPECT_GT(s.iterations, 0);
  EXPECT_LT(s.final_energy, 0.5 * s.initial_energy) << s.message;
  // The result is still a valid circular strip through the same curve.
  CircularStripInput out = in;
  out.lengths = s.lengths;
  EXPECT_LT(MeasureCircularity(StripMesh(BuildCircularStrip(out))).max_concyclicity, 1e-10);
}

// 000 §3.3: the normal at a fixed angle to a reference plane turns along a cone. The smoothing
// keeps it there (to rounding), still lowers F, and cannot beat the free smoothing.
TEST(CanalSurfaceTest, NormalOnAConeStaysOnItWhileSmoothing) {
  const CircularStripInput in = Input();
  const FrameAngles start = AnglesFromNormal(Eigen::Vector3d(0.2, -0.5, 1.0));
  CanalSmoothingOptions free_options;
  const CanalSmoothingSummary free = SmoothCanalStrip(in, start, free_options);
  for (const double angle : {30.0, -10.0, 75.0}) {
    CanalSmoothingOptions options;
    options.cone.enabled = true;
    options.cone.axis = Eigen::Vector3d(0.3, 0.1, 1.0);
    options.cone.angle_deg = angle;
    const FrameAngles on_cone = OnCone(start, options.cone);
    EXPECT_NEAR(options.cone.AngleOf(NormalOf(on_cone)), angle, 1e-9);
    // The nearest normal on the cone: in the plane of the axis and the given normal.
    EXPECT_NEAR(options.cone.axis.cross(NormalOf(start)).dot(NormalOf(on_cone)), 0.0, 1e-12);
    const CanalSmoothingSummary s = SmoothCanalStrip(in, start, options);
    const Eigen::Vector3d n = NormalOf(s.angles);
    std::printf(
        "cone at %g deg: F %.6g -> %.6g (free: %.6g), normal at %.12g deg, turned %.3g "
        "deg about the axis, %d iterations\n",
        angle, s.initial_energy, s.final_energy, free.final_energy, options.cone.AngleOf(n),
        std::acos(std::clamp(n.dot(NormalOf(on_cone)), -1.0, 1.0)) * 180 / M_PI, s.iterations);
    EXPECT_TRUE(s.converged) << s.termination;
    EXPECT_NEAR(options.cone.AngleOf(n), angle, 1e-9);
    EXPECT_NEAR(s.initial_energy, MakeCyclidicStrip(BuildCircularStrip(in), on_cone).energy,
                1e-9 * s.initial_energy);
    EXPECT_LT(s.final_energy, s.initial_energy);
    EXPECT_GE(s.final_energy, free.final_energy * (1.0 - 1e-6));
    EXPECT_GT((n - NormalOf(on_cone)).norm(), 1e-4);  // the normal turned along the cone
  }
  // Without smoothing the frame's normal is moved onto the cone.
  CanalSurfaceOptions plain;
  plain.smoothing.cone.enabled = true;
  plain.smoothing.cone.angle_deg = 20.0;
  const CanalSurface canal(in, start, plain);
  EXPECT_NEAR(plain.smoothing.cone.AngleOf(NormalOf(canal.angles())), 20.0, 1e-9);
  // A cone that is one normal, and a zero axis, are refused.
  plain.smoothing.cone.angle_deg = 90.0;
  EXPECT_THROW(CanalSurface(in, start, plain), InputError);
  plain.smoothing.cone.angle_deg = 20.0;
  plain.smoothing.cone.axis = Eigen::Vector3d::Zero();
  EXPECT_THROW(CanalSurface(in, start, plain), InputError);
}

TEST(CanalSurfaceTest, RunReportsTheSmoothingWithNamedMeasures) {
  CanalSurfaceOptions options;
  options.smooth = true;
  options.segments = 6;
  CanalSurface canal(Input(), AnglesFromNormal(Eigen::Vector3d(0.2, -0.5, 1.0)), options);
  int calls = 0;
  const RunReport report = canal.Run([&](const RunRecord&) { return ++calls, true; });
  EXPECT_EQ(report.solver, SolverKind::kCeres);
  EXPECT_EQ(report.method, "BFGS");
  EXPECT_TRUE(report.converged) << report.termination;
  EXPECT_FALSE(report.failed);
  EXPECT_EQ(calls, static_cast<int>(report.history.size()));
  EXPECT_EQ(report.history.size(), static_cast<size_t>(report.iterations) + 1);
  // F per iterate, from the start to the end.
  EXPECT_DOUBLE_EQ(ValueOf(report.history.front().measures, "smoothness_energy"),
                   ValueOf(report.initial, "smoothness_energy"));
  EXPECT_DOUBLE_EQ(ValueOf(report.history.back().measures, "smoothness_energy"),
                   ValueOf(report.final, "smoothness_energy"));
  EXPECT_LT(ValueOf(report.final, "smoothness_energy"),
            0.5 * ValueOf(report.initial, "smoothness_energy"));
  EXPECT_LT(ValueOf(report.final, "max_concyclicity"), 1e-10);
  EXPECT_EQ(canal.Mesh().n_faces(), 8u * 6u);
}

// The strip, its diagnoses, its smoothing and the mesh are scale-free: the input moved and
// scaled by 1e±20 or 1e±150 builds, smooths in the same iterations and ends at the same shape
// (at 1e-20 the line search used to fail at the first step and report convergence; from 1e20
// the strip was refused as collinear, from 1e150 the mesh as degenerate).
TEST(CanalSurfaceTest, SmoothingAndMeshAreTheSameAtEveryScale) {
  const FrameAngles angles = AnglesFromNormal(Eigen::Vector3d(0.2, -0.5, 1.0));
  CanalSurfaceOptions options;
  options.smooth = true;
  CanalSurface unit(Input(), angles, options);
  const RunReport unit_run = unit.Run();
  ASSERT_TRUE(unit_run.converged) << unit_run.termination;
  const double unit_energy = ValueOf(unit_run.final, "smoothness_energy");
  for (double scale : {1e-150, 1e-20, 1e20, 1e150}) {
    CircularStripInput in = Input();
    const Eigen::Vector3d shift(2.0, -1.0, 0.5);
    for (Eigen::Vector3d& p : in.curve) p = (p + shift) * scale;
    in.first_point = (in.first_point + shift) * scale;
    for (double& l : in.lengths) l *= scale;
    CanalSurface canal(in, angles, options);
    const RunReport run = canal.Run();
    EXPECT_TRUE(run.converged) << "scale " << scale << ": " << run.termination;
    EXPECT_EQ(run.iterations, unit_run.iterations) << "scale " << scale;
    EXPECT_NEAR(ValueOf(run.final, "smoothness_energy") * scale * scale / unit_energy, 1.0, 1e-6)
        << scale;
    EXPECT_LT(ValueOf(run.final, "max_concyclicity"), 1e-10) << scale;
    for (size_t k = 0; k < in.lengths.size(); ++k)
      EXPECT_NEAR(canal.input().lengths[k] / scale, unit.input().lengths[k], 1e-6) << scale;
    const PolyMesh mesh = canal.Mesh(), unit_mesh = unit.Mesh();
    for (auto v : mesh.vertices()) {
      const PolyMesh::Point back = mesh.point(v) / scale - PolyMesh::Point(2.0, -1.0, 0.5);
      EXPECT_LT((back - unit_mesh.point(v)).norm(), 1e-6) << scale << ", vertex " << v.idx();
    }
  }
}

TEST(CanalSurfaceTest, SmoothingCutShortIsNotConvergedAndWithoutSmoothingNothingRuns) {
  CanalSurfaceOptions options;
  options.smooth = true;
  options.smoothing.max_iterations = 1;
  const FrameAngles angles = AnglesFromNormal(Eigen::Vector3d(0.2, -0.5, 1.0));
  const RunReport cut = CanalSurface(Input(), angles, options).Run();
  EXPECT_FALSE(cut.converged) << cut.termination;
  EXPECT_EQ(cut.iterations, 1);
  options.smooth = false;
  CanalSurface plain(Input(), angles, options);
  const RunReport none = plain.Run();
  EXPECT_EQ(none.solver, SolverKind::kDirect);
  EXPECT_EQ(none.method, "closed form");
  EXPECT_TRUE(none.converged);
  EXPECT_EQ(none.iterations, 0);
  EXPECT_DOUBLE_EQ(ValueOf(none.final, "smoothness_energy"), plain.Net().energy);
}

TEST(CanalSurfaceTest, BadInputIsRefused) {
  CircularStripInput in = Input();
  in.lengths[3] = 100.0;  // longer than the circle's diameter
  try {
    BuildCircularStrip(in);
    FAIL() << "expected InputError";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("length 3"), std::string::npos) << e.what();
  }
  in = Input();
  in.first_point = in.curve[0] + 2.0 * (in.curve[1] - in.curve[0]);
  EXPECT_THROW(BuildCircularStrip(in), InputError);
  in = Input();
  in.lengths.pop_back();
  EXPECT_THROW(BuildCircularStrip(in), InputError);
}

}  // namespace
}  // namespace gproj::circular
