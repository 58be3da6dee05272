#include "gproj/problems/marionette/marionette_polygons.h"

#include <Eigen/Geometry>
#include <Eigen/LU>
#include <Eigen/OrderingMethods>
#include <Eigen/SPQRSupport>
#include <Eigen/SparseCore>
#include <Eigen/SparseLU>
#include <algorithm>
#include <cmath>
#include <cstdio>

#include "gproj/geometry/mesh/scale_free.h"
#include "gproj/problems/marionette/marionette.h"

namespace gproj::marionette {
namespace {

Eigen::Vector2d Plan(const PolyMesh& mesh, PolyMesh::VertexHandle v) {
  return Eigen::Vector2d(mesh.point(v)[0], mesh.point(v)[1]);
}

double Cross(const Eigen::Vector2d& a, const Eigen::Vector2d& b) {
  return a.x() * b.y() - a.y() * b.x();
}

// One planarity row: z_k − z_0 − α (z_a − z_0) − β (z_b − z_0) = 0 as (vertex, coefficient).
struct PlanarityRow {
  int face;
  std::array<std::pair<int, double>, 4> terms;
};

std::vector<PlanarityRow> PlanarityRows(const PolyMesh& plan) {
  std::vector<PlanarityRow> rows;
  for (auto f : plan.faces()) {
    std::vector<int> v;
    std::vector<Eigen::Vector2d> p;
    for (auto fv : plan.fv_range(f)) v.push_back(fv.idx()), p.push_back(Plan(plan, fv));
    const int n = static_cast<int>(v.size());
    if (n <= 3) continue;
    // The most spread-out triple through corner 0.
    int a = -1, b = -1;
    double best = 0.0, extent = 0.0;
    for (int i = 1; i < n; ++i) extent = std::max(extent, (p[i] - p[0]).norm());
    for (int i = 1; i < n; ++i)
      for (int j = i + 1; j < n; ++j) {
        const double area = std::abs(Cross(p[i] - p[0], p[j] - p[0]));
        if (area > best) best = area, a = i, b = j;
      }
    if (!(best > 1e-12 * extent * extent))
      throw InputError("plan face " + std::to_string(f.idx()) +
                       " has all its points on one line: its plane is not fixed by its plan");
    Eigen::Matrix2d m;
    m.col(0) = p[a] - p[0];
    m.col(1) = p[b] - p[0];
    const Eigen::Matrix2d inverse = m.inverse();
    for (int k = 1; k < n; ++k) {
      if (k == a || k == b) continue;
      const Eigen::Vector2d ab = inverse * (p[k] - p[0]);
      rows.push_back(
          {f.idx(),
           {{{v[k], 1.0}, {v[0], -1.0 + ab.x() + ab.y()}, {v[a], -ab.x()}, {v[b], -ab.y()}}}});
    }
  }
  return rows;
}

// Sparse QR with column pivoting by SuiteSparseQR (rank-revealing with its default tolerance).
using RankRevealingQr = Eigen::SPQR<Eigen::SparseMatrix<double>>;

int SparseRank(const Eigen::SparseMatrix<double>& m) {
  if (m.rows() == 0 || m.cols() == 0) return 0;
  RankRevealingQr qr;
  qr.compute(m);
  if (qr.info() != Eigen::Success) throw InputError("the rank of the planarity rows failed");
  return static_cast<int>(qr.rank());
}

Eigen::SparseMatrix<double> RowsMatrix(const std::vector<PlanarityRow>& rows, int n) {
  std::vector<Eigen::Triplet<double>> entries;
  for (size_t r = 0; r < rows.size(); ++r)
    for (const auto& [vertex, value] : rows[r].terms)
      entries.emplace_back(static_cast<int>(r), vertex, value);
  Eigen::SparseMatrix<double> m(static_cast<int>(rows.size()), n);
  m.setFromTriplets(entries.begin(), entries.end());
  m.makeCompressed();
  return m;
}

MarionetteDesignSpace DesignSpaceOf(const std::vector<PlanarityRow>& rows, int n) {
  MarionetteDesignSpace space;
  space.vertices = n;
  space.planarity_rows = static_cast<int>(rows.size());
  space.estimate = space.vertices - space.planarity_rows;
  space.rank = SparseRank(RowsMatrix(rows, n));
  space.dimension = space.vertices - space.rank;
  return space;
}

// Per vertex whether `heights` gives it one; throws InputError for an index out of range, a
// vertex given twice or a height that is not finite.
std::vector<char> CheckHeights(const PolyMesh& plan,
                               const std::vector<std::pair<int, double>>& heights) {
  const int n = static_cast<int>(plan.n_vertices());
  std::vector<char> given(n, 0);
  for (const auto& [vertex, z] : heights) {
    if (vertex < 0 || vertex >= n)
      throw InputError("prescribed height at vertex " + std::to_string(vertex) +
                       ": the plan has vertices 0.." + std::to_string(n - 1));
    if (given[vertex]) throw InputError("vertex " + std::to_string(vertex) + " is given twice");
    if (!std::isfinite(z))
      throw InputError("the height at vertex " + std::to_string(vertex) + " is not finite");
    given[vertex] = 1;
  }
  return given;
}

// x minimising ½ xᵀQx subject to A x = b (A given by its entries, m = b.size() rows): the KKT
// system regularised by −δ I on the multipliers, so that dependent rows do not make it singular,
// then refined against the unregularised one. Throws InputError when it cannot be solved.
Eigen::VectorXd SolveRegularisedKkt(const Eigen::SparseMatrix<double>& q,
                                    const std::vector<Eigen::Triplet<double>>& a_entries,
                                    const std::vector<double>& b, int n) {
  constexpr double kDelta = 1e-12;
  const int m = static_cast<int>(b.size());
  std::vector<Eigen::Triplet<double>> k_entries;
  for (int c = 0; c < q.outerSize(); ++c)
    for (Eigen::SparseMatrix<double>::InnerIterator it(q, c); it; ++it)
      k_entries.emplace_back(it.row(), it.col(), it.value());
  for (const auto& e : a_entries) {
    k_entries.emplace_back(n + e.row(), e.col(), e.value());
    k_entries.emplace_back(e.col(), n + e.row(), e.value());
  }
  std::vector<Eigen::Triplet<double>> exact_entries = k_entries;
  for (int r = 0; r < m; ++r) k_entries.emplace_back(n + r, n + r, -kDelta);
  Eigen::SparseMatrix<double> kkt(n + m, n + m), exact(n + m, n + m);
  kkt.setFromTriplets(k_entries.begin(), k_entries.end());
  kkt.makeCompressed();
  exact.setFromTriplets(exact_entries.begin(), exact_entries.end());
  Eigen::VectorXd rhs = Eigen::VectorXd::Zero(n + m);
  for (int r = 0; r < m; ++r) rhs[n + r] = b[r];
  Eigen::SparseLU<Eigen::SparseMatrix<double>> lu;
  lu.compute(kkt);
  if (lu.info() != Eigen::Success)
    throw InputError("the lift's KKT system could not be factorised");
  Eigen::VectorXd solution = lu.solve(rhs);
  for (int refinement = 0; refinement < 5 && solution.allFinite(); ++refinement)
    solution += lu.solve(rhs - exact * solution);
  if (!solution.allFinite()) throw InputError("the lift is not finite");
  return solution.head(n);
}

}  // namespace

Eigen::SparseMatrix<double> PolygonPlanarityMatrix(const PolyMesh& plan) {
  return RowsMatrix(PlanarityRows(plan), static_cast<int>(plan.n_vertices()));
}

MarionetteDesignSpace MeasureMarionetteDesignSpace(const PolyMesh& plan) {
  return DesignSpaceOf(PlanarityRows(plan), static_cast<int>(plan.n_vertices()));
}

std::vector<int> IndependentHeights(const PolyMesh& plan) {
  const int n = static_cast<int>(plan.n_vertices());
  const std::vector<PlanarityRow> rows = PlanarityRows(plan);
  if (rows.empty()) {
    std::vector<int> all(n);
    for (int v = 0; v < n; ++v) all[v] = v;
    return all;
  }
  RankRevealingQr qr;
  qr.compute(RowsMatrix(rows, n));
  if (qr.info() != Eigen::Success) throw InputError("the rank of the planarity rows failed");
  const int rank = static_cast<int>(qr.rank());
  std::vector<int> free;
  for (int k = rank; k < n; ++k) free.push_back(qr.colsPermutation().indices()[k]);
  std::sort(free.begin(), free.end());
  return free;
}

std::vector<std::array<int, 3>> StraightTriples(const PolyMesh& plan, double max_turn_deg) {
  std::vector<std::array<int, 3>> out;
  const double min_cos = std::cos(max_turn_deg * M_PI / 180.0);
  for (auto v : plan.vertices()) {
    std::vector<int> neighbours;
    for (auto w : plan.vv_range(v)) neighbours.push_back(w.idx());
    const Eigen::Vector2d p = Plan(plan, v);
    for (size_t i = 0; i < neighbours.size(); ++i) {
      // The straightest continuation of the edge from neighbour i through v.
      const Eigen::Vector2d in = (p - Plan(plan, plan.vertex_handle(neighbours[i]))).normalized();
      int best = -1;
      double best_cos = min_cos;
      for (size_t j = 0; j < neighbours.size(); ++j) {
        if (j == i) continue;
        const Eigen::Vector2d out_dir =
            (Plan(plan, plan.vertex_handle(neighbours[j])) - p).normalized();
        if (in.dot(out_dir) > best_cos) best_cos = in.dot(out_dir), best = static_cast<int>(j);
      }
      if (best >= 0 && neighbours[i] < neighbours[best])
        out.push_back({neighbours[i], v.idx(), neighbours[best]});
    }
  }
  return out;
}

namespace {

// Throws InputError when [A; F] (the constraints over the fairness rows) leaves directions of
// the heights free.
void CheckDetermined(const std::vector<Eigen::Triplet<double>>& a_entries, int m,
                     const std::vector<Eigen::Triplet<double>>& f_entries, int fairness_rows, int n,
                     size_t prescribed, int planar_dimension) {
  std::vector<Eigen::Triplet<double>> stacked = a_entries;
  for (const auto& e : f_entries) stacked.emplace_back(m + e.row(), e.col(), e.value());
  Eigen::SparseMatrix<double> s(m + fairness_rows, n);
  s.setFromTriplets(stacked.begin(), stacked.end());
  s.makeCompressed();
  const int rank = SparseRank(s);
  if (rank < n)
    throw InputError(std::to_string(n - rank) + " direction(s) of the heights stay free with " +
                     std::to_string(prescribed) +
                     " prescribed heights and the fairness energy: prescribe more heights (at "
                     "least three not on a line; the planarity leaves " +
                     std::to_string(planar_dimension) + " free)");
}

// Throws InputError when z misses a constraint A z = b, naming the face or the prescribed
// height of the worst row (the least-squares compromise spreads a conflict, largest where it
// is).
void CheckConstraintsMet(const std::vector<Eigen::Triplet<double>>& a_entries,
                         const std::vector<double>& b, const Eigen::VectorXd& z,
                         const std::vector<PlanarityRow>& rows,
                         const std::vector<std::pair<int, double>>& heights) {
  const int m = static_cast<int>(b.size()), n = static_cast<int>(z.size());
  Eigen::SparseMatrix<double> a(m, n);
  a.setFromTriplets(a_entries.begin(), a_entries.end());
  const Eigen::VectorXd residual = a * z - Eigen::Map<const Eigen::VectorXd>(b.data(), m);
  double scale = 1.0;
  for (double x : b) scale = std::max(scale, std::abs(x));
  int worst = 0;
  residual.cwiseAbs().maxCoeff(&worst);
  if (m > 0 && std::abs(residual[worst]) > 1e-8 * scale) {
    if (worst < static_cast<int>(rows.size()))
      throw InputError("the prescribed heights cannot all be met by planar faces (face " +
                       std::to_string(rows[worst].face) +
                       " would bend most): they over-determine the lift; prescribe fewer");
    throw InputError("the prescribed height at vertex " +
                     std::to_string(heights[worst - rows.size()].first) +
                     " contradicts the others through the planar faces; prescribe fewer");
  }
}

// Planarity: each face's vertices against the plane of its most spread-out triple, per `unit`.
double MaxPlanarity(const PolyMesh& mesh, double unit) {
  double worst = 0.0;
  for (auto face : mesh.faces()) {
    std::vector<Eigen::Vector3d> p;
    for (auto fv : mesh.fv_range(face)) p.emplace_back(mesh.point(fv).data());
    if (p.size() <= 3) continue;
    Eigen::Vector3d normal = Eigen::Vector3d::Zero();
    for (size_t i = 1; i < p.size(); ++i)
      for (size_t j = i + 1; j < p.size(); ++j) {
        const Eigen::Vector3d c = (p[i] - p[0]).cross(p[j] - p[0]);
        if (c.norm() > normal.norm()) normal = c;
      }
    normal.normalize();
    for (const Eigen::Vector3d& x : p)
      worst = std::max(worst, std::abs(normal.dot(x - p[0])) / unit);
  }
  return worst;
}

}  // namespace

MarionettePolygonLift LiftPolygonPlan(const PolyMesh& plan,
                                      const std::vector<std::pair<int, double>>& heights) {
  const int n = static_cast<int>(plan.n_vertices());
  if (plan.n_faces() == 0) throw InputError("the plan has no faces");
  CheckHeights(plan, heights);
  MarionettePolygonLift out;
  const std::vector<PlanarityRow> rows = PlanarityRows(plan);
  out.space = DesignSpaceOf(rows, n);
  const std::vector<std::array<int, 3>> triples = StraightTriples(plan);
  out.fairness_triples = static_cast<int>(triples.size());
  // Heights at the scale of the plan's edges (the regularised KKT below is then well scaled).
  const double unit = std::max(MeanEdgeLength(plan), 1e-300);
  // Constraints A z = b: planarity rows, then the prescribed heights.
  std::vector<Eigen::Triplet<double>> a_entries, f_entries;
  std::vector<double> b;
  for (size_t r = 0; r < rows.size(); ++r) {
    for (const auto& [vertex, value] : rows[r].terms)
      a_entries.emplace_back(static_cast<int>(r), vertex, value);
    b.push_back(0.0);
  }
  for (const auto& [vertex, z] : heights) {
    a_entries.emplace_back(static_cast<int>(b.size()), vertex, 1.0);
    b.push_back(z / unit);
  }
  const int m = static_cast<int>(b.size());
  for (size_t t = 0; t < triples.size(); ++t) {
    f_entries.emplace_back(static_cast<int>(t), triples[t][0], 1.0);
    f_entries.emplace_back(static_cast<int>(t), triples[t][1], -2.0);
    f_entries.emplace_back(static_cast<int>(t), triples[t][2], 1.0);
  }
  CheckDetermined(a_entries, m, f_entries, static_cast<int>(triples.size()), n, heights.size(),
                  out.space.dimension);
  Eigen::SparseMatrix<double> f(static_cast<int>(triples.size()), n);
  f.setFromTriplets(f_entries.begin(), f_entries.end());
  const Eigen::VectorXd z =
      SolveRegularisedKkt(Eigen::SparseMatrix<double>(f.transpose() * f), a_entries, b, n);
  CheckConstraintsMet(a_entries, b, z, rows, heights);
  out.mesh = plan;
  for (auto v : out.mesh.vertices()) {
    auto p = out.mesh.point(v);
    p[2] = z[v.idx()] * unit;
    out.mesh.set_point(v, p);
  }
  for (const auto& [vertex, height] : heights)
    out.max_height_error = std::max(
        out.max_height_error, std::abs(out.mesh.point(out.mesh.vertex_handle(vertex))[2] - height));
  const Eigen::VectorXd fz = f * z;
  out.fairness = fz.squaredNorm() * unit * unit;
  out.max_planarity = MaxPlanarity(out.mesh, unit);
  return out;
}

std::vector<std::pair<int, double>> NearestPlanarHeights(
    const PolyMesh& plan, const std::vector<std::pair<int, double>>& targets) {
  const int n = static_cast<int>(plan.n_vertices());
  const std::vector<char> given = CheckHeights(plan, targets);
  // min |E z − t|² (+ a 1e-12 ridge for the vertices no target reaches) subject to P z = 0.
  std::vector<Eigen::Triplet<double>> q_entries, a_entries;
  std::vector<double> b;
  for (int v = 0; v < n; ++v) q_entries.emplace_back(v, v, given[v] ? 1.0 : 1e-12);
  const std::vector<PlanarityRow> rows = PlanarityRows(plan);
  for (size_t r = 0; r < rows.size(); ++r) {
    for (const auto& [vertex, value] : rows[r].terms)
      a_entries.emplace_back(static_cast<int>(r), vertex, value);
    b.push_back(0.0);
  }
  // In the shifted unknown y = z − t̂ (t̂: the targets, 0 elsewhere) the objective is |E y|²
  // (plus the ridge) subject to P y = −P t̂.
  Eigen::VectorXd shift = Eigen::VectorXd::Zero(n);
  for (const auto& [vertex, z] : targets) shift[vertex] = z;
  const Eigen::VectorXd moved_rhs = -(RowsMatrix(rows, n) * shift);
  for (size_t r = 0; r < rows.size(); ++r) b[r] = moved_rhs[r];
  Eigen::SparseMatrix<double> q(n, n);
  q.setFromTriplets(q_entries.begin(), q_entries.end());
  const Eigen::VectorXd y = SolveRegularisedKkt(q, a_entries, b, n);
  std::vector<std::pair<int, double>> out;
  for (const auto& [vertex, z] : targets) out.push_back({vertex, z + y[vertex]});
  return out;
}

ClosedRingsLift LiftClosedRings(const std::vector<std::vector<Eigen::Vector2d>>& curves,
                                const Eigen::VectorXd& inner_heights) {
  if (curves.size() < 2 || curves[0].size() < 3)
    throw InputError("closed rings need at least 2 curves of at least 3 points");
  const int n = static_cast<int>(curves[0].size());
  for (const auto& c : curves)
    if (static_cast<int>(c.size()) != n)
      throw InputError("every curve of closed rings needs " + std::to_string(n) + " points");
  if (inner_heights.size() != n)
    throw InputError("closed rings need one height per inner point (" + std::to_string(n) + ")");
  ClosedRingsLift out;
  const int rings = static_cast<int>(curves.size()) - 1;
  for (int r = 0; r < rings; ++r) {
    const ClosedStrip strip{curves[r], curves[r + 1]};
    const int quad = DegenerateClosedStripQuad(strip);
    if (quad >= 0)
      throw InputError("quad " + std::to_string(quad) + " of ring " + std::to_string(r) +
                       " has a degenerate plan view");
    const ClosedStripLift plan_only = LiftClosedStrip(strip, Eigen::VectorXd::Zero(n));
    out.a.push_back(plan_only.a);
    out.v_norm.push_back(plan_only.v.norm());
  }
  PolyMesh plan;
  for (const auto& c : curves)
    for (const Eigen::Vector2d& p : c) plan.add_vertex(PolyMesh::Point(p.x(), p.y(), 0.0));
  for (int r = 0; r < rings; ++r)
    for (int i = 0; i < n; ++i) {
      const int j = (i + 1) % n;
      plan.add_face(std::vector<PolyMesh::VertexHandle>{
          plan.vertex_handle(r * n + i), plan.vertex_handle((r + 1) * n + i),
          plan.vertex_handle((r + 1) * n + j), plan.vertex_handle(r * n + j)});
    }
  std::vector<std::pair<int, double>> targets;
  for (int i = 0; i < n; ++i) targets.push_back({i, inner_heights[i]});
  const std::vector<std::pair<int, double>> reachable = NearestPlanarHeights(plan, targets);
  const MarionettePolygonLift lift = LiftPolygonPlan(plan, reachable);
  out.mesh = lift.mesh;
  out.max_planarity = lift.max_planarity;
  out.inner_heights.resize(n);
  for (int i = 0; i < n; ++i) {
    out.inner_heights[i] = reachable[i].second;
    out.inner_change = std::max(out.inner_change, std::abs(reachable[i].second - inner_heights[i]));
  }
  return out;
}

}  // namespace gproj::marionette
