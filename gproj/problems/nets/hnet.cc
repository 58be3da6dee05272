#include "gproj/problems/nets/hnet.h"

#include <Eigen/Eigenvalues>
#include <Eigen/Geometry>
#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <deque>
#include <limits>
#include <memory>

#include "gproj/constraints/frame_point_planarity.h"
#include "gproj/geometry/mesh/closest_point.h"
#include "gproj/geometry/mesh/scale_free.h"
#include "gproj/problems/mesh/panel_bounds.h"
#include "gproj/solver/inequality.h"

namespace gproj::nets {
namespace {

Eigen::Vector3d P(const PolyMesh& mesh, int v) {
  return ToEigen(mesh.point(PolyMesh::VertexHandle(v)));
}

double Det(const Eigen::Vector3d& a, const Eigen::Vector3d& b, const Eigen::Vector3d& c) {
  return a.dot(b.cross(c));
}

std::array<int, 4> FaceVertices(const PolyMesh& mesh, PolyMesh::FaceHandle f) {
  std::array<int, 4> v{};
  int k = 0;
  for (auto fv : mesh.fv_range(f)) v[k++ % 4] = fv.idx();
  return v;
}

}  // namespace

std::vector<int> TwoColourVertices(const PolyMesh& mesh) {
  std::vector<int> colour(mesh.n_vertices(), -1);
  for (auto start : mesh.vertices()) {
    if (colour[start.idx()] >= 0) continue;
    colour[start.idx()] = 0;
    std::deque<PolyMesh::VertexHandle> queue = {start};
    while (!queue.empty()) {
      const auto v = queue.front();
      queue.pop_front();
      for (auto w : mesh.vv_range(v)) {
        if (colour[w.idx()] < 0) {
          colour[w.idx()] = 1 - colour[v.idx()];
          queue.push_back(w);
        } else if (colour[w.idx()] == colour[v.idx()]) {
          throw InputError("the vertices cannot be 2-coloured (edge " + std::to_string(v.idx()) +
                           "-" + std::to_string(w.idx()) +
                           " closes an odd cycle), so the patch diagonals cannot be chosen");
        }
      }
    }
  }
  return colour;
}

EdgeStencil EdgeStencilOf(const PolyMesh& mesh, const std::vector<int>& colour,
                          PolyMesh::EdgeHandle e) {
  auto h = mesh.halfedge_handle(e, 0);
  if (colour[mesh.from_vertex_handle(h).idx()] != 0) h = mesh.halfedge_handle(e, 1);
  const auto o = mesh.opposite_halfedge_handle(h);
  EdgeStencil s;
  s.b[0] = mesh.from_vertex_handle(h).idx();
  s.b[3] = mesh.to_vertex_handle(h).idx();
  s.b[4] = mesh.to_vertex_handle(mesh.next_halfedge_handle(h)).idx();
  s.b[5] = mesh.to_vertex_handle(mesh.next_halfedge_handle(mesh.next_halfedge_handle(h))).idx();
  s.b[1] = mesh.to_vertex_handle(mesh.next_halfedge_handle(o)).idx();
  s.b[2] = mesh.to_vertex_handle(mesh.next_halfedge_handle(mesh.next_halfedge_handle(o))).idx();
  s.right_face = mesh.face_handle(h).idx();
  s.left_face = mesh.face_handle(o).idx();
  return s;
}

double ShapeParameterRatio(const PolyMesh& mesh, const EdgeStencil& s) {
  auto b = [&](int i, int j) { return Eigen::Vector3d(P(mesh, s.b[i]) - P(mesh, s.b[j])); };
  return Det(b(3, 0), b(5, 0), b(2, 0)) / Det(b(3, 0), b(1, 0), b(4, 0));
}

std::pair<double, double> ClosureProducts(const PolyMesh& mesh, PolyMesh::VertexHandle v) {
  // B[1..2n]: odd entries the edge neighbours, even entries the free vertices of the quads.
  std::vector<Eigen::Vector3d> b;
  const Eigen::Vector3d b0 = ToEigen(mesh.point(v));
  auto h = mesh.halfedge_handle(v);
  const auto first = h;
  do {
    b.push_back(ToEigen(mesh.point(mesh.to_vertex_handle(h))) - b0);
    b.push_back(ToEigen(mesh.point(mesh.to_vertex_handle(mesh.next_halfedge_handle(h)))) - b0);
    h = mesh.opposite_halfedge_handle(mesh.prev_halfedge_handle(h));
  } while (h != first);
  const int m = static_cast<int>(b.size());  // 2n
  auto at = [&](int k) -> const Eigen::Vector3d& { return b[((k - 1) % m + m) % m]; };
  double lhs = 1.0, rhs = 1.0;
  for (int i = 1; i <= m / 2; ++i) {
    lhs *= Det(at(2 * i + 1), at(2 * i + 3), at(2 * i));
    rhs *= Det(at(2 * i + 1), at(2 * i - 1), at(2 * i + 2));
  }
  return {lhs, rhs};
}

double OptimalShapeScale(const std::vector<double>& w) {
  double s2 = 0.0, s1 = 0.0, si = 0.0, si2 = 0.0;
  for (double x : w) {
    s2 += x * x;
    s1 += x;
    si += 1.0 / x;
    si2 += 1.0 / (x * x);
  }
  auto objective = [&w](double lambda) {
    double f = 0.0;
    for (double x : w) f += std::pow(lambda * x - 1.0, 2) + std::pow(1.0 / (lambda * x) - 1.0, 2);
    return f;
  };
  // Companion matrix of λ⁴ + a3 λ³ + a2 λ² + a1 λ + a0 (divided by ΣW²).
  const double a3 = -s1 / s2, a2 = 0.0, a1 = si / s2, a0 = -si2 / s2;
  Eigen::Matrix4d companion = Eigen::Matrix4d::Zero();
  companion(1, 0) = companion(2, 1) = companion(3, 2) = 1.0;
  companion(0, 3) = -a0;
  companion(1, 3) = -a1;
  companion(2, 3) = -a2;
  companion(3, 3) = -a3;
  const Eigen::Vector4cd roots = Eigen::EigenSolver<Eigen::Matrix4d>(companion).eigenvalues();
  double best = 1.0, best_f = std::numeric_limits<double>::infinity();
  for (int i = 0; i < 4; ++i) {
    const double re = roots[i].real();
    if (re <= 0.0 || std::abs(roots[i].imag()) > 1e-8 * std::abs(re)) continue;
    const double f = objective(re);
    if (f < best_f) {
      best_f = f;
      best = re;
    }
  }
  return best;
}

ShapeParameters PropagateShapeParameters(const PolyMesh& mesh, const std::vector<int>& colour,
                                         int seed_face) {
  ShapeParameters out;
  out.w.assign(mesh.n_faces(), std::numeric_limits<double>::quiet_NaN());
  std::vector<bool> visited(mesh.n_faces(), false);
  auto spread = [&](int seed) {
    visited[seed] = true;
    out.w[seed] = 1.0;
    std::deque<int> queue = {seed};
    while (!queue.empty()) {
      const auto f = PolyMesh::FaceHandle(queue.front());
      queue.pop_front();
      for (auto h : mesh.fh_range(f)) {
        const auto edge = mesh.edge_handle(h);
        if (mesh.is_boundary(edge)) continue;
        const EdgeStencil s = EdgeStencilOf(mesh, colour, edge);
        const double ratio = ShapeParameterRatio(mesh, s);  // W_right / W_left
        const bool f_is_left = s.left_face == f.idx();
        const int g = f_is_left ? s.right_face : s.left_face;
        const double predicted = f_is_left ? out.w[f.idx()] * ratio : out.w[f.idx()] / ratio;
        if (!visited[g]) {
          visited[g] = true;
          out.w[g] = predicted;
          queue.push_back(g);
        } else {
          out.max_inconsistency =
              std::max(out.max_inconsistency, std::abs(predicted / out.w[g] - 1.0));
        }
      }
    }
  };
  spread(seed_face);
  for (auto f : mesh.faces())
    if (!visited[f.idx()]) spread(f.idx());
  out.lambda = OptimalShapeScale(out.w);
  for (double& x : out.w) x *= out.lambda;
  return out;
}

std::array<double, 4> CornerWeights(const PolyMesh& mesh, const std::vector<int>& colour,
                                    PolyMesh::FaceHandle f, double w) {
  const std::array<int, 4> v = FaceVertices(mesh, f);
  std::array<double, 4> weights = {1.0, 1.0, 1.0, 1.0};
  for (int k = 0; k < 4; ++k)
    if (colour[v[k]] == 0) {
      weights[k] = w;
      break;
    }
  return weights;
}

void EvaluatePatch(const PolyMesh& mesh, PolyMesh::FaceHandle f, const std::array<double, 4>& w,
                   double u, double v, Eigen::Vector3d* point, Eigen::Vector3d* normal) {
  const std::array<int, 4> c = FaceVertices(mesh, f);
  const double basis[4] = {(1 - u) * (1 - v), u * (1 - v), u * v, (1 - u) * v};
  const double du[4] = {-(1 - v), 1 - v, v, -v};
  const double dv[4] = {-(1 - u), -u, u, 1 - u};
  Eigen::Vector4d x = Eigen::Vector4d::Zero(), xu = x, xv = x;
  for (int i = 0; i < 4; ++i) {
    Eigen::Vector4d h;
    h << w[i] * P(mesh, c[i]), w[i];
    x += basis[i] * h;
    xu += du[i] * h;
    xv += dv[i] * h;
  }
  *point = x.head<3>() / x[3];
  const Eigen::Vector3d tu = (xu.head<3>() * x[3] - x.head<3>() * xu[3]) / (x[3] * x[3]);
  const Eigen::Vector3d tv = (xv.head<3>() * x[3] - x.head<3>() * xv[3]) / (x[3] * x[3]);
  *normal = tu.cross(tv).normalized();
}

double EdgeParameterAt(double s, double w0, double w1) {
  if (!(w0 * w1 > 0.0)) return s;
  const double a = s * w0, b = (1.0 - s) * w1;
  return a / (a + b);
}

Eigen::Vector2d PatchEdgeUv(int k, double t) {
  switch (k) {
    case 0:
      return {t, 0.0};
    case 1:
      return {1.0, t};
    case 2:
      return {1.0 - t, 1.0};
    default:
      return {0.0, 1.0 - t};
  }
}

namespace {
// Normal of face f's patch at the point (1 − s) a + s b of its edge from vertex a to vertex b.
Eigen::Vector3d NormalOnEdge(const PolyMesh& mesh, PolyMesh::FaceHandle f,
                             const std::array<double, 4>& w, int a, double s) {
  const std::array<int, 4> c = FaceVertices(mesh, f);
  int k = 0;
  while (c[k] != a) ++k;
  const Eigen::Vector2d uv = PatchEdgeUv(k, EdgeParameterAt(s, w[k], w[(k + 1) % 4]));
  Eigen::Vector3d point, normal;
  EvaluatePatch(mesh, f, w, uv.x(), uv.y(), &point, &normal);
  return normal;
}
}  // namespace

std::vector<double> TangentPlaneAngles(const PolyMesh& input,
                                       const std::vector<std::array<double, 4>>& weights,
                                       int samples) {
  // At unit scale: the patch normals' cross products neither overflow nor underflow.
  const PolyMesh mesh = UnitScaleCopy(input);
  std::vector<double> angles(mesh.n_edges(), 0.0);
  for (auto e : mesh.edges()) {
    if (mesh.is_boundary(e)) continue;
    const auto h = mesh.halfedge_handle(e, 0);
    const auto o = mesh.opposite_halfedge_handle(h);
    const int a = mesh.from_vertex_handle(h).idx(), b = mesh.to_vertex_handle(h).idx();
    const auto f = mesh.face_handle(h), g = mesh.face_handle(o);
    for (int k = 0; k <= samples; ++k) {
      const double s = static_cast<double>(k) / samples;
      const Eigen::Vector3d n1 = NormalOnEdge(mesh, f, weights[f.idx()], a, s);
      const Eigen::Vector3d n2 = NormalOnEdge(mesh, g, weights[g.idx()], b, 1.0 - s);
      const double sine = n1.cross(n2).norm();
      angles[e.idx()] = std::max(angles[e.idx()], std::asin(std::min(1.0, sine)) * 180.0 / M_PI);
    }
  }
  return angles;
}

double MaxTangentPlaneAngle(const PolyMesh& mesh, const std::vector<std::array<double, 4>>& weights,
                            int samples) {
  const std::vector<double> angles = TangentPlaneAngles(mesh, weights, samples);
  return angles.empty() ? 0.0 : *std::max_element(angles.begin(), angles.end());
}

std::vector<std::pair<int, int>> EquitwistViolations(const PolyMesh& mesh,
                                                     const std::vector<int>& colour) {
  std::vector<std::pair<int, int>> out;
  for (auto e : mesh.edges()) {
    if (mesh.is_boundary(e)) continue;
    if (ShapeParameterRatio(mesh, EdgeStencilOf(mesh, colour, e)) <= 0.0) {
      const auto h = mesh.halfedge_handle(e, 0);
      out.emplace_back(mesh.from_vertex_handle(h).idx(), mesh.to_vertex_handle(h).idx());
    }
  }
  return out;
}

std::string SimplyConnectedProblem(const PolyMesh& mesh) {
  // Connected components over faces.
  std::vector<int> component(mesh.n_faces(), -1);
  int components = 0;
  for (auto f0 : mesh.faces()) {
    if (component[f0.idx()] >= 0) continue;
    std::deque<PolyMesh::FaceHandle> queue = {f0};
    component[f0.idx()] = components;
    while (!queue.empty()) {
      const auto f = queue.front();
      queue.pop_front();
      for (auto g : mesh.ff_range(f))
        if (component[g.idx()] < 0) {
          component[g.idx()] = components;
          queue.push_back(g);
        }
    }
    ++components;
  }
  if (components != 1)
    return "the mesh has " + std::to_string(components) + " connected components";
  std::vector<bool> seen(mesh.n_halfedges(), false);
  int loops = 0;
  for (auto h : mesh.halfedges()) {
    if (!mesh.is_boundary(h) || seen[h.idx()]) continue;
    ++loops;
    for (auto k = h; !seen[k.idx()]; k = mesh.next_halfedge_handle(k)) seen[k.idx()] = true;
  }
  int used_vertices = 0;
  for (auto v : mesh.vertices()) used_vertices += mesh.is_isolated(v) ? 0 : 1;
  const int euler =
      used_vertices - static_cast<int>(mesh.n_edges()) + static_cast<int>(mesh.n_faces());
  const int genus2 = 2 - euler - loops;  // 2g
  if (genus2 == 0 && loops <= 1) return "";
  return "the mesh is not simply connected (" + std::to_string(loops) + " boundary loops, genus " +
         std::to_string(genus2 / 2) + ")";
}

PolyMesh SampleHNetSurface(const PolyMesh& mesh, const std::vector<std::array<double, 4>>& weights,
                           int samples) {
  // One output vertex per mesh vertex and per inner sample of each edge, shared by the patches
  // on both sides (the patches of an H-net join along their common straight edges: their
  // samples are placed at the same fractions of the edge, each patch reaching them at its own
  // parameters), then each patch's inner samples.
  const int n = samples;
  PolyMesh out;
  std::vector<PolyMesh::VertexHandle> corner(mesh.n_vertices());
  for (auto v : mesh.vertices()) corner[v.idx()] = out.add_vertex(mesh.point(v));
  std::vector<std::vector<PolyMesh::VertexHandle>> edge(mesh.n_edges());
  for (auto e : mesh.edges()) {
    const auto h = mesh.halfedge_handle(e, 0);
    const Eigen::Vector3d a = P(mesh, mesh.from_vertex_handle(h).idx());
    const Eigen::Vector3d b = P(mesh, mesh.to_vertex_handle(h).idx());
    for (int k = 1; k < n; ++k) {
      const Eigen::Vector3d q = a + (static_cast<double>(k) / n) * (b - a);
      edge[e.idx()].push_back(out.add_vertex(PolyMesh::Point(q[0], q[1], q[2])));
    }
  }
  std::vector<PolyMesh::VertexHandle> grid((n + 1) * (n + 1));
  auto at = [&grid, n](int i, int j) -> PolyMesh::VertexHandle& { return grid[i * (n + 1) + j]; };
  for (auto f : mesh.faces()) {
    const std::array<int, 4> c = FaceVertices(mesh, f);
    const std::array<double, 4>& w = weights[f.idx()];
    // Corner k sits at (u, v) = (0, 0), (1, 0), (1, 1), (0, 1); edge k runs from corner k to
    // k + 1. Sample m of edge k (m = 0..n from corner k) is the shared vertex.
    auto edge_sample = [&](int k, int m) {
      if (m == 0) return corner[c[k]];
      if (m == n) return corner[c[(k + 1) % 4]];
      const auto from = mesh.vertex_handle(c[k]), to = mesh.vertex_handle(c[(k + 1) % 4]);
      const auto h = mesh.find_halfedge(from, to);
      const auto e = mesh.edge_handle(h);
      const bool forward = mesh.halfedge_handle(e, 0) == h;
      return edge[e.idx()][forward ? m - 1 : n - m - 1];
    };
    for (int i = 0; i <= n; ++i) {
      at(i, 0) = edge_sample(0, i);
      at(n, i) = edge_sample(1, i);
      at(n - i, n) = edge_sample(2, i);
      at(0, n - i) = edge_sample(3, i);
    }
    // Inner samples: the edges' parameters blended across the patch, so that the rows and
    // columns of samples end at the shared edge samples.
    for (int i = 1; i < n; ++i)
      for (int j = 1; j < n; ++j) {
        const double si = static_cast<double>(i) / n, sj = static_cast<double>(j) / n;
        const double u_bottom = EdgeParameterAt(si, w[0], w[1]);
        const double u_top = 1.0 - EdgeParameterAt(1.0 - si, w[2], w[3]);
        const double v_right = EdgeParameterAt(sj, w[1], w[2]);
        const double v_left = 1.0 - EdgeParameterAt(1.0 - sj, w[3], w[0]);
        const double u = (1.0 - sj) * u_bottom + sj * u_top;
        const double v = (1.0 - si) * v_left + si * v_right;
        Eigen::Vector3d point, normal;
        EvaluatePatch(mesh, f, w, u, v, &point, &normal);
        at(i, j) = out.add_vertex(PolyMesh::Point(point[0], point[1], point[2]));
      }
    for (int i = 0; i < n; ++i)
      for (int j = 0; j < n; ++j) {
        out.add_face(at(i, j), at(i + 1, j), at(i + 1, j + 1));
        out.add_face(at(i, j), at(i + 1, j + 1), at(i, j + 1));
      }
  }
  return out;
}

HNet::HNet(const PolyMesh& mesh, const PolyMesh* reference, const HNetOptions& options)
    : options_(options), input_(mesh), mesh_(mesh), reference_(reference) {
  std::string why;
  if (!options.anet.IsValid(&why)) throw InputError("invalid H-net options: " + why);
  if (!(options.frame_weight > 0.0) || options.max_rounds < 1 || options.iterations_per_round < 1)
    throw InputError("invalid H-net options: frame weight > 0, rounds and iterations ≥ 1");
  if (mesh.n_faces() == 0) throw InputError("the mesh has no faces");
  CheckANetTopology(mesh, "");
  // The weight and frame-point formulas work in the input's units; products of coordinates
  // must stay finite (the A-net step alone is scale-free).
  const double mean_edge = MeanEdgeLength(mesh);
  if (!(mean_edge >= kMinHNetEdge && mean_edge <= kMaxHNetEdge)) {
    char text[160];
    std::snprintf(text, sizeof(text),
                  "the mean edge length is %.3g; the H-net rounds need it within [%g, %g] "
                  "(rescale the mesh)",
                  mean_edge, kMinHNetEdge, kMaxHNetEdge);
    throw InputError(text);
  }
  topology_note_ = SimplyConnectedProblem(mesh);
  if (!topology_note_.empty() && !options.allow_not_simply_connected)
    throw InputError(topology_note_ +
                     "; the exact H-net extension needs a simply connected A-net (pass "
                     "`allow_not_simply_connected` to optimise anyway)");
  colour_ = TwoColourVertices(mesh);
}

namespace {

// The vertex-update problem of 004 §3.2: the A-net families and frame-point planarity per
// inner edge, with an eliminable frame normal per edge.
struct VertexUpdate {
  Problem problem;
  MeshNormalization norm;
  int vertex_block = -1, edge_block = -1;
  FramePointPlanarity* frame = nullptr;  // weights frozen (exact extension)
  int shape_block = -1;                  // weights as unknowns: W per face
  std::vector<EdgeStencil> stencils;     // per inner edge
  VertexControl control;                 // held and gliding vertices, as in the A-net step
  PanelBounds bounds;                    // the A-net step's corner and edge bounds
  PolyMesh start;                        // the mesh the update was built from (held positions)
};

// Starts each frame normal from the frame points of the current vertices and weights w.
void StartFrameNormals(const std::vector<double>& w, VertexUpdate* u) {
  Eigen::VectorXd& x = u->problem.x();
  const VariableLayout& layout = u->problem.layout();
  for (size_t k = 0; k < u->stencils.size(); ++k) {
    const EdgeStencil& s = u->stencils[k];
    const double wl = w[s.left_face], wr = w[s.right_face];
    auto b = [&](int i) {
      return Eigen::Vector3d(x.segment<3>(layout.Index(u->vertex_block, s.b[i], 0)));
    };
    const Eigen::Vector3d f1 = (b(1) + wl * b(2)) / (1 + wl), f4 = (b(5) + wr * b(4)) / (1 + wr);
    Eigen::Vector3d n = (b(3) - b(0)).cross(f1 - f4);
    if (n.norm() > 0) n.normalize();
    x.segment<3>(layout.Index(u->edge_block, static_cast<int>(k), 0)) = n;
  }
}

// The vertex update of `mesh`, whose panel bounds are measured on `input` (the same
// connectivity) as the A-net step's are; with `free_weights` (their start values) the shape
// parameters are unknowns too: frame rows with W, W near 1 (soft, 004 eq. 11) and W ≥ min
// (inequality).
std::unique_ptr<VertexUpdate> BuildVertexUpdate(const PolyMesh& mesh, const PolyMesh& input,
                                                const std::vector<int>& colour,
                                                const HNetOptions& options,
                                                const PolyMesh& reference,
                                                const std::vector<double>* free_weights = nullptr) {
  auto u = std::make_unique<VertexUpdate>();
  Problem& problem = u->problem;
  u->norm = MeshNormalization::Of(mesh);
  u->vertex_block = problem.layout().AddBlock("vertices", static_cast<int>(mesh.n_vertices()), 3);
  const ANetFamilies anet = AddANetLayout(mesh, options.anet, &problem);
  std::vector<PolyMesh::EdgeHandle> inner_edges;
  for (auto e : mesh.edges())
    if (!mesh.is_boundary(e)) inner_edges.push_back(e);
  u->edge_block = problem.layout().AddBlock("frame_normals", static_cast<int>(inner_edges.size()),
                                            3, /*eliminable=*/true);
  if (free_weights)
    u->shape_block =
        problem.layout().AddBlock("shape_parameters", static_cast<int>(mesh.n_faces()), 1);
  problem.ResizeToLayout();
  LoadVertices(mesh, u->norm, u->vertex_block, &problem);
  LoadANetNormals(mesh, u->vertex_block, anet, &problem);
  AddANetFamilies(mesh, options.anet, u->vertex_block, anet, &reference, u->norm, &problem);
  // Bounds measured on the input, not on this update's start: a bound relaxed to the input's
  // value, or the default edge floor (a tenth of the input length), must not shrink with every
  // update.
  u->bounds = AddPanelBounds(input, u->norm, u->vertex_block, options.anet.panels, &problem);
  u->control = ApplyVertexControl(mesh, u->norm, u->vertex_block, options.anet.vertices, &problem);
  u->start = mesh;
  for (auto e : inner_edges) u->stencils.push_back(EdgeStencilOf(mesh, colour, e));
  const VariableLayout& layout = problem.layout();
  const BlockItems edge(layout, u->edge_block), vertex(layout, u->vertex_block);
  if (!free_weights) {
    u->frame = problem.AddFamily<FramePointPlanarity>(options.frame_weight);
    for (size_t k = 0; k < inner_edges.size(); ++k) {
      const EdgeStencil& s = u->stencils[k];
      u->frame->AddEdge(edge[static_cast<int>(k)], vertex[s.b[0]], vertex[s.b[1]], vertex[s.b[2]],
                        vertex[s.b[3]], vertex[s.b[4]], vertex[s.b[5]], 1.0, 1.0);
    }
    return u;
  }
  const int faces = static_cast<int>(mesh.n_faces());
  for (int f = 0; f < faces; ++f)
    problem.x()[layout.Index(u->shape_block, f, 0)] = (*free_weights)[f];
  StartFrameNormals(*free_weights, u.get());
  const BlockItems shape(layout, u->shape_block);
  auto* frame = problem.AddTerm<4, 3, 3, 3, 3, 3, 3, 3, 1, 1>(
      "frame_planarity", FramePointPlanarityWithWeightsResidual{}, FamilyRole::kConstraint,
      options.frame_weight);
  frame->AddElements(IndexRange(static_cast<int>(inner_edges.size())), [&](int k) {
    const EdgeStencil& s = u->stencils[k];
    std::array<int, 9> items;
    items[0] = edge[k];
    for (int i = 0; i < 6; ++i) items[1 + i] = vertex[s.b[i]];
    items[7] = shape[s.left_face];
    items[8] = shape[s.right_face];
    return items;
  });
  auto* near_one = problem.AddTerm<2, 1>("shape_near_one", ShapeParameterNearOneResidual{},
                                         FamilyRole::kSoft, options.shape_regularity);
  near_one->AddElements(IndexRange(faces), [&](int f) { return shape(f); });
  const double min_w = options.min_shape_parameter;
  AddInequalities<1, 1>(
      &problem, "shape_positive", [min_w](const auto* w, auto* r) { r[0] = w[0] - min_w; },
      IndexRange(faces), [&](int f) { return shape(f); });
  return u;
}

// Freezes the shape parameters w in the frame rows and starts each frame normal from the
// current frame points.
void FreezeWeights(const std::vector<double>& w, VertexUpdate* u) {
  for (size_t k = 0; k < u->stencils.size(); ++k)
    u->frame->SetShapeParameters(static_cast<int>(k), w[u->stencils[k].left_face],
                                 w[u->stencils[k].right_face]);
  StartFrameNormals(w, u);
}

// The first face whose shape parameter cannot place a frame point (not finite, or −1, where
// (b + w b') / (1 + w) has no value), as "face F has W = …"; empty if there is none.
std::string UnusableWeight(const std::vector<double>& w) {
  for (size_t f = 0; f < w.size(); ++f)
    if (!std::isfinite(w[f]) || std::abs(1.0 + w[f]) < 1e-12) {
      char text[96];
      std::snprintf(text, sizeof(text), "face %zu has shape parameter W = %g", f, w[f]);
      return text;
    }
  return "";
}

struct VertexUpdateResult {
  bool failed = false, converged = false;
  bool stopped = false;  // by the run's callback: x holds the last iterate
  int steps = 0;
  std::string message;
};

// The vertex update's iterates as records for the run's callback: numbered after `offset`
// earlier iterations, with the star measures of the vertices (`mesh` with the update's vertices,
// held ones restored, against `input`). The update's start is the iterate before it, already
// recorded: it is not passed again.
class VertexUpdateRecords {
 public:
  VertexUpdateRecords(const VertexUpdate& update, const PolyMesh& mesh, const PolyMesh& input,
                      int offset, StopTracker* stop)
      : update_(update), current_(mesh), input_(input), offset_(offset), stop_(stop) {}

  // false when the run must stop.
  bool Record(RunRecord record) {
    if (record.iteration == 0) return !stop_->stopped();
    record.iteration += offset_;
    StoreVertices(update_.problem, update_.vertex_block, update_.norm, &current_);
    update_.control.RestoreHeld(update_.start, &current_);
    record.measures = ToNamedValues(MeasureStarPlanarity(current_, input_));
    return stop_->Record(record);
  }
  bool listening() const { return stop_->listening(); }
  bool stopped() const { return stop_->stopped(); }

 private:
  const VertexUpdate& update_;
  PolyMesh current_;
  const PolyMesh& input_;
  int offset_;
  StopTracker* stop_;
};

// One vertex update: guided projection with `options`, or (kCeres) Ceres' LM on the same rows
// with the soft terms at the options' initial soft scale. Every iterate goes to `records` (none
// without a listener); it stops the update when it returns false.
VertexUpdateResult SolveVertexUpdate(const SolverOptions& options, SolverKind solver,
                                     VertexUpdate* update, VertexUpdateRecords* records) {
  const bool listening = records->listening();
  if (solver != SolverKind::kCeres) {
    const IterationCallback on_iteration = [records](const IterationRecord& r,
                                                     const Eigen::VectorXd&) {
      return records->Record(ToRunRecord(r)) ? CallbackResult::kContinue : CallbackResult::kAbort;
    };
    const SolverSummary s =
        gproj::Solve(options, &update->problem, listening ? on_iteration : nullptr);
    const bool stopped = s.termination == TerminationType::kUserAbort;
    return {s.termination == TerminationType::kFailure, s.converged() && !stopped, stopped,
            s.num_steps(), s.message};
  }
  const CeresIterationCallback on_iteration = [records](const CeresIterationRecord& r,
                                                        const Eigen::VectorXd&) {
    return records->Record(ToRunRecord(r));
  };
  const CeresSummary s =
      SolveWithCeres(CeresOptionsFor(options, options.max_iterations, options.initial_soft_scale),
                     &update->problem, listening ? on_iteration : nullptr);
  // Ceres reads a stop by the callback as a success (USER_SUCCESS).
  const bool stopped = records->stopped();
  return {s.termination == TerminationType::kFailure,
          s.termination == TerminationType::kConvergence && !stopped, stopped, s.num_steps(),
          s.message};
}

// The largest distance of a vertex of `mesh` to the surface `reference`, over the reference's
// bounding-box diagonal.
double MaxDistanceToSurface(const PolyMesh& mesh, const PolyMesh& reference) {
  const ClosestPointQuery query(reference);
  Eigen::AlignedBox3d box;
  for (auto v : reference.vertices()) box.extend(Eigen::Vector3d(reference.point(v).data()));
  double worst = 0.0;
  for (auto v : mesh.vertices()) {
    const Eigen::Vector3d q(mesh.point(v).data());
    Eigen::Vector3d p, n;
    query.Project(q, &p, &n);
    worst = std::max(worst, (q - p).norm());
  }
  const double diagonal = box.diagonal().norm();
  return diagonal > 0.0 ? worst / diagonal : worst;
}

// The report lists the inner edges whose patches meet at an angle of at least this, worst
// first, up to kReportedEdges.
constexpr double kReportedEdgeAngleDeg = 1e-6;
constexpr size_t kReportedEdges = 100;

}  // namespace

bool HNet::RunANetStep(const PolyMesh& reference, StopTracker* stop, HNetSummary* summary) {
  RunReport& report = summary->report;
  report.initial = ToNamedValues(MeasureStarPlanarity(mesh_, input_));
  report.solver = options_.solver;
  if (MeasureStarPlanarity(mesh_, mesh_).max_star_planarity <= options_.anet.tolerance) return true;
  ANet anet(mesh_, &reference, options_.anet);
  const RunReport step = anet.RunWith(options_.solver, stop->callback());
  report.history = step.history;
  report.iterations = step.iterations;
  report.summary = step.summary;
  summary->anet_step_run = true;
  if (step.failed) {
    report.failed = true;
    report.termination = "A-net step failed: " + step.termination;
    return false;
  }
  mesh_ = anet.Result();
  if (stop->stopped()) {  // the whole run stops, without rounds
    report.termination = "USER_ABORT: stopped on request in the A-net step";
    return false;
  }
  return true;
}

HNetRound HNet::UpdateWeights(int round, const PolyMesh& reference) {
  (void)reference;
  const ShapeParameters shape = PropagateShapeParameters(mesh_, colour_, 0);
  double change = 0.0;
  if (!w_.empty())
    for (size_t f = 0; f < w_.size(); ++f)
      change = std::max(change, std::abs(shape.w[f] / w_[f] - 1.0));
  w_ = shape.w;
  HNetRound r = MeasureRound(round);
  r.max_inconsistency = shape.max_inconsistency;
  r.weight_change = change;
  return r;
}

HNetRound HNet::MeasureRound(int round) {
  HNetRound r;
  r.round = round;
  weights_.clear();
  for (auto f : mesh_.faces()) weights_.push_back(CornerWeights(mesh_, colour_, f, w_[f.idx()]));
  r.min_w = *std::min_element(w_.begin(), w_.end());
  r.max_w = *std::max_element(w_.begin(), w_.end());
  r.max_tangent_angle_deg = MaxTangentPlaneAngle(mesh_, weights_);
  r.star = MeasureStarPlanarity(mesh_, input_);  // displacement: vertex by vertex
  return r;
}

// 004 §3 where no exact extension need exist (not simply connected): round 0 measures the
// weights propagated over a spanning tree (inconsistent around the holes); round 1 solves for
// the vertices and the weights together.
void HNet::RunJoint(const PolyMesh& reference, const RoundCallback& on_round, StopTracker* stop,
                    HNetSummary* summary) {
  RunReport& report = summary->report;
  summary->equitwist_violations = EquitwistViolations(mesh_, colour_);
  auto start_time = std::chrono::steady_clock::now();
  HNetRound propagated = UpdateWeights(0, reference);
  propagated.seconds = SecondsSince(start_time);
  summary->rounds.push_back(propagated);
  if (on_round) on_round(propagated);
  const bool met = SolveJointly(1, 1.0, reference, on_round, stop, summary);
  if (report.failed) return;
  if (stop->stopped()) {
    report.termination =
        "USER_ABORT: stopped on request in the joint solve of vertices and weights";
    return;
  }
  report.converged = met;
  report.termination = met ? "vertices and weights optimised together (no exact extension "
                             "exists for this topology; frame rows met)"
                           : "vertices and weights optimised together; the frame rows were not "
                             "met within the iterations";
}

bool HNet::SolveJointly(int round, double soft_scale, const PolyMesh& reference,
                        const RoundCallback& on_round, StopTracker* stop, HNetSummary* summary) {
  RunReport& report = summary->report;
  const auto start_time = std::chrono::steady_clock::now();
  // Start from the current weights where they are usable, 1 elsewhere.
  std::vector<double> start = w_;
  for (double& w : start) w = std::isfinite(w) && w > 0.0 ? std::clamp(w, 0.1, 10.0) : 1.0;
  const std::unique_ptr<VertexUpdate> update =
      BuildVertexUpdate(mesh_, input_, colour_, options_, reference, &start);
  report.variables = update->problem.layout().num_variables();
  SolverOptions solver_options = options_.anet.solver;
  solver_options.residual_tolerance = options_.residual_tolerance;
  solver_options.initial_soft_scale = soft_scale;
  VertexUpdateRecords records(*update, mesh_, input_, report.iterations, stop);
  const VertexUpdateResult s =
      SolveVertexUpdate(solver_options, options_.solver, update.get(), &records);
  if (s.failed) {
    report.failed = true;
    report.termination = "joint vertex and weight update failed: " + s.message;
    return false;
  }
  StoreVertices(update->problem, update->vertex_block, update->norm, &mesh_);
  update->control.RestoreHeld(update->start, &mesh_);
  const VariableLayout& layout = update->problem.layout();
  for (size_t f = 0; f < w_.size(); ++f)
    w_[f] = update->problem.x()[layout.Index(update->shape_block, static_cast<int>(f), 0)];
  summary->faces_at_angle_bound = FacesAtCornerBound(mesh_, update->bounds);
  HNetRound joint = MeasureRound(round);
  joint.solver_iterations = s.steps;
  joint.vertex_update_converged = s.converged;
  joint.seconds = SecondsSince(start_time);
  report.iterations += s.steps;
  summary->rounds.push_back(joint);
  if (on_round) on_round(joint);
  return !s.stopped && s.converged && joint.min_w > 0.0 &&
         joint.star.max_star_planarity <= options_.anet.tolerance;
}

void HNet::RunRounds(const PolyMesh& reference, const RoundCallback& on_round, StopTracker* stop,
                     HNetSummary* summary) {
  RunReport& report = summary->report;
  const std::unique_ptr<VertexUpdate> update =
      BuildVertexUpdate(mesh_, input_, colour_, options_, reference);
  report.variables = update->problem.layout().num_variables();
  summary->equitwist_violations = EquitwistViolations(mesh_, colour_);
  SolverOptions solver_options = options_.anet.solver;
  solver_options.max_iterations = options_.iterations_per_round;
  solver_options.residual_tolerance = options_.residual_tolerance;
  solver_options.initial_soft_scale = options_.round_soft_scale;
  // Weights from the vertices, then vertices with the weights frozen.
  for (int round = 0; round < options_.max_rounds; ++round) {
    const auto round_start = std::chrono::steady_clock::now();
    StoreVertices(update->problem, update->vertex_block, update->norm, &mesh_);
    update->control.RestoreHeld(update->start, &mesh_);
    HNetRound r = UpdateWeights(round, reference);
    const bool settled = round > 0 && r.weight_change <= options_.weight_tolerance;
    const bool last = settled || round + 1 == options_.max_rounds;
    if (!last) {
      const std::string unusable = UnusableWeight(w_);
      if (!unusable.empty()) {
        report.failed = true;
        report.termination =
            "no frame points: " + unusable +
            "; the vertex stars there are flat or degenerate (an H-net needs a surface of "
            "negative Gaussian curvature: a flat region has no asymptotic directions)";
        return;
      }
      FreezeWeights(w_, update.get());
      VertexUpdateRecords records(*update, mesh_, input_, report.iterations, stop);
      const VertexUpdateResult s =
          SolveVertexUpdate(solver_options, options_.solver, update.get(), &records);
      if (s.failed) {
        report.failed = true;
        report.termination = "vertex update failed: " + s.message;
        return;
      }
      if (s.stopped) {
        // The round ends at the last iterate, the result: its vertices with the round's weights.
        StoreVertices(update->problem, update->vertex_block, update->norm, &mesh_);
        update->control.RestoreHeld(update->start, &mesh_);
        HNetRound at = MeasureRound(round);
        at.weight_change = r.weight_change;
        at.max_inconsistency = r.max_inconsistency;
        at.solver_iterations = s.steps;
        at.seconds = SecondsSince(round_start);
        report.iterations += s.steps;
        summary->rounds.push_back(at);
        if (on_round) on_round(at);
        report.termination =
            "USER_ABORT: stopped on request in the vertex update of round " + std::to_string(round);
        return;
      }
      r.vertex_update_converged = s.converged;
      r.solver_iterations = s.steps;
      report.iterations += s.steps;
    }
    r.seconds = SecondsSince(round_start);
    summary->rounds.push_back(r);
    if (on_round) on_round(r);
    if (last) {
      summary->faces_at_angle_bound = FacesAtCornerBound(mesh_, update->bounds);
      // Settled weights are not enough: the stars must be planar to the tolerance, which a
      // vertex update cut short by iterations_per_round can leave them not quite; a joint solve
      // of vertices and weights from the settled state (soft terms as in the rounds) finishes.
      report.converged = settled && r.star.max_star_planarity <= options_.anet.tolerance;
      report.termination =
          settled ? "weights and vertices settled" : "maximum number of rounds reached";
      if (settled && !report.converged) {
        report.converged =
            SolveJointly(round + 1, options_.round_soft_scale, reference, on_round, stop, summary);
        if (report.failed) return;
        if (stop->stopped()) {
          report.termination =
              "USER_ABORT: stopped on request in the joint solve of vertices and weights";
          return;
        }
        report.termination = report.converged
                                 ? "weights settled; a joint solve of vertices and weights made "
                                   "the stars planar"
                                 : "weights settled, but the stars are not planar to the "
                                   "tolerance even after a joint solve";
      }
      return;
    }
  }
}

HNetSummary HNet::Run(const IterationCallback& on_iteration, const RoundCallback& on_round) {
  const auto start = std::chrono::steady_clock::now();
  HNetSummary summary;
  summary.simply_connected = topology_note_.empty();
  const PolyMesh& reference = reference_ != nullptr ? *reference_ : input_;
  // 1. The A-net step, unless the stars are already planar to tolerance; 2. the rounds.
  StopTracker stop(on_iteration);
  if (RunANetStep(reference, &stop, &summary)) {
    if (summary.simply_connected)
      RunRounds(reference, on_round, &stop, &summary);
    else
      RunJoint(reference, on_round, &stop, &summary);
  }
  RunReport& report = summary.report;
  if (!summary.rounds.empty()) {
    const HNetRound& last = summary.rounds.back();
    report.final = ToNamedValues(last.star);
    for (const char* key :
         {"max_tangent_angle_deg", "weight_change", "w_min", "w_max", "max_inconsistency"})
      report.final.push_back({key, ValueOf(ToNamedValues(last), key)});
    const std::vector<double> angles = TangentPlaneAngles(mesh_, weights_);
    std::vector<int> order;
    for (size_t e = 0; e < angles.size(); ++e)
      if (angles[e] >= kReportedEdgeAngleDeg) order.push_back(static_cast<int>(e));
    std::sort(order.begin(), order.end(), [&](int a, int b) { return angles[a] > angles[b]; });
    summary.worst_edges = nlohmann::json::array();
    for (size_t k = 0; k < order.size() && k < kReportedEdges; ++k) {
      const auto h = mesh_.halfedge_handle(mesh_.edge_handle(order[k]), 0);
      summary.worst_edges.push_back(
          {{"vertices", {mesh_.from_vertex_handle(h).idx(), mesh_.to_vertex_handle(h).idx()}},
           {"tangent_angle_deg", angles[order[k]]}});
    }
    if (reference_ != nullptr) {
      summary.max_reference_distance = MaxDistanceToSurface(mesh_, *reference_);
      report.final.push_back({"max_reference_distance", summary.max_reference_distance});
    }
  }
  report.seconds = SecondsSince(start);
  return summary;
}

NamedValues ToNamedValues(const HNetRound& r) {
  NamedValues values = {{"round", static_cast<double>(r.round)},
                        {"max_tangent_angle_deg", r.max_tangent_angle_deg},
                        {"weight_change", r.weight_change},
                        {"w_min", r.min_w},
                        {"w_max", r.max_w},
                        {"max_inconsistency", r.max_inconsistency}};
  for (const NamedValue& v : ToNamedValues(r.star)) values.push_back(v);
  values.push_back({"solver_iterations", static_cast<double>(r.solver_iterations)});
  values.push_back({"seconds", r.seconds});
  return values;
}

nlohmann::json HNetJson(const PolyMesh& mesh, const std::vector<std::array<double, 4>>& weights) {
  nlohmann::json vertices = nlohmann::json::array(), faces = nlohmann::json::array(),
                 w = nlohmann::json::array();
  for (auto v : mesh.vertices()) {
    const auto& p = mesh.point(v);
    vertices.push_back({p[0], p[1], p[2]});
  }
  for (auto f : mesh.faces()) {
    nlohmann::json face = nlohmann::json::array();
    for (auto fv : mesh.fv_range(f)) face.push_back(fv.idx());
    faces.push_back(face);
    const auto& c = weights[f.idx()];
    w.push_back({c[0], c[1], c[2], c[3]});
  }
  return {{"vertices", vertices}, {"faces", faces}, {"weights", w}};
}

nlohmann::json HNet::ReportFacts(const HNetSummary& summary) {
  nlohmann::json rounds = nlohmann::json::array(), violations = nlohmann::json::array();
  for (const HNetRound& r : summary.rounds) {
    rounds.push_back(MeasuresJson(ToNamedValues(r)));
  }
  for (const auto& [a, b] : summary.equitwist_violations) violations.push_back({a, b});
  return {{"rounds", rounds},
          {"worst_edges", summary.worst_edges},
          {"simply_connected", summary.simply_connected},
          {"faces_at_angle_bound", summary.faces_at_angle_bound},
          {"equitwist_violations", violations}};
}

}  // namespace gproj::nets
