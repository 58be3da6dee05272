#include "gproj/problems/marionette/marionette_polygons.h"

#include <gtest/gtest.h>

#include <Eigen/LU>
#include <Eigen/QR>
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <map>
#include <random>

#include "gproj/problems/marionette/marionette.h"

namespace gproj::marionette {
namespace {

// Point (i, j) of the triangular lattice of unit spacing.
Eigen::Vector2d Lattice(int i, int j) { return {i + 0.5 * j, 0.5 * std::sqrt(3.0) * j}; }

// Builds a plan from polygons of plan points, merging equal points.
class PlanBuilder {
 public:
  int Vertex(const Eigen::Vector2d& p) {
    const auto key = std::make_pair(std::llround(p.x() * 1e6), std::llround(p.y() * 1e6));
    const auto it = index_.find(key);
    if (it != index_.end()) return it->second;
    const int v = static_cast<int>(mesh_.add_vertex(PolyMesh::Point(p.x(), p.y(), 0)).idx());
    index_[key] = v;
    return v;
  }
  // Adds the polygon, counter-clockwise in the plan.
  void Face(std::vector<Eigen::Vector2d> points) {
    double area = 0.0;
    for (size_t k = 0; k < points.size(); ++k) {
      const auto& a = points[k];
      const auto& b = points[(k + 1) % points.size()];
      area += a.x() * b.y() - a.y() * b.x();
    }
    if (area < 0.0) std::reverse(points.begin(), points.end());
    std::vector<PolyMesh::VertexHandle> handles;
    for (const auto& p : points) handles.push_back(mesh_.vertex_handle(Vertex(p)));
    ASSERT_TRUE(mesh_.add_face(handles).is_valid());
  }
  const PolyMesh& mesh() const { return mesh_; }

 private:
  PolyMesh mesh_;
  std::map<std::pair<long long, long long>, int> index_;
};

// Lattice vertices (i, j) with 0 <= i, j <= n and their triangles.
bool Inner(int i, int j, int n) { return i > 0 && j > 0 && i < n && j < n; }

// Kagome (trihexagonal) pattern over an n × n lattice parallelogram: a triangle in every lattice
// triangle (its edges' midpoints), a hexagon around every inner lattice vertex.
PolyMesh Kagome(int n) {
  PlanBuilder b;
  auto mid = [](Eigen::Vector2d p, Eigen::Vector2d q) { return Eigen::Vector2d(0.5 * (p + q)); };
  for (int i = 0; i < n; ++i)
    for (int j = 0; j < n; ++j) {
      const auto p = Lattice(i, j), q = Lattice(i + 1, j), r = Lattice(i, j + 1),
                 s = Lattice(i + 1, j + 1);
      b.Face({mid(p, q), mid(q, r), mid(r, p)});
      b.Face({mid(q, s), mid(s, r), mid(r, q)});
    }
  const int di[6] = {1, 0, -1, -1, 0, 1}, dj[6] = {0, 1, 1, 0, -1, -1};
  for (int i = 1; i < n; ++i)
    for (int j = 1; j < n; ++j) {
      std::vector<Eigen::Vector2d> hexagon;
      for (int k = 0; k < 6; ++k)
        hexagon.push_back(mid(Lattice(i, j), Lattice(i + di[k], j + dj[k])));
      b.Face(hexagon);
    }
  return b.mesh();
}

// Dual-Kagome (rhombille) pattern: a rhombus across every inner lattice edge, between its two
// ends and the centres of its two triangles.
PolyMesh DualKagome(int n) {
  PlanBuilder b;
  auto centre = [](Eigen::Vector2d p, Eigen::Vector2d q, Eigen::Vector2d r) {
    return Eigen::Vector2d((p + q + r) / 3.0);
  };
  for (int i = 0; i < n; ++i)
    for (int j = 0; j < n; ++j) {
      const auto p = Lattice(i, j), q = Lattice(i + 1, j), r = Lattice(i, j + 1),
                 s = Lattice(i + 1, j + 1);
      // The diagonal q r inside the cell; the edges p q (i, j > 0) and p r (i > 0) with the cell
      // below / to the left.
      b.Face({q, centre(q, s, r), r, centre(p, q, r)});
      if (j > 0) b.Face({p, centre(p, q, r), q, centre(p, q, Lattice(i + 1, j - 1))});
      if (i > 0) b.Face({r, centre(p, q, r), p, centre(p, r, Lattice(i - 1, j + 1))});
    }
  return b.mesh();
}

// A honeycomb of rows × cols hexagons (centred at lattice points, corners at the centres of
// the lattice triangles), each split into six quads (centre, edge midpoint, corner, edge
// midpoint).
PolyMesh SubdividedHexagons(int rows, int cols) {
  PlanBuilder b;
  const int di[6] = {1, 0, -1, -1, 0, 1}, dj[6] = {0, 1, 1, 0, -1, -1};
  for (int i = 0; i < rows; ++i)
    for (int j = 0; j < cols; ++j) {
      const Eigen::Vector2d c = Lattice(i, j);
      std::vector<Eigen::Vector2d> corner;
      for (int k = 0; k < 6; ++k)
        corner.push_back((c + Lattice(i + di[k], j + dj[k]) +
                          Lattice(i + di[(k + 1) % 6], j + dj[(k + 1) % 6])) /
                         3.0);
      for (int k = 0; k < 6; ++k) {
        const Eigen::Vector2d before = 0.5 * (corner[(k + 5) % 6] + corner[k]);
        const Eigen::Vector2d after = 0.5 * (corner[k] + corner[(k + 1) % 6]);
        b.Face({c, before, corner[k], after});
      }
    }
  return b.mesh();
}

std::map<int, int> FaceSizes(const PolyMesh& m) {
  std::map<int, int> out;
  for (auto f : m.faces()) ++out[static_cast<int>(m.valence(f))];
  return out;
}

// 002 Appendix B: the design space's dimension by rank against the estimate of eq. 16,
// N − Σ (n_F − 3), on patterns of Fig. 16 (our own patches of them: the paper's counts 31, 29, 21
// belong to its figure's patches). Kagome and dual-Kagome (rhombille: a honeycomb's hexagons
// split in three) patches meet the estimate; a honeycomb whose hexagons are split in six has
// one dependent row per hexagon surrounded by hexagons (its ring of quads closes up: the
// "closed curves" for which 002 says eq. 16 is not exact).
TEST(MarionettePolygonsTest, DesignSpaceOfPeriodicPatterns) {
  struct Case {
    const char* name;
    PolyMesh plan;
    int dependent_rows;
  };
  const std::vector<Case> cases = {{"Kagome", Kagome(8), 0},
                                   {"dual Kagome (rhombille)", DualKagome(8), 0},
                                   {"hexagons split in six, 3 x 9", SubdividedHexagons(3, 9), 7},
                                   {"hexagons split in six, 4 x 5", SubdividedHexagons(4, 5), 6}};
  for (const Case& c : cases) {
    const MarionetteDesignSpace space = MeasureMarionetteDesignSpace(c.plan);
    std::printf("%s: %d vertices,", c.name, space.vertices);
    for (const auto& [size, count] : FaceSizes(c.plan)) std::printf(" %d %d-gons,", count, size);
    std::printf(" eq. 16 %d, rank-based dimension %d\n", space.estimate, space.dimension);
    // The sparse QR's rank against a dense, fully pivoted LU.
    const Eigen::MatrixXd dense(PolygonPlanarityMatrix(c.plan));
    Eigen::FullPivLU<Eigen::MatrixXd> lu(dense);
    EXPECT_EQ(space.rank, static_cast<int>(lu.rank())) << c.name;
    EXPECT_EQ(space.dimension - space.estimate, c.dependent_rows) << c.name;
    EXPECT_EQ(static_cast<int>(IndependentHeights(c.plan).size()), space.dimension) << c.name;
  }
}

// Heights of the paraboloid z = x² + y² make every face inscribed in a circle planar (Kagome's
// regular polygons, the split hexagons' right-angled kites). Prescribed at the independent
// vertices only, the lift rebuilds them everywhere: the planarity rows fix the rest.
TEST(MarionettePolygonsTest, IndependentHeightsDetermineThePlanarLift) {
  for (const PolyMesh& plan : {Kagome(6), SubdividedHexagons(3, 4)}) {
    std::vector<std::pair<int, double>> heights;
    for (int v : IndependentHeights(plan)) {
      const auto& p = plan.point(plan.vertex_handle(v));
      heights.push_back({v, p[0] * p[0] + p[1] * p[1]});
    }
    const MarionettePolygonLift lift = LiftPolygonPlan(plan, heights);
    EXPECT_LT(lift.max_planarity, 1e-10);
    EXPECT_LT(lift.max_height_error, 1e-10);
    for (auto v : lift.mesh.vertices()) {
      const auto& p = lift.mesh.point(v);
      EXPECT_NEAR(p[2], p[0] * p[0] + p[1] * p[1], 1e-9) << v.idx();
      EXPECT_EQ(p[0], plan.point(v)[0]);  // the plan view is kept
    }
  }
}

// With fewer prescribed heights (two guide polylines of a Kagome patch and three isolated
// points), the fairness energy of 002 eq. 17 fixes the rest: planar faces, the heights met, and
// no more energy than another planar lift with the same prescribed heights (the paraboloid's).
TEST(MarionettePolygonsTest, FairnessFixesTheHeightsTheGuidesLeaveFree) {
  const PolyMesh plan = Kagome(6);
  std::vector<std::pair<int, double>> heights;
  auto paraboloid = [&](int v) {
    const auto& p = plan.point(plan.vertex_handle(v));
    return p[0] * p[0] + p[1] * p[1];
  };
  for (auto v : plan.vertices()) {
    const auto& p = plan.point(v);
    // Guides: the lowest row of midpoints and the leftmost column.
    if (p[1] < 1e-9 || std::abs(p[0] - p[1] / std::sqrt(3.0)) < 1e-9)
      heights.push_back({v.idx(), paraboloid(v.idx())});
  }
  const size_t guides = heights.size();
  for (int v : {30, 60, 90}) heights.push_back({v, paraboloid(v)});
  const MarionettePolygonLift lift = LiftPolygonPlan(plan, heights);
  std::printf("Kagome 6: %zu guide heights + 3 points, %d fairness triples, F = %.4g\n", guides,
              lift.fairness_triples, lift.fairness);
  EXPECT_LT(lift.max_planarity, 1e-9);
  EXPECT_LT(lift.max_height_error, 1e-9);
  double paraboloid_energy = 0.0;
  for (const auto& t : StraightTriples(plan)) {
    const double second = paraboloid(t[0]) - 2 * paraboloid(t[1]) + paraboloid(t[2]);
    paraboloid_energy += second * second;
  }
  EXPECT_LE(lift.fairness, paraboloid_energy * (1 + 1e-9));
  EXPECT_GT(lift.fairness_triples, 100);
}

TEST(MarionettePolygonsTest, RefusesUndeterminedOrContradictoryHeights) {
  const PolyMesh plan = Kagome(4);
  try {
    LiftPolygonPlan(plan, {{0, 1.0}, {1, 2.0}});
    ADD_FAILURE() << "two heights cannot fix a lift";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("stay free"), std::string::npos) << e.what();
  }
  // Every vertex of a hexagon prescribed, one of them off the plane of the others.
  std::vector<std::pair<int, double>> heights;
  for (auto f : plan.faces()) {
    if (plan.valence(f) != 6) continue;
    for (auto v : plan.fv_range(f)) heights.push_back({v.idx(), heights.empty() ? 1.0 : 0.0});
    break;
  }
  for (int v : IndependentHeights(plan)) {
    bool given = false;
    for (const auto& h : heights) given |= h.first == v;
    if (!given) heights.push_back({v, 0.0});
  }
  try {
    LiftPolygonPlan(plan, heights);
    ADD_FAILURE() << "a bent hexagon";
  } catch (const InputError& e) {
    // The lifted vertex (the only height that disagrees) is the one named.
    EXPECT_NE(
        std::string(e.what()).find("vertex " + std::to_string(heights[0].first) + " contradicts"),
        std::string::npos)
        << e.what();
  }
  EXPECT_THROW(LiftPolygonPlan(plan, {{100000, 1.0}}), InputError);
  EXPECT_THROW(LiftPolygonPlan(plan, {{0, 1.0}, {0, 2.0}}), InputError);
}

// Closed curves around the origin: radius r (1 + e cos(θ + φ)) at N angles, shifted by `shift`.
std::vector<Eigen::Vector2d> Curve(int n, double r, double e, double phi,
                                   const Eigen::Vector2d& shift = Eigen::Vector2d::Zero()) {
  std::vector<Eigen::Vector2d> c;
  for (int i = 0; i < n; ++i) {
    const double t = 2 * M_PI * i / n;
    c.push_back(shift +
                r * (1 + e * std::cos(t + phi)) * Eigen::Vector2d(std::cos(t), std::sin(t)));
  }
  return c;
}

Eigen::VectorXd InnerHeights(int n) {
  Eigen::VectorXd z(n);
  for (int i = 0; i < n; ++i)
    z[i] = 1.0 + 0.3 * std::sin(2 * M_PI * i / n) + 0.1 * std::cos(6 * M_PI * i / n);
  return z;
}

// 002 Figs. 7–8, eq. 9: three rings of an asymmetric plan (every a ≠ 1) close in one way, which
// is the lift handed ring by ring (each ring's outer heights the next one's inner heights,
// 002 eq. 8); the inner curve is kept.
TEST(MarionettePolygonsTest, ClosedRingsHandTheirHeightsOutward) {
  const int n = 16;
  const std::vector<std::vector<Eigen::Vector2d>> curves = {
      Curve(n, 2.0, 0.10, 0.3), Curve(n, 3.0, 0.15, 0.9, {0.1, 0.0}),
      Curve(n, 4.2, 0.05, 1.7, {0.0, 0.2}), Curve(n, 5.0, 0.12, 0.2)};
  const Eigen::VectorXd z = InnerHeights(n);
  const ClosedRingsLift lift = LiftClosedRings(curves, z);
  Eigen::VectorXd inner = z;
  for (size_t r = 0; r + 1 < curves.size(); ++r) {
    const ClosedStripLift ring = LiftClosedStrip({curves[r], curves[r + 1]}, inner);
    ASSERT_FALSE(ring.a_is_one) << r;
    EXPECT_NEAR(lift.a[r], ring.a, 1e-12);
    for (int i = 0; i < n; ++i)
      EXPECT_NEAR(lift.mesh.point(lift.mesh.vertex_handle((r + 1) * n + i))[2],
                  ring.outer_heights[i], 1e-8)
          << "ring " << r << " point " << i;
    inner = ring.outer_heights;
  }
  EXPECT_LT(lift.inner_change, 1e-10);
  EXPECT_LT(lift.max_planarity, 1e-10);
}

// A ring whose plan quads are all trapezoids (its outer curve's edges parallel to the inner
// curve's, scaled by varying factors: a = 1, 002 Appendix A example 1) closes only for V·Z = 0:
// the inner curve is projected onto what the rings can close, and the lift is planar.
// Concentric circles also have a = 1 with V = 0, but leave a cone's slope free: refused, naming
// the free direction.
TEST(MarionettePolygonsTest, ClosedRingsWithARingOfTrapezoids) {
  const int n = 12;
  const std::vector<Eigen::Vector2d> c0 = Curve(n, 2.0, 0.10, 0.3);
  const std::vector<Eigen::Vector2d> c1 = Curve(n, 3.0, 0.15, 0.9, {0.1, 0.0});
  // c2: edges λ_i (c1_{i+1} − c1_i), the last two λ solved so that the curve closes.
  std::vector<Eigen::Vector2d> edge(n);
  for (int i = 0; i < n; ++i) edge[i] = c1[(i + 1) % n] - c1[i];
  std::vector<double> lambda(n);
  Eigen::Vector2d sum = Eigen::Vector2d::Zero();
  for (int i = 0; i + 2 < n; ++i) {
    lambda[i] = 1.4 + 0.15 * std::sin(4 * M_PI * i / n + 0.5);
    sum += lambda[i] * edge[i];
  }
  Eigen::Matrix2d m;
  m << edge[n - 2], edge[n - 1];
  const Eigen::Vector2d last = m.colPivHouseholderQr().solve(-sum);
  lambda[n - 2] = last.x();
  lambda[n - 1] = last.y();
  std::vector<Eigen::Vector2d> c2 = {c1[0] * 1.45};
  for (int i = 0; i + 1 < n; ++i) c2.push_back(c2.back() + lambda[i] * edge[i]);
  const ClosedRingsLift lift = LiftClosedRings({c0, c1, c2}, InnerHeights(n));
  std::printf("rings: a = %.6f, %.6f; |V| = %.3g, %.3g; inner curve moved by %.3g\n", lift.a[0],
              lift.a[1], lift.v_norm[0], lift.v_norm[1], lift.inner_change);
  EXPECT_NEAR(lift.a[1], 1.0, 1e-9);
  EXPECT_GT(lift.v_norm[1], 1e-3);
  EXPECT_GT(lift.inner_change, 1e-6);
  EXPECT_LT(lift.max_planarity, 1e-9);
  try {
    LiftClosedRings({Curve(n, 2.0, 0, 0), Curve(n, 3.0, 0, 0), Curve(n, 4.0, 0, 0)},
                    InnerHeights(n));
    ADD_FAILURE() << "concentric circles leave a cone free";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("stay free"), std::string::npos) << e.what();
  }
}

}  // namespace
}  // namespace gproj::marionette
