#include "gproj/problems/marionette/marionette_mesh.h"

#include <gtest/gtest.h>

#include <Eigen/Dense>
#include <cmath>
#include <random>

#include "gproj/constraints/marionette_planarity.h"
#include "gproj/geometry/mesh/quad_grid.h"
#include "input_error_test_util.h"

namespace gproj::marionette {
namespace {

// A plan with one singular vertex: n rhombic sectors of k × k quads around vertex 0 (inner
// valence n), warped and jittered so that no two quads are alike. Vertex 1 + s k + (i − 1) is
// step i of spoke s; sector s holds faces s k² .. (s + 1) k² − 1.
PolyMesh Star(int n, int k, double radius = 5.0) {
  std::vector<Eigen::Vector2d> xy = {Eigen::Vector2d::Zero()};
  auto e = [&](int s) {
    const double a = 2 * M_PI * (s % n) / n;
    return Eigen::Vector2d(std::cos(a), std::sin(a));
  };
  auto spoke = [&](int s, int i) { return i == 0 ? 0 : 1 + (s % n) * k + (i - 1); };
  auto inner = [&](int s, int i, int j) { return 1 + n * k + s * k * k + (i - 1) * k + (j - 1); };
  for (int s = 0; s < n; ++s)
    for (int i = 1; i <= k; ++i) xy.push_back(radius * i / k * e(s));
  for (int s = 0; s < n; ++s)
    for (int i = 1; i <= k; ++i)
      for (int j = 1; j <= k; ++j) xy.push_back(radius * (i * e(s) + j * e(s + 1)) / k);
  PolyMesh mesh;
  for (size_t v = 0; v < xy.size(); ++v) {
    const double x = xy[v].x(), y = xy[v].y(), h = 0.06 * radius / k;
    mesh.add_vertex({x + 0.04 * radius * std::sin(0.7 * y) + h * std::sin(12.9898 * v + 1.0),
                     y + 0.04 * radius * std::cos(0.6 * x) + h * std::sin(78.233 * v + 2.0), 0.0});
  }
  auto id = [&](int s, int i, int j) {
    return PolyMesh::VertexHandle(j == 0 ? spoke(s, i) : i == 0 ? spoke(s + 1, j) : inner(s, i, j));
  };
  for (int s = 0; s < n; ++s)
    for (int i = 0; i < k; ++i)
      for (int j = 0; j < k; ++j)
        mesh.add_face({id(s, i, j), id(s, i + 1, j), id(s, i + 1, j + 1), id(s, i, j + 1)});
  return mesh;
}

// Heights on the n spokes of Star(n, k), all 1.5 at the centre.
std::vector<MarionetteGuide> SpokeGuides(int n, int k, int skip = -1) {
  std::vector<MarionetteGuide> guides;
  for (int s = 0; s < n; ++s) {
    if (s == skip) continue;
    MarionetteGuide g;
    g.start = 0;
    g.next = 1 + s * k;
    for (int i = 0; i <= k; ++i)
      g.values.push_back(1.5 - 0.05 * i * i + 0.2 * (std::sin(s + 0.3 * i) - std::sin(s)));
    guides.push_back(g);
  }
  return guides;
}

MarionetteLines Vertical(const PolyMesh& plan) { return MakeMarionetteLines(plan, {}); }

Eigen::VectorXd SolveGP(const MarionetteLines& lines, const std::vector<MarionetteTarget>& guides,
                        int* steps = nullptr) {
  Problem problem = MakeMarionetteMeshProblem(lines, guides);
  const SolverSummary s = Solve(MarionetteMeshSolverOptions(lines.projection), &problem);
  EXPECT_NE(s.termination, TerminationType::kFailure) << s.FullReport();
  if (steps != nullptr) *steps = s.num_steps();
  return MarionetteMeshParameters(problem);
}

TEST(MarionettePatchTest, ValenceSixStarSplitsIntoSixGridPatchesAndSixStrips) {
  const PolyMesh plan =
      ReadMesh(std::string(GPROJ_SOURCE_DIR) + "/examples/data/marionette_plan_valence6.obj");
  ASSERT_EQ(plan.n_faces(), 150u);
  const MarionettePatchLayout layout = DecomposeIntoPatches(plan);
  // The valence-6 centre and the six outer corners (boundary valence 2).
  EXPECT_EQ(layout.singular_vertices.size(), 7u);
  EXPECT_EQ(layout.singular_vertices[0], 0);
  EXPECT_EQ(layout.separatrices.size(), 6u);
  for (const auto& sep : layout.separatrices) EXPECT_EQ(sep.size(), 6u);
  ASSERT_EQ(layout.patches.size(), 6u);
  for (int p = 0; p < 6; ++p) {
    EXPECT_EQ(layout.patches[p].rows, 5);
    EXPECT_EQ(layout.patches[p].cols, 5);
    EXPECT_EQ(layout.patches[p].corners.size(), 4u);
    EXPECT_EQ(layout.patch_of_face[25 * p + 12], p);
  }
  // Each face strip turns around the centre through two neighbouring sectors: six strips of
  // patches, five faces wide, 30 face strips, so 31 guide values (the six spokes).
  EXPECT_EQ(layout.num_face_strips, 30);
  EXPECT_EQ(layout.num_closed_face_strips, 0);
  ASSERT_EQ(layout.patch_strips.size(), 6u);
  for (const auto& strip : layout.patch_strips) {
    EXPECT_EQ(strip.patches.size(), 2u);
    EXPECT_EQ(strip.face_strips.size(), 5u);
  }
  EXPECT_EQ(layout.design_dimension(), 31);
}

TEST(MarionettePatchTest, DesignDimensionIsTheNullityOfThePlanarityRows) {
  for (int n : {3, 5, 6}) {
    const MarionetteLines lines = Vertical(Star(n, 3));
    const int nv = lines.num_vertices(), nf = static_cast<int>(lines.mesh.n_faces());
    Eigen::MatrixXd p = Eigen::MatrixXd::Zero(nf, nv);
    for (auto fh : lines.mesh.faces()) {
      int q[4], k = 0;
      for (auto v : lines.mesh.fv_range(fh)) q[k++] = v.idx();
      double al, be;
      ASSERT_TRUE(MarionettePlanarity::PlanCoefficients(
          lines.origin[q[0]].head<2>(), lines.origin[q[1]].head<2>(), lines.origin[q[2]].head<2>(),
          lines.origin[q[3]].head<2>(), &al, &be));
      p.row(fh.idx())(q[0]) = -1 + al + be;
      p.row(fh.idx())(q[1]) = -al;
      p.row(fh.idx())(q[2]) = 1;
      p.row(fh.idx())(q[3]) = -be;
    }
    Eigen::FullPivLU<Eigen::MatrixXd> lu(p);
    lu.setThreshold(1e-10);
    EXPECT_EQ(nv - lu.rank(), DecomposeIntoPatches(lines.mesh).design_dimension()) << n;
    EXPECT_EQ(nv - lu.rank(), n * 3 + 1) << n;
  }
}

class MarionetteSingularTest : public ::testing::TestWithParam<int> {};

TEST_P(MarionetteSingularTest, SpokesLiftEveryPatchAndGuidedProjectionAgrees) {
  const int n = GetParam(), k = 4;
  const MarionetteLines lines = Vertical(Star(n, k));
  const MarionettePatchLayout layout = DecomposeIntoPatches(lines.mesh);
  const auto guides = ResolveMarionetteGuides(lines.mesh, SpokeGuides(n, k), {});
  EXPECT_EQ(static_cast<int>(guides.size()), layout.design_dimension());
  const MarionetteMeshLift lift = LiftMarionetteMesh(lines, layout, guides);
  EXPECT_EQ(static_cast<int>(lift.patch_order.size()), n);
  EXPECT_TRUE(lift.redundant_faces.empty());
  for (const auto& g : guides) EXPECT_EQ(lift.t[g.vertex], g.height);
  EXPECT_LE(MaxLiftPlanarity(lines, lift.t), 1e-12);
  EXPECT_GT(lift.t.maxCoeff() - lift.t.minCoeff(), 0.3);  // not flat

  int steps = 0;
  const Eigen::VectorXd gp = SolveGP(lines, guides, &steps);
  EXPECT_EQ(steps, 1);
  EXPECT_LE((gp - lift.t).norm(), 1e-10 * lift.t.norm());
  EXPECT_LE(MaxLiftPlanarity(lines, gp), 1e-12);
}

INSTANTIATE_TEST_SUITE_P(Valences, MarionetteSingularTest, ::testing::Values(3, 5, 6),
                         [](const ::testing::TestParamInfo<int>& info) {
                           return "Valence" + std::to_string(info.param);
                         });

TEST(MarionetteSingularTest, ShippedValenceSixExampleLiftsFromItsSpokes) {
  const std::string plan_path =
      std::string(GPROJ_SOURCE_DIR) + "/examples/data/marionette_plan_valence6.obj";
  const MarionetteLines lines = Vertical(ReadMesh(plan_path, MeshRequirements{true}));
  const auto guides = ResolveMarionetteGuides(lines.mesh, SpokeGuides(6, 5), {});
  const MarionetteMeshLift lift =
      LiftMarionetteMesh(lines, DecomposeIntoPatches(lines.mesh), guides);
  EXPECT_LE(MaxLiftPlanarity(lines, lift.t), 1e-12);
  EXPECT_LE((SolveGP(lines, guides) - lift.t).norm(), 1e-10 * lift.t.norm());
}

TEST(MarionetteSingularTest, MissingSpokeLeavesItsTwoPatchesUnderDetermined) {
  const MarionetteLines lines = Vertical(Star(6, 3));
  const auto layout = DecomposeIntoPatches(lines.mesh);
  const auto guides = ResolveMarionetteGuides(lines.mesh, SpokeGuides(6, 3, /*skip=*/5), {});
  const std::string error = InputErrorOf([&] { LiftMarionetteMesh(lines, layout, guides); });
  // Spoke 5 separates sectors 4 and 5; its vertices 16, 17, 18 are left.
  EXPECT_NE(error.find("the guides do not determine patches 4, 5: "), std::string::npos) << error;
  EXPECT_NE(error.find("(16, 17, 18, "), std::string::npos) << error;
  EXPECT_NE(error.find("no guide crosses strip of patches"), std::string::npos) << error;
  EXPECT_NE(error.find("needs 19 values"), std::string::npos) << error;
}

TEST(MarionetteSingularTest, ExtraGuideOnTheBoundaryIsRefusedUnlessCompatible) {
  const int k = 3;
  const MarionetteLines lines = Vertical(Star(6, k));
  const auto layout = DecomposeIntoPatches(lines.mesh);
  std::vector<MarionetteGuide> guides = SpokeGuides(6, k);
  const MarionetteMeshLift exact =
      LiftMarionetteMesh(lines, layout, ResolveMarionetteGuides(lines.mesh, guides, {}));
  // The outer side of sector 0: from the end of spoke 0 along the boundary (k + 1 vertices).
  const std::vector<int> side = TraceMeshPolyline(lines.mesh, k, 1 + 6 * k + (k - 1) * k, k + 1);
  ASSERT_EQ(side.size(), static_cast<size_t>(k + 1));
  MarionetteGuide extra;
  extra.start = side[0];
  extra.next = side[1];
  extra.where = "extra.txt:1";
  for (int v : side) extra.values.push_back(exact.t[v]);
  guides.push_back(extra);
  // Values of the exact lift: over-determined but compatible, reported, not refused.
  const MarionetteMeshLift again =
      LiftMarionetteMesh(lines, layout, ResolveMarionetteGuides(lines.mesh, guides, {}));
  EXPECT_FALSE(again.redundant_faces.empty());
  EXPECT_EQ(again.over_determined_patches, std::vector<int>{0});
  EXPECT_LE((again.t - exact.t).norm(), 1e-12 * exact.t.norm());
  // Other values: incompatible, refused naming a face of patch 0.
  guides.back().values[2] += 0.1;
  const std::string error = InputErrorOf(
      [&] { LiftMarionetteMesh(lines, layout, ResolveMarionetteGuides(lines.mesh, guides, {})); });
  EXPECT_EQ(error.rfind("incompatible guides: face ", 0), 0u) << error;
  EXPECT_NE(error.find("(patch 0, vertices "), std::string::npos) << error;
}

TEST(MarionetteSingularTest, GuideErrorsNameTheGuide) {
  const PolyMesh mesh = Star(6, 3);
  MarionetteGuide g;
  g.start = 0;
  g.next = 1;
  g.where = "g.txt:4";
  g.values = {1, 2, 3, 4, 5};  // the spoke has 4 vertices
  EXPECT_NE(InputErrorOf([&] {
              ResolveMarionetteGuides(mesh, {g}, {});
            }).find("g.txt:4: the polyline from vertex 0 through 1 has only 4 vertices"),
            std::string::npos);
  g.next = 2;  // not a neighbour of 0
  g.values = {1, 2};
  EXPECT_NE(InputErrorOf([&] {
              ResolveMarionetteGuides(mesh, {g}, {});
            }).find("g.txt:4: vertices 0 and 2 are not joined by an edge"),
            std::string::npos);
  g.next = 1;
  EXPECT_NE(InputErrorOf([&] {
              ResolveMarionetteGuides(mesh, {g}, {{1, 7.0}});
            }).find("incompatible guides: vertex 1 gets 2.000000 from g.txt:4 and 7.000000"),
            std::string::npos);
}

TEST(MarionetteSingularTest, RefusesDegeneratePlanViewNamingTheFace) {
  PolyMesh mesh = Star(6, 3);
  // The centre onto the line through the first steps of spokes 0 and 1: face 0 has three
  // collinear plan vertices when its fourth is propagated.
  const auto a = mesh.point(PolyMesh::VertexHandle(1)), b = mesh.point(PolyMesh::VertexHandle(4));
  mesh.set_point(PolyMesh::VertexHandle(0), 0.5 * (a + b));
  const MarionetteLines lines = Vertical(mesh);
  const auto guides = ResolveMarionetteGuides(mesh, SpokeGuides(6, 3), {});
  const std::string error =
      InputErrorOf([&] { LiftMarionetteMesh(lines, DecomposeIntoPatches(mesh), guides); });
  EXPECT_EQ(error.rfind("face 0 (patch 0) has a degenerate plan view: its vertices ", 0), 0u)
      << error;
  EXPECT_NE(error.find("are collinear in x, y"), std::string::npos) << error;
}

TEST(MarionetteSingularTest, GridThroughTheGeneralPathEqualsTheGridLift) {
  QuadGridOptions o;
  o.nu = 8;
  o.nv = 6;
  o.noise = 0.15;
  const PolyMesh grid = MakeQuadGrid(o);
  const MarionettePlan plan = MakeMarionettePlan(grid);
  Eigen::VectorXd row(plan.cols + 1), column(plan.rows + 1);
  for (int j = 0; j <= plan.cols; ++j) row[j] = std::sin(0.8 * j);
  for (int i = 0; i <= plan.rows; ++i) column[i] = 0.3 * i - 0.1 * i * i;
  column[0] = row[0];
  std::vector<MarionetteTarget> guides;
  for (int j = 0; j <= plan.cols; ++j) guides.push_back({plan.Vertex(0, j), row[j]});
  for (int i = 1; i <= plan.rows; ++i) guides.push_back({plan.Vertex(i, 0), column[i]});
  const MarionetteLines lines = Vertical(grid);
  const Eigen::VectorXd expected = LiftMarionette(plan, row, column);
  const MarionetteMeshLift lift = LiftMarionetteMesh(lines, DecomposeIntoPatches(grid), guides);
  EXPECT_LE((lift.t - expected).norm(), 1e-12 * expected.norm());
}

// A tower plan: (rows + 1) × (cols + 1) vertices on a cylinder of radius 10 about the z axis over
// 270°, in grid order; `jitter` moves every vertex (angle, height and radius) at random.
PolyMesh Tower(int rows, int cols, double jitter) {
  std::mt19937 rng(11);
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  PolyMesh mesh;
  for (int i = 0; i <= rows; ++i)
    for (int j = 0; j <= cols; ++j) {
      const double a = 1.5 * M_PI * (j + jitter * u(rng)) / cols;
      const double z = 30.0 * (i + jitter * u(rng)) / rows, r = 10.0 * (1 + 0.1 * jitter * u(rng));
      mesh.add_vertex({r * std::cos(a), r * std::sin(a), z});
    }
  auto v = [&](int i, int j) { return PolyMesh::VertexHandle(i * (cols + 1) + j); };
  for (int i = 0; i < rows; ++i)
    for (int j = 0; j < cols; ++j)
      mesh.add_face({v(i, j), v(i + 1, j), v(i + 1, j + 1), v(i, j + 1)});
  return mesh;
}

// Guide values on row 0 and column 0 of a (rows + 1) × (cols + 1)-vertex grid.
std::vector<MarionetteTarget> GridGuides(int rows, int cols, const std::function<double(int)>& row,
                                         const std::function<double(int)>& column) {
  std::vector<MarionetteTarget> guides;
  for (int j = 0; j <= cols; ++j) guides.push_back({j, row(j)});
  for (int i = 1; i <= rows; ++i) guides.push_back({i * (cols + 1), column(i)});
  return guides;
}

MarionetteProjectionOptions Cylindrical() {
  MarionetteProjectionOptions o;
  o.type = MarionetteProjection::kCylindrical;
  o.axis_point = Eigen::Vector3d(0, 0, -4);
  o.axis_direction = Eigen::Vector3d(0, 0, 2);
  return o;
}

TEST(MarionetteProjectionTest, ConstantRadiiOverACylinderPlanGiveACylinder) {
  const MarionetteLines lines = MakeMarionetteLines(Tower(6, 9, 0.0), Cylindrical());
  const auto guides = GridGuides(
      6, 9, [](int) { return 7.0; }, [](int) { return 7.0; });
  const MarionetteMeshLift lift =
      LiftMarionetteMesh(lines, DecomposeIntoPatches(lines.mesh), guides);
  for (int v = 0; v < lines.num_vertices(); ++v) {
    const Eigen::Vector3d p = lines.Point(v, lift.t[v]);
    EXPECT_NEAR(p.head<2>().norm(), 7.0, 7e-12) << v;
  }
  EXPECT_LE(MaxLiftPlanarity(lines, lift.t), 1e-12);
}

TEST(MarionetteProjectionTest, CylindricalLiftOfAJitteredTowerAgreesWithGuidedProjection) {
  const MarionetteLines lines = MakeMarionetteLines(Tower(8, 10, 0.2), Cylindrical());
  const auto guides = GridGuides(
      8, 10, [](int j) { return 9.0 + 0.8 * std::sin(0.6 * j); },
      [](int i) { return 9.0 - 0.04 * i * i + 0.3 * std::sin(0.9 * i); });
  const MarionetteMeshLift lift =
      LiftMarionetteMesh(lines, DecomposeIntoPatches(lines.mesh), guides);
  EXPECT_LE(MaxLiftPlanarity(lines, lift.t), 1e-12);
  EXPECT_GT((lift.t - lines.plan_parameters).cwiseAbs().maxCoeff(), 0.5);  // really moved
  int steps = 0;
  const Eigen::VectorXd gp = SolveGP(lines, guides, &steps);
  EXPECT_GT(steps, 1);  // bilinear rows: several iterations
  EXPECT_LE((gp - lift.t).norm(), 1e-8 * lift.t.norm());
  EXPECT_LE(MaxLiftPlanarity(lines, gp), 1e-10);
}

TEST(MarionetteProjectionTest, CentralLiftScalesAPlanarPlanAndAgreesWithGuidedProjection) {
  QuadGridOptions o;
  o.nu = 7;
  o.nv = 9;
  o.a = o.b = 0.0;
  o.noise = 0.2;
  PolyMesh plan = MakeQuadGrid(o);
  for (auto v : plan.vertices()) plan.set_point(v, {plan.point(v)[0], plan.point(v)[1], 3.0});
  MarionetteProjectionOptions central;
  central.type = MarionetteProjection::kCentral;
  central.centre = Eigen::Vector3d(0.2, -0.1, 0.0);
  const MarionetteLines lines = MakeMarionetteLines(plan, central);
  const auto layout = DecomposeIntoPatches(lines.mesh);
  // Guides 1.7 times the plan's distances: the lift is the plan scaled about the centre.
  const auto scaled = GridGuides(
      6, 8, [&](int j) { return 1.7 * lines.plan_parameters[j]; },
      [&](int i) { return 1.7 * lines.plan_parameters[i * 9]; });
  const MarionetteMeshLift similar = LiftMarionetteMesh(lines, layout, scaled);
  EXPECT_LE((similar.t - 1.7 * lines.plan_parameters).cwiseAbs().maxCoeff(), 1e-12 * 1.7 * 3.0);
  // Generic guides.
  const auto guides = GridGuides(
      6, 8, [&](int j) { return lines.plan_parameters[j] * (1.0 + 0.1 * std::sin(j)); },
      [&](int i) { return lines.plan_parameters[i * 9] * (1.0 + 0.05 * i); });
  const MarionetteMeshLift lift = LiftMarionetteMesh(lines, layout, guides);
  EXPECT_LE(MaxLiftPlanarity(lines, lift.t), 1e-12);
  const Eigen::VectorXd gp = SolveGP(lines, guides);
  EXPECT_LE((gp - lift.t).norm(), 1e-8 * lift.t.norm());
  EXPECT_LE(MaxLiftPlanarity(lines, gp), 1e-10);
}

TEST(MarionetteProjectionTest, RefusesLinesParallelToTheFacePlaneAndVerticesOnTheAxis) {
  QuadGridOptions o;
  o.nu = o.nv = 3;
  o.a = o.b = 0.0;
  PolyMesh plan = MakeQuadGrid(o);  // flat, z = 0
  MarionetteProjectionOptions central;
  central.type = MarionetteProjection::kCentral;
  central.centre = Eigen::Vector3d(5, 5, 0);  // in the plane of the plan
  const MarionetteLines lines = MakeMarionetteLines(plan, central);
  const auto guides = GridGuides(
      2, 2, [&](int j) { return lines.plan_parameters[j]; },
      [&](int i) { return lines.plan_parameters[3 * i]; });
  const std::string error =
      InputErrorOf([&] { LiftMarionetteMesh(lines, DecomposeIntoPatches(plan), guides); });
  EXPECT_EQ(error.rfind("face 0 (patch 0): the line of vertex 4 is parallel to the plane", 0), 0u)
      << error;

  MarionetteProjectionOptions cylindrical;
  cylindrical.type = MarionetteProjection::kCylindrical;
  cylindrical.axis_point = Eigen::Vector3d(plan.point(PolyMesh::VertexHandle(4))[0],
                                           plan.point(PolyMesh::VertexHandle(4))[1], 0);
  cylindrical.axis_direction = Eigen::Vector3d(0, 0, 1);
  EXPECT_EQ(InputErrorOf([&] { MakeMarionetteLines(plan, cylindrical, "p.obj"); }),
            "p.obj: vertex 4 lies on the axis, so it has no line perpendicular to it");
}

}  // namespace
}  // namespace gproj::marionette
