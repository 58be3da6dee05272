#include "gproj/problems/remesh/quad_remeshing.h"

#include <Eigen/Geometry>
#include <Eigen/SparseCore>
#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <functional>
#include <limits>
#include <memory>
#include <numeric>
#include <queue>
#include <string>

#include "gproj/geometry/mesh/scale_free.h"
#include "gproj/problems/mesh/vertex_control.h"
#include "gproj/problems/nets/hnet.h"

namespace gproj::remesh {
namespace {

constexpr double kQuarter = M_PI / 2.0;
// The quads' edge length, in mean triangle edges.
constexpr double kMinEdgeLength = 0.25, kMaxEdgeLength = 1e6;
// Map values this close to an integer (in quad edges) are taken as that integer.
constexpr double kSnapToInteger = 1e-8;

Eigen::Vector2d Direction(double angle) { return {std::cos(angle), std::sin(angle)}; }

// A face's own orthonormal basis (e1 along its first edge, e2 = n × e1) and its corners there.
struct FaceBasis {
  std::array<int, 3> vertex;
  Eigen::Vector3d e1, e2, normal;
  std::array<Eigen::Vector2d, 3> corner;
  double area = 0.0;
  Eigen::Vector2d To2d(const Eigen::Vector3d& x) const { return {x.dot(e1), x.dot(e2)}; }
  int Corner(int v) const { return vertex[0] == v ? 0 : vertex[1] == v ? 1 : 2; }
  // The gradient of the linear function with corner values s: G s, G 2 × 3.
  Eigen::Matrix<double, 2, 3> Gradient() const {
    Eigen::Matrix<double, 2, 3> g;
    for (int i = 0; i < 3; ++i) {
      const Eigen::Vector2d e = corner[(i + 2) % 3] - corner[(i + 1) % 3];
      g.col(i) = Eigen::Vector2d(-e.y(), e.x()) / (2.0 * area);
    }
    return g;
  }
};

// The frame of a face: the cross angle γ (of the bisector of a and b) in its basis and the half
// angle θ of the pair about it: a at γ − θ, b at γ + θ. A quarter turn (a, b) → (b, −a) is
// (γ, θ) → (γ + π/2, π/2 − θ).
struct Frame {
  double gamma = 0.0, theta = M_PI / 4;
  void Turn(int k) {
    k &= 3;
    gamma += k * kQuarter;
    if (k & 1) theta = kQuarter - theta;
  }
};

struct Surface {
  const PolyMesh& mesh;
  std::vector<FaceBasis> basis;
  std::vector<Frame> frame;
  // Quarter turns per symmetry step: 1 for the principal cross (d1 and d2 may trade places), 2
  // for the asymptotic pair (its two families never do: they differ in the sign of their
  // torsion, Beltrami–Enneper).
  int step = 2;
};

// Angle that carries a direction of face(opposite(h))'s basis to face(h)'s, unfolding across
// their common edge.
double Transport(const Surface& s, PolyMesh::HalfedgeHandle h) {
  const auto& m = s.mesh;
  const auto& p = m.point(m.from_vertex_handle(h));
  const auto& q = m.point(m.to_vertex_handle(h));
  const Eigen::Vector3d e(q[0] - p[0], q[1] - p[1], q[2] - p[2]);
  const FaceBasis& f = s.basis[m.face_handle(h).idx()];
  const FaceBasis& g = s.basis[m.opposite_face_handle(h).idx()];
  const Eigen::Vector2d ef = f.To2d(e), eg = g.To2d(e);
  return std::atan2(ef.y(), ef.x()) - std::atan2(eg.y(), eg.x());
}

// The quarter turns k (a multiple of s.step) that bring the frame of face(opposite(h)) closest
// to that of face(h), and the remaining turning δ ∈ [−step π/4, step π/4] of the frame from
// face(h) to its neighbour.
int Matching(const Surface& s, PolyMesh::HalfedgeHandle h, double* delta) {
  const Frame& f = s.frame[s.mesh.face_handle(h).idx()];
  const Frame& g = s.frame[s.mesh.opposite_face_handle(h).idx()];
  const double carried = g.gamma + Transport(s, h);
  const double k = s.step * std::round((f.gamma - carried) / (s.step * kQuarter));
  if (delta) *delta = carried + k * kQuarter - f.gamma;
  return static_cast<int>(((static_cast<long long>(k) % 4) + 4) % 4);
}

Surface Frames(const PolyMesh& mesh, const DirectionField& field,
               const QuadRemeshOptions& options) {
  Surface s{mesh, {}, {}, field.symmetry == 4 ? 1 : 2};
  s.basis.resize(mesh.n_faces());
  s.frame.resize(mesh.n_faces());
  const double min_half = 0.5 * options.min_net_angle_deg * M_PI / 180.0;
  for (auto f : mesh.faces()) {
    FaceBasis& b = s.basis[f.idx()];
    std::array<Eigen::Vector3d, 3> p;
    int i = 0;
    for (auto fv = mesh.cfv_iter(f); fv.is_valid(); ++fv, ++i) {
      b.vertex[i] = fv->idx();
      const auto& q = mesh.point(*fv);
      p[i] = Eigen::Vector3d(q[0], q[1], q[2]);
    }
    const Eigen::Vector3d n = (p[1] - p[0]).cross(p[2] - p[0]);
    b.normal = n.normalized();
    b.e1 = (p[1] - p[0]).normalized();
    b.e2 = b.normal.cross(b.e1);
    for (int k = 0; k < 3; ++k) b.corner[k] = b.To2d(p[k] - p[0]);
    b.area = 0.5 * n.norm();
    // The principal line d1 of the corners, averaged with the field's symmetry (angles times
    // 2 or 4), and the asymptotic half angle where K < 0.
    const double symmetry = field.symmetry;
    Eigen::Vector2d doubled = Eigen::Vector2d::Zero();
    double theta = 0.0;
    int negative = 0;
    for (int k = 0; k < 3; ++k) {
      const VertexCurvature& c = field.curvature[b.vertex[k]];
      if (!c.fitted) continue;
      const Eigen::Vector2d d = b.To2d(c.d1);
      if (!(d.norm() > 0.0)) continue;
      const double alpha = std::atan2(d.y(), d.x());
      doubled += d.norm() * Direction(symmetry * alpha);
      if (c.k1 > 0.0 && c.k2 < 0.0) theta += std::atan(std::sqrt(-c.k1 / c.k2)), ++negative;
    }
    const double alpha = std::atan2(doubled.y(), doubled.x()) / symmetry;
    Frame& frame = s.frame[f.idx()];
    if (options.directions == DirectionKind::kPrincipal) {
      frame.gamma = alpha + M_PI / 4;  // a = d1, b = d2
      frame.theta = M_PI / 4;
    } else {
      frame.gamma = alpha;  // the asymptotic pair is symmetric about d1
      frame.theta = negative > 0 ? theta / negative : M_PI / 4;
      frame.theta = std::clamp(frame.theta, min_half, kQuarter - min_half);
    }
  }
  return s;
}

// Frame singularities at inner vertices: (Σ δ + angle defect) / 2π, in quarters (cross) or
// halves (pair).
std::vector<FrameSingularity> FrameSingularities(const Surface& s) {
  const auto& m = s.mesh;
  std::vector<FrameSingularity> out;
  for (auto v : m.vertices()) {
    if (m.is_boundary(v) || m.is_isolated(v)) continue;
    double total = 2.0 * M_PI;
    for (auto h : m.voh_range(v)) {
      // Corner angle of face(h) at v, and the turning of the cross from face(opposite(h)) to
      // face(h) (counter-clockwise about v).
      const auto& o = m.point(v);
      const auto& a = m.point(m.to_vertex_handle(h));
      const auto& b = m.point(m.to_vertex_handle(m.next_halfedge_handle(h)));
      const Eigen::Vector3d x(a[0] - o[0], a[1] - o[1], a[2] - o[2]);
      const Eigen::Vector3d y(b[0] - o[0], b[1] - o[1], b[2] - o[2]);
      total -= std::atan2(x.cross(y).norm(), x.dot(y));
      double delta = 0.0;
      Matching(s, m.opposite_halfedge_handle(h), &delta);
      total += delta;
    }
    const double steps = 4.0 / s.step;  // the index is a multiple of 1 / steps
    const double index = std::round(steps * total / (2.0 * M_PI)) / steps;
    if (index != 0.0) out.push_back({v.idx(), index});
  }
  return out;
}

// The shortest path (by length) from any of `sources` to a vertex `target` accepts, through
// vertices not `blocked`; its vertices from the source on, or empty when there is none.
std::vector<int> ShortestPath(const PolyMesh& m, const std::vector<int>& sources,
                              const std::function<bool(int)>& target,
                              const std::vector<char>& blocked) {
  std::vector<double> distance(m.n_vertices(), std::numeric_limits<double>::infinity());
  std::vector<int> previous(m.n_vertices(), -1);
  using Item = std::pair<double, int>;
  std::priority_queue<Item, std::vector<Item>, std::greater<Item>> queue;
  for (int v : sources) distance[v] = 0.0, queue.push({0.0, v});
  while (!queue.empty()) {
    const auto [d, v] = queue.top();
    queue.pop();
    if (d > distance[v]) continue;
    if (target(v)) {
      std::vector<int> path;
      for (int w = v; w >= 0; w = previous[w]) path.push_back(w);
      std::reverse(path.begin(), path.end());
      return path;
    }
    const auto vh = m.vertex_handle(v);
    for (auto h : m.voh_range(vh)) {
      const int w = m.to_vertex_handle(h).idx();
      if (blocked[w]) continue;
      const double step = (m.point(m.to_vertex_handle(h)) - m.point(vh)).norm();
      if (d + step < distance[w]) {
        distance[w] = d + step;
        previous[w] = v;
        queue.push({d + step, w});
      }
    }
  }
  return {};
}

// Shortest paths that join every boundary loop to the longest one (each loop to one already
// joined, so the paths form a tree), avoiding the `blocked` vertices and each other: cut along
// them a surface with holes is a disk. Per path its vertices from the loop already joined on;
// the paths' vertices are added to `blocked`.
std::vector<std::vector<int>> HolePaths(const PolyMesh& m,
                                        const std::vector<std::vector<int>>& loops,
                                        std::vector<char>* blocked) {
  std::vector<std::vector<int>> paths;
  if (loops.size() < 2) return paths;
  std::vector<int> loop_of(m.n_vertices(), -1);
  std::vector<double> length(loops.size(), 0.0);
  for (size_t l = 0; l < loops.size(); ++l)
    for (size_t i = 0; i < loops[l].size(); ++i) {
      loop_of[loops[l][i]] = static_cast<int>(l);
      const int next = loops[l][(i + 1) % loops[l].size()];
      length[l] += (m.point(m.vertex_handle(next)) - m.point(m.vertex_handle(loops[l][i]))).norm();
    }
  std::vector<char> joined(loops.size(), 0);
  joined[std::max_element(length.begin(), length.end()) - length.begin()] = 1;
  for (size_t round = 1; round < loops.size(); ++round) {
    std::vector<int> sources;
    for (size_t l = 0; l < loops.size(); ++l)
      if (joined[l])
        for (int v : loops[l])
          if (!(*blocked)[v]) sources.push_back(v);
    const std::vector<int> path = ShortestPath(
        m, sources, [&](int v) { return loop_of[v] >= 0 && !joined[loop_of[v]] && !(*blocked)[v]; },
        *blocked);
    if (path.size() < 2) {
      size_t l = 0;
      while (joined[l]) ++l;
      throw InputError("the hole bounded by vertex " + std::to_string(loops[l][0]) +
                       " cannot be joined to the other boundary loops without crossing a frame "
                       "singularity or another cut: the cut through the holes needs a path "
                       "between them");
    }
    joined[loop_of[path.back()]] = 1;
    for (int v : path) (*blocked)[v] = 1;
    paths.push_back(path);
  }
  return paths;
}

PolyMesh::HalfedgeHandle HalfedgeBetween(const PolyMesh& m, int a, int b) {
  return m.find_halfedge(m.vertex_handle(a), m.vertex_handle(b));
}

// Faces joined by edges (not `cut` ones, when given): the number of pieces.
int FaceComponents(const PolyMesh& m, const std::vector<char>* cut = nullptr) {
  std::vector<char> seen(m.n_faces(), 0);
  int components = 0;
  for (auto start : m.faces()) {
    if (seen[start.idx()]) continue;
    ++components;
    std::vector<int> stack = {start.idx()};
    seen[start.idx()] = 1;
    while (!stack.empty()) {
      const auto f = m.face_handle(stack.back());
      stack.pop_back();
      for (auto h : m.fh_range(f)) {
        const auto g = m.opposite_face_handle(h);
        if (g.is_valid() && !seen[g.idx()] && !(cut && (*cut)[m.edge_handle(h).idx()]))
          seen[g.idx()] = 1, stack.push_back(g.idx());
      }
    }
  }
  return components;
}

// Faces in a union–find forest, for the dual spanning tree.
struct FaceSets {
  std::vector<int> parent;
  explicit FaceSets(size_t n) : parent(n) { std::iota(parent.begin(), parent.end(), 0); }
  int Find(int f) {
    while (parent[f] != f) f = parent[f] = parent[parent[f]];
    return f;
  }
  bool Join(int a, int b) {
    a = Find(a), b = Find(b);
    if (a == b) return false;
    parent[a] = b;
    return true;
  }
};

// The arcs around a handle of the surface cut along `cut`, shortest first: each between two
// boundary vertices not `blocked`, through vertices not blocked, keeping the faces connected.
// Tree–cotree (Erickson and Whittlesey 2005) with the boundary as the root: a shortest-path
// forest T from the free boundary vertices and a spanning tree of the faces across edges not in
// T; an edge in neither closes a loop around a handle, and T's paths from its ends to the
// boundary make it an arc. The second path is tried first as the shortest around the first to a
// boundary vertex not next to the first's root along the boundary, then as T's own path (from
// another root), then to any boundary vertex.
std::vector<std::vector<int>> HandleArcs(const PolyMesh& m, const std::vector<char>& blocked,
                                         std::vector<char>* cut) {
  const size_t n = m.n_vertices();
  std::vector<double> distance(n, std::numeric_limits<double>::infinity());
  std::vector<int> previous(n, -1), root(n, -1);
  using Item = std::pair<double, int>;
  std::priority_queue<Item, std::vector<Item>, std::greater<Item>> queue;
  for (auto v : m.vertices())
    if (m.is_boundary(v) && !blocked[v.idx()])
      distance[v.idx()] = 0.0, root[v.idx()] = v.idx(), queue.push({0.0, v.idx()});
  while (!queue.empty()) {
    const auto [d, v] = queue.top();
    queue.pop();
    if (d > distance[v]) continue;
    for (auto h : m.voh_range(m.vertex_handle(v))) {
      const int w = m.to_vertex_handle(h).idx();
      const double step = m.calc_edge_length(h);
      if (!blocked[w] && d + step < distance[w])
        distance[w] = d + step, previous[w] = v, root[w] = root[v], queue.push({d + step, w});
    }
  }
  std::vector<char> in_tree(m.n_edges(), 0);
  for (size_t w = 0; w < n; ++w)
    if (previous[w] >= 0)
      in_tree[m.edge_handle(HalfedgeBetween(m, previous[w], static_cast<int>(w))).idx()] = 1;
  // The faces' tree takes the edges no arc can use (at a blocked vertex) first.
  FaceSets faces(m.n_faces());
  std::vector<int> loop_edges;
  for (const bool usable : {false, true})
    for (auto e : m.edges()) {
      if (m.is_boundary(e) || (*cut)[e.idx()] || in_tree[e.idx()]) continue;
      const auto h = m.halfedge_handle(e, 0);
      const int a = m.from_vertex_handle(h).idx(), b = m.to_vertex_handle(h).idx();
      const bool free = !blocked[a] && !blocked[b] && root[a] >= 0 && root[b] >= 0;
      if (free != usable) continue;
      if (!faces.Join(m.face_handle(h).idx(), m.opposite_face_handle(h).idx()) && usable)
        loop_edges.push_back(e.idx());
    }
  const auto arc_length = [&](int e) {
    const auto h = m.halfedge_handle(m.edge_handle(e), 0);
    return distance[m.from_vertex_handle(h).idx()] + distance[m.to_vertex_handle(h).idx()] +
           m.calc_edge_length(h);
  };
  std::sort(loop_edges.begin(), loop_edges.end(),
            [&](int a, int b) { return arc_length(a) < arc_length(b); });
  const auto tree_path = [&](int v) {  // from its root to v
    std::vector<int> path;
    for (int w = v; w >= 0; w = previous[w]) path.push_back(w);
    std::reverse(path.begin(), path.end());
    return path;
  };
  const auto next_on_boundary = [&](int r, int v) {
    const auto h = m.find_halfedge(m.vertex_handle(r), m.vertex_handle(v));
    return h.is_valid() && m.is_boundary(m.edge_handle(h));
  };
  std::vector<std::vector<int>> arcs;
  const auto try_arc = [&](std::vector<int> arc) {
    // A simple arc between two boundary vertices, its inner vertices off the boundary (one that
    // touched the boundary would be two arcs, or run along a boundary edge).
    if (arc.size() < 2 || arc.front() == arc.back() ||
        !m.is_boundary(m.vertex_handle(arc.front())) || !m.is_boundary(m.vertex_handle(arc.back())))
      return;
    for (size_t i = 1; i + 1 < arc.size(); ++i)
      if (m.is_boundary(m.vertex_handle(arc[i]))) return;
    for (size_t i = 0; i + 1 < arc.size(); ++i)
      if (m.is_boundary(m.edge_handle(HalfedgeBetween(m, arc[i], arc[i + 1])))) return;
    std::vector<int> arc_edges;
    for (size_t i = 0; i + 1 < arc.size(); ++i)
      arc_edges.push_back(m.edge_handle(HalfedgeBetween(m, arc[i], arc[i + 1])).idx());
    for (int c : arc_edges) (*cut)[c] = 1;
    if (FaceComponents(m, cut) == 1) arcs.push_back(std::move(arc));
    for (int c : arc_edges) (*cut)[c] = 0;
  };
  for (int e : loop_edges) {
    const auto h = m.halfedge_handle(m.edge_handle(e), 0);
    int a = m.from_vertex_handle(h).idx(), b = m.to_vertex_handle(h).idx();
    std::vector<int> first = tree_path(a);
    if (std::find(first.begin(), first.end(), b) != first.end()) {  // b above a: start from b
      std::swap(a, b);
      first = tree_path(a);
    }
    std::vector<std::vector<int>> tried;  // the kinds' arcs often coincide
    std::vector<char> around = blocked;
    for (int v : first) around[v] = 1;
    std::vector<char> apart = around;  // also away from the boundary next to a's root
    for (auto r : m.vv_range(m.vertex_handle(root[a])))
      if (next_on_boundary(root[a], r.idx())) apart[r.idx()] = 1;
    // The way back from b to a boundary vertex not next to a's root (so that the arc leaves
    // free boundary vertices on both of its sides), then T's own path, then any.
    for (int kind = 0; kind < 3; ++kind) {
      std::vector<int> rest;
      if (kind == 1 && root[b] == root[a]) continue;
      if (kind == 1) {
        rest = tree_path(b);
        std::reverse(rest.begin(), rest.end());
      } else {
        if (kind == 0 && apart[b]) continue;
        rest = ShortestPath(
            m, {b}, [&](int v) { return m.is_boundary(m.vertex_handle(v)); },
            kind == 0 ? apart : around);
      }
      if (rest.empty() || !m.is_boundary(m.vertex_handle(rest.back()))) continue;
      std::vector<int> arc = first;
      arc.insert(arc.end(), rest.begin(), rest.end());
      if (std::find(tried.begin(), tried.end(), arc) != tried.end()) continue;
      tried.push_back(arc);
      try_arc(std::move(arc));
    }
  }
  return arcs;
}

// Cuts `arcs` more arcs around the handles (HandleArcs), each keeping the next ones possible:
// an arc after which the rest cannot be cut is taken back and the next one tried, up to
// *attempts arcs in all (polling `stop` between them). Whether it succeeded; the arcs are added to
// *paths, their vertices to `blocked` and their edges to `cut`.
bool CutAroundHandles(const PolyMesh& m, int arcs, int* attempts, const StopPoll& stop,
                      std::vector<char>* blocked, std::vector<char>* cut,
                      std::vector<std::vector<int>>* paths) {
  if (arcs == 0) return true;
  PollStop(stop, "the cut around the handles");
  for (const std::vector<int>& arc : HandleArcs(m, *blocked, cut)) {
    if (--*attempts < 0) return false;
    std::vector<int> arc_edges;
    for (size_t i = 0; i + 1 < arc.size(); ++i)
      arc_edges.push_back(m.edge_handle(HalfedgeBetween(m, arc[i], arc[i + 1])).idx());
    for (int v : arc) (*blocked)[v] = 1;
    for (int c : arc_edges) (*cut)[c] = 1;
    paths->push_back(arc);
    if (CutAroundHandles(m, arcs - 1, attempts, stop, blocked, cut, paths)) return true;
    paths->pop_back();
    for (int v : arc) (*blocked)[v] = 0;
    for (int c : arc_edges) (*cut)[c] = 0;
  }
  return false;
}

// Two arcs around every handle (each between boundary vertices, avoiding the `blocked` vertices
// and each other, the faces still connected across the edges not `cut`): cut along them and the
// holes' paths a surface of genus g is a disk. The arcs' vertices are added to `blocked` and
// their edges to `cut`.
std::vector<std::vector<int>> HandlePaths(const PolyMesh& m, int handles, const StopPoll& stop,
                                          std::vector<char>* blocked, std::vector<char>* cut) {
  std::vector<std::vector<int>> paths;
  int attempts = 16 * handles;
  if (!CutAroundHandles(m, 2 * handles, &attempts, stop, blocked, cut, &paths))
    throw InputError("the surface's " + std::to_string(handles) + " handle" +
                     (handles == 1 ? "" : "s") +
                     " cannot be cut open without crossing a frame singularity or another cut "
                     "(two arcs from the boundary around each handle, disjoint; a larger hole "
                     "leaves more room for them): cut the surface open along a closed curve "
                     "around each handle first");
  return paths;
}

// Shortest paths from every singularity to the boundary, each avoiding the other singularities,
// the `blocked` vertices and the paths already cut. Per path its vertices from the singularity
// on; the paths' vertices are added to `blocked`.
std::vector<std::vector<int>> SingularityPaths(const PolyMesh& m,
                                               const std::vector<FrameSingularity>& singularities,
                                               std::vector<char>* blocked) {
  for (const FrameSingularity& s : singularities) (*blocked)[s.vertex] = 1;
  std::vector<std::vector<int>> paths;
  for (const FrameSingularity& s : singularities) {
    const std::vector<int> path = ShortestPath(
        m, {s.vertex}, [&](int v) { return v != s.vertex && m.is_boundary(m.vertex_handle(v)); },
        *blocked);
    if (path.empty())
      throw InputError("the frame singularity at vertex " + std::to_string(s.vertex) +
                       " cannot be joined to the boundary without crossing another "
                       "singularity's cut: the field has " +
                       std::to_string(singularities.size()) +
                       " singularities, too many for a cut from each to the boundary (a noisy "
                       "mesh? smooth the field more with a smaller `smooth`, or the mesh)");
    for (int v : path) (*blocked)[v] = 1;  // the boundary end too: one cut per boundary vertex
    paths.push_back(path);
  }
  return paths;
}

// V − E + F over the vertices faces use.
long EulerCharacteristic(const PolyMesh& m) {
  long used = 0;
  for (auto v : m.vertices()) used += !m.is_isolated(v);
  return used - static_cast<long>(m.n_edges()) + static_cast<long>(m.n_faces());
}

}  // namespace

int CheckTriangulatedSurface(const PolyMesh& m) {
  if (m.n_faces() == 0) throw InputError("the mesh has no faces");
  for (auto f : m.faces())
    if (m.valence(f) != 3)
      throw InputError("face " + std::to_string(f.idx()) + " has " + std::to_string(m.valence(f)) +
                       " vertices: the remeshing needs a triangle mesh");
  for (auto v : m.vertices()) {
    int boundary = 0;
    for (auto h : m.voh_range(v)) boundary += m.is_boundary(h);
    if (boundary > 1)
      throw InputError("vertex " + std::to_string(v.idx()) +
                       " joins separate fans of faces (a non-manifold vertex): the remeshing "
                       "needs a manifold surface");
  }
  const int loops = static_cast<int>(BoundaryLoops(m).size());
  const long euler = EulerCharacteristic(m);
  const std::string shape = "Euler characteristic " + std::to_string(euler) + ", " +
                            std::to_string(loops) + " boundary loop" + (loops == 1 ? "" : "s");
  if (FaceComponents(m) != 1)
    throw InputError("the surface has several components (" + shape +
                     "): the remeshing needs one connected surface; remesh each on its own");
  if (loops == 0)
    throw InputError("the surface is closed (" + shape +
                     "): the quad remeshing cuts it from its holes, so cut it open first");
  return loops;
}

bool QuadRemeshOptions::IsValid(std::string* why) const {
  if (!(edge_length >= 0.0) || !std::isfinite(edge_length)) {
    *why = "the edge length must be a finite number >= 0 (0: 3 mean triangle edges)";
    return false;
  }
  if (!(smoothing > 0.0) || !std::isfinite(smoothing)) {
    *why = "the field smoothing weight must be a finite number > 0";
    return false;
  }
  if (!(size_weight > 0.0 && size_weight <= 10.0)) {
    *why = "the size weight must be in (0, 10]";
    return false;
  }
  if (!(min_net_angle_deg > 0.0 && min_net_angle_deg <= 90.0)) {
    *why = "the smallest net angle must be in (0, 90] degrees";
    return false;
  }
  return fit.IsValid(why);
}

namespace {

// The quads' edge length in mean edges of the unit-scaled mesh; throws InputError outside
// [kMinEdgeLength, kMaxEdgeLength].
double UnitEdgeLength(const QuadRemeshOptions& options, const UnitFrame& unit) {
  const double h = options.edge_length > 0.0 ? options.edge_length / unit.length : 3.0;
  // Quads much smaller than the triangles only interpolate them (and a tiny h asks for
  // millions of quads): at least a quarter of a mean triangle edge.
  if (!(h >= kMinEdgeLength && h <= kMaxEdgeLength)) {
    char text[200];
    std::snprintf(text, sizeof(text),
                  "the edge length (`edge_length`) %g is %g mean triangle edges; it must be within "
                  "%g … %g of "
                  "them (%g … %g)",
                  h * unit.length, h, kMinEdgeLength, kMaxEdgeLength, kMinEdgeLength * unit.length,
                  kMaxEdgeLength * unit.length);
    throw InputError(text);
  }
  return h;
}

void RefuseSingularitiesNoQuadCanFollow(const std::vector<FrameSingularity>& singularities) {
  for (const FrameSingularity& sg : singularities)
    if (sg.index >= 1.0) {
      char text[300];
      std::snprintf(text, sizeof(text),
                    "the frame field has a singularity of index %+g at vertex %d (an umbilic of "
                    "a surface of revolution?), which no quad vertex can follow (valence 4 - 4 × "
                    "index): perturb the surface or smooth the field more",
                    sg.index, sg.vertex);
      throw InputError(text);
    }
}

// The cut of the mesh into a disk along paths from the singularities, and how the map jumps
// across it.
struct Cuts {
  // Vertex paths: first the arcs between boundary vertices (those through the holes, each from a
  // boundary loop to another, then two around each handle), then one from each singularity to
  // the boundary.
  std::vector<std::vector<int>> paths;
  // Per path: −1 for a singularity's, whose translation is (I − R) u(s) (s its first vertex, a
  // fixed point); k ≥ 0 for an arc, whose translation t_k is unknown (map unknowns
  // 2 n + 2k, 2 n + 2k + 1, n the vertices).
  std::vector<int> translation;
  int arcs = 0;                     // paths between boundary vertices
  std::vector<char> cut;            // per edge: on a path
  std::vector<int> path_of_vertex;  // the path a vertex is on (not a singularity), or −1
  std::vector<int> path_turns;      // per path: the quarter turns of the frames across it
  // Per face and corner: on the right of a path (the map there is R u(v) + t_p).
  std::vector<std::array<char, 3>> right_side;
  // The first vertex of path p with corners on its right: a singularity's own corners are all
  // on the left.
  size_t FirstSplit(size_t p) const { return translation[p] < 0 ? 1 : 0; }
};

Cuts CutAlongPaths(const PolyMesh& m, const std::vector<FrameSingularity>& singularities,
                   int handles, const StopPoll& stop, std::vector<int>* cut_edges) {
  Cuts c;
  std::vector<char> blocked(m.n_vertices(), 0);
  for (const FrameSingularity& s : singularities) blocked[s.vertex] = 1;
  c.paths = HolePaths(m, BoundaryLoops(m), &blocked);
  c.cut.assign(m.n_edges(), 0);
  for (const auto& path : c.paths)
    for (size_t i = 0; i + 1 < path.size(); ++i)
      c.cut[m.edge_handle(HalfedgeBetween(m, path[i], path[i + 1])).idx()] = 1;
  for (auto& arc : HandlePaths(m, handles, stop, &blocked, &c.cut))
    c.paths.push_back(std::move(arc));
  c.arcs = static_cast<int>(c.paths.size());
  for (int k = 0; k < c.arcs; ++k) c.translation.push_back(k);
  for (auto& path : SingularityPaths(m, singularities, &blocked)) {
    c.paths.push_back(std::move(path));
    c.translation.push_back(-1);
  }
  c.path_of_vertex.assign(m.n_vertices(), -1);
  for (size_t p = 0; p < c.paths.size(); ++p) {
    for (size_t i = c.FirstSplit(p); i < c.paths[p].size(); ++i)
      c.path_of_vertex[c.paths[p][i]] = static_cast<int>(p);
    for (size_t i = 0; i + 1 < c.paths[p].size(); ++i) {
      const auto hh = HalfedgeBetween(m, c.paths[p][i], c.paths[p][i + 1]);
      c.cut[m.edge_handle(hh).idx()] = 1;
      cut_edges->push_back(m.edge_handle(hh).idx());
    }
  }
  return c;
}

// Combs the frames across the uncut edges (breadth first from face 0); throws InputError when
// an uncut edge still has a matching.
void CombFrames(const PolyMesh& m, const Cuts& cuts, Surface* s) {
  std::vector<char> combed(m.n_faces(), 0);
  std::queue<int> queue;
  queue.push(0);
  combed[0] = 1;
  while (!queue.empty()) {
    const auto f = m.face_handle(queue.front());
    queue.pop();
    for (auto hh : m.fh_range(f)) {
      const auto g = m.opposite_face_handle(hh);
      if (!g.is_valid() || combed[g.idx()] || cuts.cut[m.edge_handle(hh).idx()]) continue;
      s->frame[g.idx()].Turn(Matching(*s, hh, nullptr));
      combed[g.idx()] = 1;
      queue.push(g.idx());
    }
  }
  for (auto e : m.edges()) {
    if (m.is_boundary(e) || cuts.cut[e.idx()]) continue;
    if (Matching(*s, m.halfedge_handle(e, 0), nullptr) != 0)
      throw InputError("the frame field does not comb across edge " + std::to_string(e.idx()) +
                       " (a singularity below the detection threshold): smooth the field more");
  }
}

// Across a path the combed frames turn by k quarter turns (the same k along the path: its inner
// vertices are regular); a frame turned by a quarter turn has the target gradient turned by
// −π/2, so the map jumps by R = Rot(kπ/2) from the left faces to the right.
void FindPathTurns(const PolyMesh& m, const Surface& s, Cuts* cuts) {
  const auto& paths = cuts->paths;
  cuts->path_turns.assign(paths.size(), 0);
  for (size_t p = 0; p < paths.size(); ++p)
    for (size_t i = 0; i + 1 < paths[p].size(); ++i) {
      const int k = Matching(s, HalfedgeBetween(m, paths[p][i], paths[p][i + 1]), nullptr);
      if (i == 0) cuts->path_turns[p] = k;
      if (k != cuts->path_turns[p])
        throw InputError("the frame field turns differently along the cut from vertex " +
                         std::to_string(paths[p][0]) + " (at vertex " +
                         std::to_string(paths[p][i]) + "): smooth the field more");
    }
}

// Corners on the right of a path: flooded around the vertex from the path's right face across
// uncut edges.
void FindRightSides(const PolyMesh& m, const Surface& s, Cuts* cuts) {
  const auto& paths = cuts->paths;
  cuts->right_side.assign(m.n_faces(), {0, 0, 0});
  for (size_t p = 0; p < paths.size(); ++p)
    for (size_t i = cuts->FirstSplit(p); i < paths[p].size(); ++i) {
      const int v = paths[p][i];
      // The face on the right of the path's edge at v: that of v → previous, or of next → v at
      // a hole path's first vertex.
      const auto right =
          i > 0 ? HalfedgeBetween(m, v, paths[p][i - 1]) : HalfedgeBetween(m, paths[p][i + 1], v);
      std::vector<int> stack = {m.face_handle(right).idx()};
      std::vector<int> seen;
      while (!stack.empty()) {
        const int f = stack.back();
        stack.pop_back();
        if (std::find(seen.begin(), seen.end(), f) != seen.end()) continue;
        seen.push_back(f);
        cuts->right_side[f][s.basis[f].Corner(v)] = 1;
        for (auto fh : m.fh_range(m.face_handle(f))) {
          if (m.from_vertex_handle(fh).idx() != v && m.to_vertex_handle(fh).idx() != v) continue;
          const auto g = m.opposite_face_handle(fh);
          if (g.is_valid() && !cuts->cut[m.edge_handle(fh).idx()]) stack.push_back(g.idx());
        }
      }
    }
}

// The least-squares map. Unknowns: u(v) ∈ R² per vertex (on the left of a cut); the right
// corners of path p are R u(v) + (I − R) u(s_p). Unknowns can be fixed (the singularities' u,
// rounded after a first solve).
class MapSystem {
 public:
  MapSystem(const PolyMesh& m, const Surface& s, const Cuts& cuts, double h,
            const QuadRemeshOptions& options)
      : m_(m),
        s_(s),
        cuts_(cuts),
        h_(h),
        options_(options),
        n_(2 * static_cast<int>(m.n_vertices()) + 2 * cuts.arcs),
        fixed_(n_, std::numeric_limits<double>::quiet_NaN()),
        x_(Eigen::VectorXd::Zero(n_)),
        solver_(CreateSparseCholesky(options.linear_solver, 0)) {}

  // The map at corner k of face f, component `component`: Σ coeff x[var] over *terms.
  void CornerTerms(int f, int k, int component, std::vector<std::pair<int, double>>* terms) const {
    terms->clear();
    const int v = s_.basis[f].vertex[k];
    if (!cuts_.right_side[f][k]) {
      terms->push_back({2 * v + component, 1.0});
      return;
    }
    const int p = cuts_.path_of_vertex[v];
    const Eigen::Matrix2d r = QuarterTurns(cuts_.path_turns[p]);
    for (int j = 0; j < 2; ++j)
      if (r(component, j) != 0.0) terms->push_back({2 * v + j, r(component, j)});
    if (cuts_.translation[p] >= 0) {  // a hole's cut: + t_k
      terms->push_back({TranslationUnknown(cuts_.translation[p], component), 1.0});
      return;
    }
    const int sv = cuts_.paths[p][0];  // a singularity's cut: + (I − R) u(s)
    const Eigen::Matrix2d c = Eigen::Matrix2d::Identity() - r;
    for (int j = 0; j < 2; ++j)
      if (c(component, j) != 0.0) terms->push_back({2 * sv + j, c(component, j)});
  }

  // The unknown of component `component` of the translation across hole cut k.
  int TranslationUnknown(int k, int component) const {
    return 2 * static_cast<int>(m_.n_vertices()) + 2 * k + component;
  }
  void Fix(int var, double value) { fixed_[var] = value; }
  const Eigen::VectorXd& x() const { return x_; }

  // x: the least-squares solution with the fixed unknowns at their values.
  void Solve() {
    std::vector<int> column(n_, -1);
    int free = 0;
    for (int i = 0; i < n_; ++i)
      if (std::isnan(fixed_[i])) column[i] = free++;
    std::vector<Eigen::Triplet<double>> entries;
    Eigen::VectorXd b = Eigen::VectorXd::Zero(4 * m_.n_faces());
    for (auto fh : m_.faces()) AddFaceRows(fh.idx(), column, &entries, &b);
    Eigen::SparseMatrix<double> at(free, 4 * m_.n_faces());
    at.setFromTriplets(entries.begin(), entries.end());
    at.makeCompressed();
    const CscMatrix a = ToCsc(at);
    std::string message;
    const Eigen::VectorXd rhs = at * b;
    Eigen::VectorXd y(free);
    PollStop(options_.fit.stop, "the integer-grid map");
    bool solved = solver_->Analyze(a, MatrixForm::kAAt, &message);
    PollStop(options_.fit.stop, "the integer-grid map");
    solved = solved && solver_->Factorize(a, 1e-9, &message) &&
             solver_->Solve(rhs.data(), y.data(), &message) && y.allFinite();
    if (!solved) throw InputError("the parametrisation system could not be solved: " + message);
    PollStop(options_.fit.stop, "the integer-grid map");
    for (int i = 0; i < n_; ++i) x_[i] = column[i] >= 0 ? y[column[i]] : fixed_[i];
  }

 private:
  // The four rows of face f (columns of Aᵀ in `entries`, right-hand sides in b).
  void AddFaceRows(int f, const std::vector<int>& column,
                   std::vector<Eigen::Triplet<double>>* entries, Eigen::VectorXd* b) const {
    std::vector<std::pair<int, double>> terms;
    const double w = std::sqrt(s_.basis[f].area);
    const Eigen::Matrix<double, 2, 3> g = s_.basis[f].Gradient();
    const Frame& fr = s_.frame[f];
    const Eigen::Vector2d along[2] = {Direction(fr.gamma - fr.theta),
                                      Direction(fr.gamma + fr.theta)};
    for (int c = 0; c < 2; ++c)
      for (int d = 0; d < 2; ++d) {
        // Row (c, c): ∇u_c along its own direction is 1 / h (the size, weighted σ); row
        // (c, 1 − c): ∇u_c along the other direction is 0 (the alignment).
        const int row = 4 * f + 2 * c + d;
        const double weight = w * (d == c ? options_.size_weight : 1.0);
        const Eigen::Vector3d probe = weight * (along[d].transpose() * g).transpose();
        double rhs = d == c ? weight / h_ : 0.0;
        for (int k = 0; k < 3; ++k) {
          CornerTerms(f, k, c, &terms);
          for (const auto& [var, coeff] : terms) {
            const double value = probe[k] * coeff;
            if (column[var] >= 0)
              entries->emplace_back(column[var], row, value);
            else
              rhs -= value * fixed_[var];
          }
        }
        (*b)[row] = rhs;
      }
  }

  const PolyMesh& m_;
  const Surface& s_;
  const Cuts& cuts_;
  const double h_;
  const QuadRemeshOptions& options_;
  const int n_;
  std::vector<double> fixed_;
  Eigen::VectorXd x_;
  std::unique_ptr<SparseCholesky> solver_;
};

// The integer point nearest to t, or with even_sum the nearest with an even coordinate sum: an
// asymptotic net's vertices are 2-coloured (its two families alternate, 004 §3), and a
// translation with an odd sum around a hole would join the colours in an odd cycle.
Eigen::Vector2d RoundTranslation(const Eigen::Vector2d& t, bool even_sum) {
  Eigen::Vector2d r(std::round(t.x()), std::round(t.y()));
  if (even_sum && std::fmod(std::abs(r.x() + r.y()), 2.0) == 1.0) {
    // Move the coordinate that was rounded furthest to its other neighbour.
    const Eigen::Vector2d error = t - r;
    const int j = std::abs(error.x()) >= std::abs(error.y()) ? 0 : 1;
    r[j] += error[j] >= 0.0 ? 1.0 : -1.0;
  }
  return r;
}

// The map at the corners, the quarter turns across the cuts, the frames in 3D.
void WriteMap(const PolyMesh& m, const Surface& s, const Cuts& cuts, const MapSystem& system,
              FieldParametrization* out) {
  out->map.corner_uv.resize(m.n_faces());
  out->map.halfedge_rotation.assign(m.n_halfedges(), 0);
  out->frame_a.resize(m.n_faces());
  out->frame_b.resize(m.n_faces());
  std::vector<std::pair<int, double>> terms;
  for (auto fh : m.faces()) {
    const int f = fh.idx();
    for (int k = 0; k < 3; ++k)
      for (int c = 0; c < 2; ++c) {
        system.CornerTerms(f, k, c, &terms);
        double value = 0.0;
        for (const auto& [var, coeff] : terms) value += coeff * system.x()[var];
        // Within rounding of an integer, exactly on it (an iso-line through a vertex, as on
        // grids aligned with the field): the transitions map integers to integers, so every
        // chart of the vertex agrees, and the extraction sees the exact case, not a near miss.
        if (std::abs(value - std::round(value)) < kSnapToInteger) value = std::round(value);
        out->map.corner_uv[f][k][c] = value;
      }
    if (MappedArea(out->map, f) <= 0.0) ++out->folded_faces;
    const FaceBasis& b = s.basis[f];
    const Frame& fr = s.frame[f];
    const Eigen::Vector2d a2 = Direction(fr.gamma - fr.theta), b2 = Direction(fr.gamma + fr.theta);
    out->frame_a[f] = a2.x() * b.e1 + a2.y() * b.e2;
    out->frame_b[f] = b2.x() * b.e1 + b2.y() * b.e2;
  }
  const auto& paths = cuts.paths;
  for (size_t p = 0; p < paths.size(); ++p)
    for (size_t i = 0; i + 1 < paths[p].size(); ++i) {
      const auto hh = HalfedgeBetween(m, paths[p][i], paths[p][i + 1]);
      out->map.halfedge_rotation[hh.idx()] = cuts.path_turns[p];
      out->map.halfedge_rotation[m.opposite_halfedge_handle(hh).idx()] =
          (4 - cuts.path_turns[p]) & 3;
    }
}

}  // namespace

FieldParametrization ParametrizeAlongField(const PolyMesh& triangles, const DirectionField& field,
                                           const QuadRemeshOptions& options) {
  FieldParametrization out;
  std::string why;
  if (!options.IsValid(&why)) throw InputError(why);
  if (triangles.n_faces() == 0) throw InputError("the mesh has no faces");
  if (field.curvature.size() != triangles.n_vertices())
    throw InputError("the direction field does not belong to the mesh");
  out.boundary_loops = CheckTriangulatedSurface(triangles);
  UnitFrame unit;
  const PolyMesh m = UnitScaleCopy(triangles, &unit);
  const double h = UnitEdgeLength(options, unit);
  Surface s = Frames(m, field, options);
  PollStop(options.fit.stop, "the integer-grid map");
  out.edge_length = h * unit.length;
  out.singularities = FrameSingularities(s);
  RefuseSingularitiesNoQuadCanFollow(out.singularities);
  out.handles = static_cast<int>((2 - out.boundary_loops - EulerCharacteristic(m)) / 2);
  Cuts cuts = CutAlongPaths(m, out.singularities, out.handles, options.fit.stop, &out.cut_edges);
  CombFrames(m, cuts, &s);
  FindPathTurns(m, s, &cuts);
  FindRightSides(m, s, &cuts);
  PollStop(options.fit.stop, "the integer-grid map");
  MapSystem system(m, s, cuts, h, options);
  system.Solve();
  // Every transition a grid automorphism: the singularities' map and the arcs' translations
  // rounded to integers, and the map solved again.
  if (!out.singularities.empty() || cuts.arcs > 0) {
    for (const FrameSingularity& sg : out.singularities)
      for (int j = 0; j < 2; ++j)
        system.Fix(2 * sg.vertex + j, std::round(system.x()[2 * sg.vertex + j]));
    for (int k = 0; k < cuts.arcs; ++k) {
      const int var[2] = {system.TranslationUnknown(k, 0), system.TranslationUnknown(k, 1)};
      const Eigen::Vector2d t = RoundTranslation({system.x()[var[0]], system.x()[var[1]]},
                                                 /*even_sum=*/s.step == 2);
      system.Fix(var[0], t.x());
      system.Fix(var[1], t.y());
    }
    system.Solve();
  }
  WriteMap(m, s, cuts, system, &out);
  return out;
}

std::vector<std::string> QuadRemeshResult::Problems() const {
  std::vector<std::string> out;
  auto add = [&out](int count, const char* what) {
    if (count > 0) out.push_back(std::to_string(count) + " " + what);
  };
  // Odd valences (singularities of index ±¼) are fine in a principal cross, not in an
  // asymptotic net, whose two families alternate around every vertex.
  if (field.kind == DirectionKind::kAsymptotic)
    add(odd_inner_vertices, "inner vertices of odd valence");
  if (components > 1)
    out.push_back("quads in " + std::to_string(components) +
                  " pieces (a smaller `edge_length` joins them)");
  add(pinched_vertices, "vertices where quads meet at a corner only (pinched)");
  if (euler_characteristic != surface_euler_characteristic)
    out.push_back("Euler characteristic " + std::to_string(euler_characteristic) +
                  " where the "
                  "surface's is " +
                  std::to_string(surface_euler_characteristic) +
                  " (a hole or a handle lost, or a hole merged with the boundary or another "
                  "hole: a smaller `edge_length`)");
  if (field.kind == DirectionKind::kAsymptotic && !odd_cycle.empty())
    out.push_back("quad vertices that cannot be 2-coloured (" + odd_cycle + ")");
  add(inner_valence_count.size() > 2 ? inner_valence_count[2] : 0,
      "inner vertices of valence 2 (two quads folded onto each other)");
  add(nonconvex_quads, "non-convex quads");
  add(parametrization.folded_faces, "triangles folded by the map");
  if (field.kind == DirectionKind::kAsymptotic && field.negative_area_fraction < 0.99) {
    char text[160];
    std::snprintf(text, sizeof(text),
                  "K >= 0 on %.1f%% of the area (no asymptotic directions there)",
                  100.0 * (1.0 - field.negative_area_fraction));
    out.push_back(text);
  }
  return out;
}

namespace {

// The quads' pieces, pinched vertices and Euler characteristic (QuadRemeshResult).
void MeasureTopology(const PolyMesh& q, QuadRemeshResult* out) {
  std::vector<int> boundary_out(q.n_vertices(), 0);
  for (auto h : q.halfedges())
    if (q.is_boundary(h)) ++boundary_out[q.from_vertex_handle(h).idx()];
  for (auto v : q.vertices()) out->pinched_vertices += boundary_out[v.idx()] > 1;
  out->euler_characteristic = EulerCharacteristic(q);
  out->components = FaceComponents(q);
}

}  // namespace

double EdgeAgainstFrameDeg(const Eigen::Vector3d& d, const Eigen::Vector3d& a,
                           const Eigen::Vector3d& b) {
  const Eigen::Vector3d n = a.cross(b).normalized();
  const Eigen::Vector3d in_plane = d - d.dot(n) * n;
  const Eigen::Vector3d e = in_plane.norm() > 1e-9 * d.norm() ? in_plane : d;
  return std::min(LineAngleDeg(e, a), LineAngleDeg(e, b));
}

QuadRemeshResult RemeshAlongField(const PolyMesh& triangles, const QuadRemeshOptions& options) {
  std::string why;
  if (!options.IsValid(&why)) throw InputError(why);
  QuadRemeshResult out;
  auto clock = std::chrono::steady_clock::now();
  auto lap = [&clock]() {
    const auto now = std::chrono::steady_clock::now();
    const double seconds = std::chrono::duration<double>(now - clock).count();
    clock = now;
    return seconds;
  };
  CheckTriangulatedSurface(triangles);
  out.surface_euler_characteristic = EulerCharacteristic(triangles);
  out.field = EstimateDirectionField(triangles, options.directions, options.fit, options.smoothing);
  out.seconds_field = lap();
  PollStop(options.fit.stop, "the integer-grid map");
  out.parametrization = ParametrizeAlongField(triangles, out.field, options);
  out.seconds_map = lap();
  PollStop(options.fit.stop, "the quads' extraction");
  UnitFrame unit;
  const PolyMesh scaled = UnitScaleCopy(triangles, &unit);
  out.extraction = ExtractQuads(scaled, out.parametrization.map);
  out.seconds_extraction = lap();
  PolyMesh& q = out.extraction.quads;
  if (q.n_faces() == 0)
    throw InputError("no quad could be extracted: the edge length (" +
                     std::to_string(out.parametrization.edge_length) +
                     ") is too large for the surface, or the map folds everywhere");
  // Measures at unit scale, then the quads back to the input's units.
  double quad_area = 0.0, triangle_area = 0.0;
  for (auto f : q.faces()) {
    std::vector<Eigen::Vector3d> p;
    for (auto v : q.fv_range(f)) p.emplace_back(q.point(v)[0], q.point(v)[1], q.point(v)[2]);
    quad_area += 0.5 * (p[2] - p[0]).cross(p[3] - p[1]).norm();
  }
  for (auto f : scaled.faces()) {
    std::vector<Eigen::Vector3d> p;
    for (auto v : scaled.fv_range(f))
      p.emplace_back(scaled.point(v)[0], scaled.point(v)[1], scaled.point(v)[2]);
    triangle_area += 0.5 * (p[1] - p[0]).cross(p[2] - p[0]).norm();
  }
  out.area_covered = quad_area / triangle_area;
  for (auto v : q.vertices()) {
    if (q.is_boundary(v)) continue;
    const int valence = static_cast<int>(q.valence(v));
    if (static_cast<int>(out.inner_valence_count.size()) <= valence)
      out.inner_valence_count.resize(valence + 1, 0);
    ++out.inner_valence_count[valence];
    if (valence % 2) ++out.odd_inner_vertices;
  }
  MeasureTopology(q, &out);
  try {
    nets::TwoColourVertices(q);
  } catch (const InputError& e) {
    const std::string what = e.what();  // "... (edge a-b closes an odd cycle) ..."
    const size_t open = what.find('('), close = what.find(')');
    out.odd_cycle =
        open < close && close != std::string::npos ? what.substr(open + 1, close - open - 1) : what;
  }
  out.min_corner_angle_deg = 180.0;
  for (auto f : q.faces()) {
    std::vector<Eigen::Vector3d> p;
    for (auto v : q.fv_range(f)) p.emplace_back(q.point(v)[0], q.point(v)[1], q.point(v)[2]);
    const Eigen::Vector3d n = (p[2] - p[0]).cross(p[3] - p[1]);
    bool convex = true;
    for (int k = 0; k < 4; ++k) {
      const Eigen::Vector3d a = p[(k + 3) % 4] - p[k], b = p[(k + 1) % 4] - p[k];
      out.min_corner_angle_deg = std::min(out.min_corner_angle_deg,
                                          std::atan2(a.cross(b).norm(), a.dot(b)) * 180.0 / M_PI);
      if (!(b.cross(a).dot(n) > 0.0)) convex = false;
    }
    if (!convex) ++out.nonconvex_quads;
  }
  double sum = 0.0;
  for (const QuadExtraction::Edge& e : out.extraction.edges) {
    const auto& a = q.point(q.vertex_handle(e.from));
    const auto& b = q.point(q.vertex_handle(e.to));
    const Eigen::Vector3d d(b[0] - a[0], b[1] - a[1], b[2] - a[2]);
    const double angle = EdgeAgainstFrameDeg(d, out.parametrization.frame_a[e.triangle],
                                             out.parametrization.frame_b[e.triangle]);
    sum += angle;
    out.max_alignment_deg = std::max(out.max_alignment_deg, angle);
  }
  if (!out.extraction.edges.empty()) out.mean_alignment_deg = sum / out.extraction.edges.size();
  FromUnitScale(unit, &q);
  return out;
}

}  // namespace gproj::remesh
