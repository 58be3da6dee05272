#include "gproj/problems/circular/cyclidic_surface.h"

#include <gtest/gtest.h>

#include <Eigen/Geometry>
#include <cmath>

#include "canal_test_util.h"
#include "gproj/geometry/mesh/circle.h"
#include "gproj/problems/circular/closed_canal.h"
#include "input_error_test_util.h"

namespace gproj::circular {
namespace {

using Eigen::Vector3d;

// A Dupin cyclide: the torus (R, r) about z inverted in the sphere about kCentre (radius² 4).
constexpr double kR = 2.0, kr = 0.7;
const Vector3d kCentre(0.3, -3.1, 1.7);

Vector3d Invert(const Vector3d& x) {
  return kCentre + 4.0 * (x - kCentre) / (x - kCentre).squaredNorm();
}
Vector3d InvertVector(const Vector3d& x, const Vector3d& v) {
  const Vector3d d = x - kCentre;
  return (v - 2.0 * d.dot(v) / d.squaredNorm() * d).normalized();
}
Vector3d Torus(double phi, double psi) {
  return {(kR + kr * std::cos(psi)) * std::cos(phi), (kR + kr * std::cos(psi)) * std::sin(phi),
          kr * std::sin(psi)};
}
// Distance of x from the cyclide, measured on the torus after inverting back.
double CyclideDistance(const Vector3d& x) {
  const Vector3d y = Invert(x);
  return std::abs(std::hypot(std::hypot(y.x(), y.y()) - kR, y.z()) - kr);
}

// The net of the torus's curvature lines φ_j = φ0 + j dφ (rows of the grid run along φ) and
// ψ_i = ψ0 + i dψ, inverted, with the exact frame at (0, 0).
CyclidicNet CyclideNet(int rows, int cols, double dphi, double dpsi) {
  GridShape shape;
  shape.rows = rows;
  shape.cols = cols;
  std::vector<Vector3d> points;
  const double phi0 = 0.2, psi0 = -0.3;
  for (int i = 0; i <= rows; ++i)
    for (int j = 0; j <= cols; ++j)
      points.push_back(Invert(Torus(phi0 + j * dphi, psi0 + i * dpsi)));
  const Vector3d x = Torus(phi0, psi0);
  const Vector3d d_phi(-std::sin(phi0), std::cos(phi0), 0.0);
  const Vector3d d_psi(-std::sin(psi0) * std::cos(phi0), -std::sin(psi0) * std::sin(phi0),
                       std::cos(psi0));
  Frame f;
  f.t1 = InvertVector(x, d_phi);
  f.t2 = InvertVector(x, d_psi);
  f.n = f.t1.cross(f.t2);
  return MakeCyclidicNet(shape, points, f);
}

Vector3d At(const PolyMesh& mesh, int v) {
  const auto& p = mesh.point(PolyMesh::VertexHandle(v));
  return {p[0], p[1], p[2]};
}

TEST(CyclidicSurfaceTest, PatchesOfAnInvertedTorusNetLieOnTheCyclide) {
  const CyclidicNet net = CyclideNet(3, 4, 0.35, 0.5);
  EXPECT_LT(MaxFaceFrameClosure(net), 1e-10);
  CyclidicSurfaceOptions options;
  options.segments = 6;
  const CyclidicSurface s = MeshCyclidicSurface(net, options);
  ASSERT_EQ(s.mesh.n_vertices(), 19u * 25u);
  EXPECT_EQ(s.mesh.n_faces(), 18u * 24u);
  double worst = 0.0;
  for (int v = 0; v < static_cast<int>(s.mesh.n_vertices()); ++v)
    worst = std::max(worst, CyclideDistance(At(s.mesh, v)));
  EXPECT_LT(worst, 1e-12);
  // The fine mesh follows curvature lines: every fine quad of a Dupin cyclide is circular.
  EXPECT_LT(MeasureCircularity(s.mesh).max_concyclicity, 1e-10);
  EXPECT_LT(ValueOf(s.measures, "max_tangent_angle_deg"), 1e-5);
  EXPECT_EQ(ValueOf(s.measures, "patches"), 12.0);
  // The net's vertices are fine vertices.
  for (int i = 0; i <= 3; ++i)
    for (int j = 0; j <= 4; ++j)
      EXPECT_LT((At(s.mesh, s.fine_shape.Vertex(6 * i, 6 * j)) - net.points[net.shape.Vertex(i, j)])
                    .norm(),
                1e-15);
}

TEST(CyclidicSurfaceTest, AWholeTorusRingWeldsIntoAClosedMesh) {
  // 8 patches once around φ: the last column repeats the first.
  const CyclidicNet net = CyclideNet(2, 8, 2.0 * M_PI / 8, 0.6);
  CyclidicSurfaceOptions options;
  options.segments = 4;
  options.weld_closed = true;
  const CyclidicSurface s = MeshCyclidicSurface(net, options);
  EXPECT_TRUE(s.welded);
  EXPECT_LT(ValueOf(s.measures, "seam_gap"), 1e-12);
  EXPECT_EQ(s.mesh.n_vertices(), 9u * 32u);
  EXPECT_EQ(s.mesh.n_faces(), 8u * 32u);
  for (int v = 0; v < static_cast<int>(s.mesh.n_vertices()); ++v)
    EXPECT_LT(CyclideDistance(At(s.mesh, v)), 1e-12);
}

TEST(CyclidicSurfaceTest, CanalMeshLiesOnTheSmoothSurfaceAlsoWithAStraightArc) {
  // With the default normal the first arc along the curve is straight: that patch is evaluated
  // after an inversion.
  const CircularStrip strip = BuildCircularStrip(BendingStripInput());
  const CyclidicStrip net = MakeCyclidicStrip(strip, AnglesFromNormal(DefaultCanalNormal(strip)));
  const CyclidicNet cyclidic = CyclidicNetOfStrip(net);
  EXPECT_TRUE(ArcFrom(strip.p[0], net.p_frames[0].t1, strip.p[1], "").straight);
  CyclidicSurfaceOptions options;
  options.segments = 6;
  const CyclidicSurface s = MeshCyclidicSurface(cyclidic, options);
  EXPECT_LT(MeasureCircularity(s.mesh).max_concyclicity, 1e-10);
  EXPECT_LT(ValueOf(s.measures, "max_tangent_angle_deg"), 1e-5);
  // The circular mesh between co-spherical circles (000 Fig. 13) is the smooth surface's
  // curvature-line net: its vertices are the fine mesh's on the circles C_k.
  const PolyMesh canal = MeshCanalSurface(net, 6);
  for (int k = 0; k <= 8; ++k)
    for (int j = 0; j <= 6; ++j) {
      const Vector3d fine = At(s.mesh, s.fine_shape.Vertex(j, 6 * k));
      EXPECT_LT((At(canal, k * 7 + j) - fine).norm(), 1e-10) << k << " " << j;
      EXPECT_LT(DistanceToCircle(fine, net.circles[k]), 1e-12);
    }
}

TEST(CyclidicSurfaceTest, AFlatNetIsItsOwnSmoothSurface) {
  // A rectangle grid in z = 0 with the frame along its edges: straight arcs in one plane.
  GridShape shape;
  shape.rows = 2;
  shape.cols = 3;
  std::vector<Vector3d> points;
  for (int i = 0; i <= 2; ++i)
    for (int j = 0; j <= 3; ++j) points.emplace_back(1.5 * j, 0.8 * i, 0.0);
  const CyclidicNet net =
      MakeCyclidicNet(shape, points, {Vector3d::UnitX(), Vector3d::UnitY(), Vector3d::UnitZ()});
  CyclidicSurfaceOptions options;
  options.segments = 4;
  const CyclidicSurface s = MeshCyclidicSurface(net, options);
  for (int r = 0; r <= 8; ++r)
    for (int q = 0; q <= 12; ++q)
      EXPECT_LT(
          (At(s.mesh, s.fine_shape.Vertex(r, q)) - Vector3d(1.5 * q / 4, 0.8 * r / 4, 0.0)).norm(),
          1e-12)
          << r << " " << q;
}

TEST(CyclidicSurfaceTest, ClosedCanalSurfaceClosesSmoothly) {
  CircularStripInput in;
  for (int k = 0; k < 11; ++k) {
    const double t = 2.0 * M_PI * k / 11;
    in.curve.push_back(3.0 *
                       Vector3d(std::cos(t), std::sin(t), 0.35 * std::sin(3.0 * t)).normalized());
  }
  in.first_point = Vector3d(3.2, -0.2, 0.5);
  in.lengths.assign(11, 0.5);
  ClosedCanalOptions closed_options;
  const ClosedCanalSurface c =
      BuildClosedCanalSurface(in, AnglesFromNormal(Vector3d::UnitX()), closed_options);
  ASSERT_TRUE(c.welded);
  CyclidicSurfaceOptions options;
  options.segments = 5;
  options.weld_closed = true;
  const CyclidicSurface s = MeshCyclidicSurface(CyclidicNetOfStrip(c.net), options);
  EXPECT_TRUE(s.welded);
  EXPECT_EQ(s.mesh.n_vertices(), 6u * 55u);
  EXPECT_LT(ValueOf(s.measures, "max_tangent_angle_deg"), 1e-5);
  EXPECT_LT(MeasureCircularity(s.mesh).max_concyclicity, 1e-10);
}

TEST(CyclidicSurfaceTest, NonCircularFacesShowInTheFrameClosureAndBadOptionsAreRefused) {
  CyclidicNet net = CyclideNet(2, 2, 0.35, 0.5);
  net = MakeCyclidicNet(
      net.shape,
      [&] {
        std::vector<Vector3d> p = net.points;
        p[4] += Vector3d(0.01, 0.02, -0.01);  // the middle vertex off its circles
        return p;
      }(),
      net.frames[0]);
  int face = -1;
  EXPECT_GT(MaxFaceFrameClosure(net, &face), 0.1);
  EXPECT_GE(face, 0);
  CyclidicSurfaceOptions options;
  options.segments = 0;
  EXPECT_NE(InputErrorOf([&] { MeshCyclidicSurface(net, options); }).find("segments"),
            std::string::npos);
  std::vector<Vector3d> repeated = net.points;
  repeated[1] = repeated[0];
  EXPECT_NE(
      InputErrorOf([&] { MakeCyclidicNet(net.shape, repeated, net.frames[0]); }).find("coincide"),
      std::string::npos);
}

TEST(CyclidicSurfaceTest, TheFrameOfLeastEnergyLowersEquationFive) {
  const CyclidicNet torus = CyclideNet(3, 4, 0.35, 0.5);
  const FrameAngles start = DefaultGridAngles(torus.shape, torus.points);
  const GridFrameFairing fair = FairGridFrame(torus.shape, torus.points, start);
  EXPECT_TRUE(fair.converged) << fair.message;
  EXPECT_LT(fair.final_energy, fair.initial_energy);
  const CyclidicNet best = MakeCyclidicNet(torus.shape, torus.points, fair.frame);
  EXPECT_NEAR(GridNetEnergy(best), fair.final_energy, 1e-10 * fair.final_energy);
  EXPECT_NEAR(GridNetEnergy(MakeCyclidicNet(torus.shape, torus.points,
                                            GridStartFrame(torus.shape, torus.points, start))),
              fair.initial_energy, 1e-10 * fair.initial_energy);
  // t2 keeps pointing down the first column.
  EXPECT_GT(fair.frame.t2.dot(torus.points[torus.shape.Vertex(1, 0)] - torus.points[0]), 0.0);
  CyclidicSurfaceOptions options;
  options.segments = 4;
  const CyclidicSurface s = MeshCyclidicSurface(best, options);
  EXPECT_LT(ValueOf(s.measures, "max_tangent_angle_deg"), 1e-5);
  EXPECT_LT(MeasureCircularity(s.mesh).max_concyclicity, 1e-10);
}

TEST(CyclidicSurfaceTest, LongArcsOfAFlatPatchFollowTheirCurvatureLines) {
  // One planar polar patch spanning up to 5 rad: on a flat (or spherical) patch both plane-circle
  // intersections carry consistent normals; continuity along the curvature line decides.
  for (double span : {1.0, 3.3, 5.0}) {
    GridShape shape;
    shape.rows = shape.cols = 1;
    std::vector<Vector3d> points;
    for (double r : {1.0, 1.6})
      for (double t : {0.0, span}) points.emplace_back(r * std::cos(t), r * std::sin(t), 0.0);
    const CyclidicNet net =
        MakeCyclidicNet(shape, points, {Vector3d::UnitY(), Vector3d::UnitX(), -Vector3d::UnitZ()});
    CyclidicSurfaceOptions options;
    options.segments = 8;
    const CyclidicSurface s = MeshCyclidicSurface(net, options);
    for (int r = 0; r <= 8; ++r)
      for (int q = 0; q <= 8; ++q) {
        const double radius = 1.0 + 0.6 * r / 8, t = span * q / 8;
        EXPECT_LT((At(s.mesh, s.fine_shape.Vertex(r, q)) -
                   Vector3d(radius * std::cos(t), radius * std::sin(t), 0.0))
                      .norm(),
                  1e-12)
            << span << " " << r << " " << q;
      }
    EXPECT_EQ(ValueOf(s.measures, "folded_fine_quads"), 0.0);
  }
}

TEST(CyclidicSurfaceTest, FrameJumpsAcrossAnArcAreMeasured) {
  CyclidicSurfaceOptions options;
  options.segments = 4;
  const CyclidicNet torus = CyclideNet(3, 4, 0.35, 0.5);
  // Frames that are not mirror images across an arc: the tangent planes disagree there.
  CyclidicNet jump = torus;
  for (int i = 0; i <= 3; ++i) {
    Frame& f = jump.frames[jump.shape.Vertex(i, 2)];
    f.t2 = Eigen::AngleAxisd(0.01, f.t1) * f.t2;
    f.n = f.t1.cross(f.t2);
  }
  const CyclidicSurface jumped = MeshCyclidicSurface(jump, options);
  EXPECT_GT(ValueOf(jumped.measures, "max_tangent_angle_deg"), 0.1);
  const CyclidicSurface good = MeshCyclidicSurface(torus, options);
  EXPECT_LT(ValueOf(good.measures, "max_tangent_angle_deg"), 1e-9);
  EXPECT_EQ(CyclidicSurfaceFault(good.measures, 1e-4), "");
}

TEST(CyclidicSurfaceTest, FarFromTheOriginTheSurfaceAndItsMeasuresAreTheSame) {
  const CyclidicNet torus = CyclideNet(2, 3, 0.35, 0.5);
  CyclidicNet far = torus;
  const Vector3d offset(1e5, -2e5, 3e5);
  for (Vector3d& p : far.points) p += offset;
  CyclidicSurfaceOptions options;
  options.segments = 5;
  const CyclidicSurface a = MeshCyclidicSurface(torus, options),
                        b = MeshCyclidicSurface(far, options);
  for (int v = 0; v < static_cast<int>(a.mesh.n_vertices()); ++v)
    EXPECT_LT((At(b.mesh, v) - offset - At(a.mesh, v)).norm(), 1e-9);
  EXPECT_LT(ValueOf(b.measures, "max_tangent_angle_deg"), 1e-6);
  EXPECT_EQ(ValueOf(b.measures, "folded_fine_quads"), 0.0);
}

}  // namespace
}  // namespace gproj::circular
