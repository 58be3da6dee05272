#include "gproj/problems/circular/closed_canal.h"

#include <gtest/gtest.h>

#include <Eigen/Dense>
#include <cmath>

#include "gproj/geometry/mesh/circle.h"
#include "input_error_test_util.h"

namespace gproj::circular {
namespace {

// N points of the curve (cos t, sin t, wave sin 3t) · radius, optionally pushed onto the sphere
// of that radius.
CircularStripInput ClosedInput(int n, double wave, bool on_sphere, const Eigen::Vector3d& first,
                               double length) {
  CircularStripInput in;
  for (int k = 0; k < n; ++k) {
    const double t = 2.0 * M_PI * k / n;
    Eigen::Vector3d x(std::cos(t), std::sin(t), wave * std::sin(3.0 * t));
    in.curve.push_back(3.0 * (on_sphere ? x.normalized() : x));
  }
  in.first_point = first;
  in.lengths.assign(n, length);
  return in;
}

// Ten points of a closed space curve without symmetries.
CircularStripInput AsymmetricInput(const Eigen::Vector3d& first, double length) {
  CircularStripInput in;
  for (int k = 0; k < 10; ++k) {
    const double t = 2.0 * M_PI * k / 10;
    in.curve.emplace_back(3.0 * std::cos(t) + 0.3 * std::cos(2.0 * t), 3.0 * std::sin(t),
                          0.6 * std::sin(3.0 * t));
  }
  in.first_point = first;
  in.lengths.assign(10, length);
  return in;
}

// The sphere through four points (centre, radius), by the linear system of |x|² + b·x + c = 0.
std::pair<Eigen::Vector3d, double> SphereThrough(const Eigen::Vector3d& a, const Eigen::Vector3d& b,
                                                 const Eigen::Vector3d& c,
                                                 const Eigen::Vector3d& d) {
  Eigen::Matrix4d m;
  Eigen::Vector4d rhs;
  int row = 0;
  for (const Eigen::Vector3d* p : {&a, &b, &c, &d}) {
    m.row(row) << p->x(), p->y(), p->z(), 1.0;
    rhs(row++) = -p->squaredNorm();
  }
  const Eigen::Vector4d x = m.fullPivLu().solve(rhs);
  const Eigen::Vector3d centre = -0.5 * x.head<3>();
  return {centre, std::sqrt(centre.squaredNorm() - x(3))};
}

double Concyclicity(const CircularStrip& s, int k) {
  const int n = static_cast<int>(s.p.size()), next = (k + 1) % n;
  return QuadConcyclicity({s.p[k], s.p[next], s.q[next], s.q[k]});
}

TEST(ClosedCanalTest, CaseOneKeepsTheFirstPointAndClosesATorusIntoARing) {
  // A regular octagon with Q_0 = the first point in P_0's meridian plane and the normal radial:
  // a surface of revolution, every row the turn of row 0.
  const int n = 8, m = 6;
  const CircularStripInput in = ClosedInput(n, 0.0, false, {3.5, 0.0, 0.8}, std::sqrt(0.89));
  CircularStripInput open = in;
  open.curve.pop_back();
  open.lengths.pop_back();
  const CircularStrip asked = BuildCircularStrip(open);
  ClosedCanalOptions options;
  options.segments = m;
  const ClosedCanalSurface s =
      BuildClosedCanalSurface(in, AnglesFromNormal(Eigen::Vector3d(1, 0, 0)), options);
  EXPECT_EQ(s.closed.closing_case, 1);
  EXPECT_LT(s.closed.cosphericity, 1e-12);
  EXPECT_LT((s.closed.strip.q[0] - asked.q[0]).norm(), 1e-15);
  EXPECT_LT((s.closed.strip.q[0] - in.first_point).norm(), 1e-12);
  for (int k = 0; k < n; ++k) EXPECT_LT(Concyclicity(s.closed.strip, k), 1e-12) << k;
  EXPECT_NEAR((s.closed.strip.q[n - 1] - s.closed.strip.p[n - 1]).norm(), std::sqrt(0.89), 1e-12);
  EXPECT_TRUE(s.frame_closes);
  ASSERT_TRUE(s.welded);
  EXPECT_EQ(s.mesh.n_vertices(), static_cast<size_t>(n * (m + 1)));
  EXPECT_EQ(s.mesh.n_faces(), static_cast<size_t>(n * m));
  EXPECT_LT(MeasureCircularity(s.mesh).max_concyclicity, 1e-12);
  for (int k = 0; k < n; ++k) {
    const Eigen::Matrix3d turn =
        Eigen::AngleAxisd(2.0 * M_PI * k / n, Eigen::Vector3d::UnitZ()).toRotationMatrix();
    for (int j = 0; j <= m; ++j) {
      const auto& a = s.mesh.point(PolyMesh::VertexHandle(j));
      const auto& b = s.mesh.point(PolyMesh::VertexHandle(k * (m + 1) + j));
      EXPECT_LT(
          (turn * Eigen::Vector3d(a[0], a[1], a[2]) - Eigen::Vector3d(b[0], b[1], b[2])).norm(),
          1e-12);
    }
  }
}

TEST(ClosedCanalTest, CaseTwoTakesTheIntersectionOfTheTwoSpheres) {
  const int n = 9;
  const CircularStripInput in = ClosedInput(n, 0.4, true, {3.2, 0.3, 0.8}, 0.8);
  CircularStripInput open = in;
  open.curve.pop_back();
  open.lengths.pop_back();
  const CircularStrip asked = BuildCircularStrip(open);
  const ClosedCircularStrip c = BuildClosedCircularStrip(in);
  ASSERT_EQ(c.closing_case, 2);
  EXPECT_GT(c.cosphericity, 0.1);
  const CircularStrip& s = c.strip;
  // The spheres (Γ_0, P_{N−1}) and (Γ_{N−2}, P_0), each through four of its points.
  const auto [oa, ra] = SphereThrough(s.p[0], s.p[1], in.first_point, s.p[n - 1]);
  const auto [ob, rb] = SphereThrough(s.p[n - 2], s.p[n - 1], s.q[n - 2], s.p[0]);
  for (const Eigen::Vector3d& x : {s.q[0], s.q[n - 1]}) {
    EXPECT_NEAR((x - oa).norm(), ra, 1e-12 * ra);
    EXPECT_NEAR((x - ob).norm(), rb, 1e-12 * rb);
  }
  // Q_0 moved along Γ_0; Q_1..Q_{N−2} are the open strip's.
  EXPECT_NEAR(c.start_shift, (s.q[0] - asked.q[0]).norm(), 1e-15);
  EXPECT_GT(c.start_shift, 0.05);
  EXPECT_LT(DistanceToCircle(s.q[0], CircleThrough<double>(s.p[0], s.p[1], in.first_point)), 1e-12);
  for (int k = 1; k < n - 1; ++k) EXPECT_LT((s.q[k] - asked.q[k]).norm(), 1e-14) << k;
  for (int k = 0; k < n; ++k) EXPECT_LT(Concyclicity(s, k), 1e-12) << k;
  EXPECT_LT(DistanceToCircle(s.q[n - 1], c.closing_circle), 1e-12);
  const PolyMesh ring = ClosedStripMesh(s);
  EXPECT_EQ(ring.n_faces(), static_cast<size_t>(n));
  EXPECT_LT(MeasureCircularity(ring).max_concyclicity, 1e-12);

  // A curve on a sphere with an odd count: the loop is a reflection, one frame axis must be its
  // normal, and the frame nearest the asked one is taken.
  const Eigen::Matrix3d loop = LoopReflection(s.p);
  EXPECT_NEAR(loop.determinant(), -1.0, 1e-12);
  EXPECT_NEAR(loop.trace(), 1.0, 1e-12);
  ClosedCanalOptions options;
  options.segments = 5;
  const ClosedCanalSurface surface =
      BuildClosedCanalSurface(in, AnglesFromNormal(Eigen::Vector3d(1, 0, 0)), options);
  EXPECT_TRUE(surface.frame_closes);
  EXPECT_GT(ValueOf(surface.measures, "frame_rotation_deg"), 1.0);
  EXPECT_LT(ValueOf(surface.measures, "frame_closure_deg"), 1e-9);
  ASSERT_TRUE(surface.welded);
  EXPECT_EQ(surface.mesh.n_faces(), static_cast<size_t>(n * 5));
  EXPECT_LT(MeasureCircularity(surface.mesh).max_concyclicity, 1e-10);
}

TEST(ClosedCanalTest, ACurveWhoseReflectionsTurnEveryFrameLeavesTheMeshOpen) {
  const int n = 10, m = 4;
  const CircularStripInput in = AsymmetricInput({2.0, -1.0, 0.0}, 1.0);
  const Eigen::Matrix3d loop = LoopReflection(in.curve);
  EXPECT_GT((loop * loop - Eigen::Matrix3d::Identity()).norm(), 1e-3);
  double rotation = 0.0;
  const Frame start = FrameOfAngles(in.curve, AnglesFromNormal(Eigen::Vector3d(1, 0, 0)));
  EXPECT_GT(FrameClosureAngle(loop, ClosingFrame(loop, start, &rotation)), 1.0);
  EXPECT_GT(FrameClosureAngle(loop, start), 1.0);
  ClosedCanalOptions options;
  options.segments = m;
  const ClosedCanalSurface s =
      BuildClosedCanalSurface(in, AnglesFromNormal(Eigen::Vector3d(1, 0, 0)), options);
  EXPECT_FALSE(s.frame_closes);
  EXPECT_FALSE(s.welded);
  // The strip still closes; every quad of the open mesh is circular, the seam shows the turn.
  for (int k = 0; k < n; ++k) EXPECT_LT(Concyclicity(s.closed.strip, k), 1e-12) << k;
  EXPECT_EQ(s.mesh.n_vertices(), static_cast<size_t>((n + 1) * (m + 1)));
  EXPECT_LT(MeasureCircularity(s.mesh).max_concyclicity, 1e-10);
  EXPECT_GT(ValueOf(s.measures, "seam_gap"), 1e-3);

  // A planar inscribed polygon: an even count gives the identity, an odd one a reflection.
  EXPECT_LT(
      (LoopReflection(ClosedInput(8, 0.0, false, {}, 1.0).curve) - Eigen::Matrix3d::Identity())
          .norm(),
      1e-12);
  EXPECT_NEAR(LoopReflection(ClosedInput(7, 0.0, false, {}, 1.0).curve).trace(), 1.0, 1e-12);
}

TEST(ClosedCanalTest, SameResultAtEveryScale) {
  const CircularStripInput in = ClosedInput(9, 0.4, true, {3.2, 0.3, 0.8}, 0.8);
  const ClosedCircularStrip unit = BuildClosedCircularStrip(in);
  for (double scale : {1e-6, 1e6}) {
    CircularStripInput scaled = in;
    for (Eigen::Vector3d& p : scaled.curve) p *= scale;
    scaled.first_point *= scale;
    for (double& l : scaled.lengths) l *= scale;
    const ClosedCircularStrip c = BuildClosedCircularStrip(scaled);
    EXPECT_EQ(c.closing_case, unit.closing_case);
    for (int k = 0; k < 9; ++k)
      EXPECT_LT((c.strip.q[k] / scale - unit.strip.q[k]).norm(), 1e-10) << scale << " " << k;
  }
}

TEST(ClosedCanalTest, BadInputIsRefused) {
  CircularStripInput in = ClosedInput(9, 0.4, true, {3.2, 0.3, 0.8}, 0.8);
  CircularStripInput two = in;
  two.curve.resize(2);
  two.lengths.resize(2);
  EXPECT_NE(InputErrorOf([&] { BuildClosedCircularStrip(two); }).find("at least three"),
            std::string::npos);
  CircularStripInput repeated = in;
  repeated.curve.push_back(in.curve[0]);
  repeated.lengths.push_back(0.8);
  EXPECT_NE(InputErrorOf([&] { BuildClosedCircularStrip(repeated); }).find("without repeating P_0"),
            std::string::npos);
  // A closing circle that folds the first quad is named.
  EXPECT_NE(InputErrorOf([&] {
              BuildClosedCircularStrip(AsymmetricInput({3.3, -0.2, 0.3}, 0.4));
            }).find("folds quad"),
            std::string::npos);
  ClosedCanalOptions options;
  options.segments = 0;
  EXPECT_NE(
      InputErrorOf([&] { BuildClosedCanalSurface(in, FrameAngles(), options); }).find("segments"),
      std::string::npos);
}

TEST(ClosedCanalTest, FarFromTheOriginAndRoundedTheClosingHolds) {
  const CircularStripInput in = ClosedInput(21, 0.25, true, {3.2, -0.2, 0.5}, 0.5);
  ClosedCanalOptions options;
  options.segments = 4;
  const FrameAngles angles = AnglesFromNormal(Eigen::Vector3d(1, 0, 0));
  const ClosedCanalSurface at_origin = BuildClosedCanalSurface(in, angles, options);
  ASSERT_TRUE(at_origin.welded);
  // Moved by 1e6: the same case, frame and ring (the construction runs about P_0).
  CircularStripInput far = in;
  const Eigen::Vector3d offset(1e6, -1e6, 1e6);
  for (Eigen::Vector3d& p : far.curve) p += offset;
  far.first_point += offset;
  const ClosedCanalSurface moved = BuildClosedCanalSurface(far, angles, options);
  EXPECT_EQ(moved.closed.closing_case, at_origin.closed.closing_case);
  EXPECT_TRUE(moved.frame_closes);
  EXPECT_TRUE(moved.welded);
  for (size_t k = 0; k < in.curve.size(); ++k)
    EXPECT_LT((moved.closed.strip.q[k] - offset - at_origin.closed.strip.q[k]).norm(), 1e-8);
  EXPECT_EQ(moved.mesh.n_vertices(), at_origin.mesh.n_vertices());
  // Rounded to six decimals: still closes (to its rounding) and welds.
  CircularStripInput rounded = in;
  for (Eigen::Vector3d& p : rounded.curve)
    for (int i = 0; i < 3; ++i) p[i] = std::round(p[i] * 1e6) / 1e6;
  const ClosedCanalSurface r = BuildClosedCanalSurface(rounded, angles, options);
  EXPECT_EQ(r.closed.closing_case, at_origin.closed.closing_case);
  EXPECT_TRUE(r.frame_closes) << ValueOf(r.measures, "frame_closure_deg");
  EXPECT_GT(ValueOf(r.measures, "frame_closure_deg"), 1e-12);
  EXPECT_TRUE(r.welded) << ValueOf(r.measures, "seam_gap");
  EXPECT_LT(ValueOf(r.measures, "max_concyclicity"), 1e-4);
}

TEST(ClosedCanalTest, ACoSphericalDesignRoundedStaysInCaseOne) {
  // The torus-like octagon (case 1) with a curve point moved off the common sphere by 1e-9: case
  // 2 would move Q_0 across the strip; within the tolerance the closing keeps it.
  CircularStripInput in = ClosedInput(8, 0.0, false, {3.5, 0.0, 0.8}, std::sqrt(0.89));
  in.curve[1] *= 1.0 + 1e-9;
  in.curve[1].z() += 1e-9;
  const ClosedCircularStrip c = BuildClosedCircularStrip(in);
  EXPECT_EQ(c.closing_case, 1);
  EXPECT_LT(c.start_shift, 1e-15);
  for (int k = 0; k < 8; ++k) EXPECT_LT(Concyclicity(c.strip, k), 1e-8) << k;
  EXPECT_GT(c.cosphericity, 1e-11);  // the miss is seen, and tolerated
  EXPECT_LT(c.cosphericity, 1e-6);
}

TEST(ClosedCanalTest, AFlatRingOfTrapezoidsCloses) {
  // Every point in z = 0: all circles lie in that plane (a sphere of infinite radius): case 1.
  const CircularStripInput in = ClosedInput(8, 0.0, false, {2.3, 0.0, 0.0}, 0.7);
  const ClosedCircularStrip c = BuildClosedCircularStrip(in);
  EXPECT_EQ(c.closing_case, 1);
  for (int k = 0; k < 8; ++k) {
    EXPECT_LT(Concyclicity(c.strip, k), 1e-12) << k;
    EXPECT_NEAR(c.strip.q[k].z(), 0.0, 1e-12);
  }
  EXPECT_LT(MeasureCircularity(ClosedStripMesh(c.strip)).folded_quads, 1);
}

}  // namespace
}  // namespace gproj::circular
