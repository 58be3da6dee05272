#include "gproj/geometry/mesh/quad_extraction.h"

#include <Eigen/Geometry>
#include <algorithm>
#include <cmath>
#include <limits>
#include <map>
#include <string>
#include <tuple>

namespace gproj {
namespace {

// Barycentric coordinates below this count as 0: the point lies on the edge or vertex.
constexpr double kOnBorder = 1e-9;

double Cross(const Eigen::Vector2d& a, const Eigen::Vector2d& b) {
  return a.x() * b.y() - a.y() * b.x();
}

struct Face {
  std::array<int, 3> vertex;
  std::array<PolyMesh::HalfedgeHandle, 3> halfedge;  // halfedge[i]: corner i → corner i + 1
  std::array<Eigen::Vector3d, 3> point;
  std::array<Eigen::Vector2d, 3> uv;
  Eigen::Vector3d normal;
  double area = 0.0;  // signed, of the image
  Eigen::Vector3d Barycentric(const Eigen::Vector2d& x) const {
    const double l0 = Cross(uv[1] - x, uv[2] - x) / (2.0 * area);
    const double l1 = Cross(uv[2] - x, uv[0] - x) / (2.0 * area);
    return Eigen::Vector3d(l0, l1, 1.0 - l0 - l1);
  }
  Eigen::Vector3d At(const Eigen::Vector2d& x) const {
    const Eigen::Vector3d l = Barycentric(x);
    return l[0] * point[0] + l[1] * point[1] + l[2] * point[2];
  }
};

// Where an integer point lies: a mesh vertex, a point of a mesh edge, or inside a face.
using PointKey = std::tuple<int, int, long long, long long>;

struct HalfEdge {
  int from, to, triangle;
  Eigen::Vector3d out, back;  // unit 3D directions: leaving `from`, and from `to` back
};

// A face and the line's start and direction in its chart.
struct Chart {
  int face;
  Eigen::Vector2d p, d;
};

// From face `from`, the faces around mesh vertex `vertex` (breadth first across the edges at
// it, carrying the chart by the transitions) until one holds `beyond` (given in `from`'s
// chart); *found gets it, with the line carried into its chart. False when none does.
template <typename Transition>
bool AcrossVertex(const PolyMesh& mesh, const std::vector<Face>& faces,
                  const Transition& transition, int from, int vertex, const Eigen::Vector2d& beyond,
                  Chart* found) {
  struct State {
    int face;
    Eigen::Vector2d p, d, beyond;
  };
  std::vector<State> states = {{from, found->p, found->d, beyond}};
  std::vector<int> seen = {from};
  for (size_t i = 0; i < states.size() && i < 256; ++i) {
    const State s = states[i];
    if (s.face != from && faces[s.face].area > 0.0 &&
        faces[s.face].Barycentric(s.beyond).minCoeff() >= -1e-12) {
      *found = {s.face, s.p, s.d};
      return true;
    }
    for (const auto h : faces[s.face].halfedge) {
      if (mesh.from_vertex_handle(h).idx() != vertex && mesh.to_vertex_handle(h).idx() != vertex)
        continue;
      if (mesh.is_boundary(mesh.opposite_halfedge_handle(h))) continue;
      const int g = mesh.opposite_face_handle(h).idx();
      if (std::find(seen.begin(), seen.end(), g) != seen.end()) continue;
      seen.push_back(g);
      Eigen::Matrix2d r;
      Eigen::Vector2d t;
      transition(h, &r, &t);
      states.push_back({g, r * s.p + t, r * s.d, r * s.beyond + t});
    }
  }
  return false;
}

}  // namespace

Eigen::Matrix2d QuarterTurns(int k) {
  static const int c[4] = {1, 0, -1, 0}, s[4] = {0, 1, 0, -1};
  Eigen::Matrix2d r;
  r << c[k & 3], -s[k & 3], s[k & 3], c[k & 3];
  return r;
}

double MappedArea(const IntegerGridMap& map, int face) {
  const auto& u = map.corner_uv[face];
  return 0.5 * Cross(u[1] - u[0], u[2] - u[0]);
}

QuadExtraction ExtractQuads(const PolyMesh& mesh, const IntegerGridMap& map) {
  if (map.corner_uv.size() != mesh.n_faces() || map.halfedge_rotation.size() != mesh.n_halfedges())
    throw InputError("the integer-grid map does not match the triangle mesh");
  QuadExtraction out;
  std::vector<Face> faces(mesh.n_faces());
  for (auto f : mesh.faces()) {
    if (mesh.valence(f) != 3)
      throw InputError("face " + std::to_string(f.idx()) + " is not a triangle");
    Face& face = faces[f.idx()];
    int i = 0;
    for (auto fv = mesh.cfv_iter(f); fv.is_valid(); ++fv, ++i) {
      face.vertex[i] = fv->idx();
      const auto& p = mesh.point(*fv);
      face.point[i] = Eigen::Vector3d(p[0], p[1], p[2]);
      face.uv[i] = map.corner_uv[f.idx()][i];
    }
    for (auto h : mesh.fh_range(f))
      for (int k = 0; k < 3; ++k)
        if (mesh.from_vertex_handle(h).idx() == face.vertex[k]) face.halfedge[k] = h;
    face.normal = (face.point[1] - face.point[0]).cross(face.point[2] - face.point[0]).normalized();
    face.area = MappedArea(map, f.idx());
    if (!(face.area > 0.0)) ++out.folded_triangles;
  }
  // The map of halfedge h's face, carried into its opposite face: R x + t.
  auto transition = [&](PolyMesh::HalfedgeHandle h, Eigen::Matrix2d* r, Eigen::Vector2d* t) {
    const Face& f = faces[mesh.face_handle(h).idx()];
    const Face& g = faces[mesh.opposite_face_handle(h).idx()];
    const int p = mesh.from_vertex_handle(h).idx();
    *r = QuarterTurns(map.halfedge_rotation[h.idx()]);
    Eigen::Vector2d uf, ug;
    for (int k = 0; k < 3; ++k) {
      if (f.vertex[k] == p) uf = f.uv[k];
      if (g.vertex[k] == p) ug = g.uv[k];
    }
    *t = ug - *r * uf;
  };
  auto key_of = [&](int f, const Eigen::Vector2d& x) -> PointKey {
    const Face& face = faces[f];
    const Eigen::Vector3d l = face.Barycentric(x);
    int zeros = 0;
    for (int k = 0; k < 3; ++k)
      if (std::abs(l[k]) < kOnBorder) ++zeros;
    if (zeros >= 2) {
      for (int k = 0; k < 3; ++k)
        if (std::abs(l[k]) >= kOnBorder) return {0, face.vertex[k], 0, 0};
    }
    if (zeros == 1) {
      for (int k = 0; k < 3; ++k)
        if (std::abs(l[k]) < kOnBorder) {
          const int a = (k + 1) % 3, b = (k + 2) % 3;
          const int lo = face.vertex[a] < face.vertex[b] ? a : b;
          const auto e = mesh.edge_handle(face.halfedge[a]);
          return {1, e.idx(), std::llround(l[lo] * 1e7), 0};
        }
    }
    return {2, f, std::llround(x.x()), std::llround(x.y())};
  };
  // Grid points and their occurrences (the faces whose image holds them).
  std::map<PointKey, int> point_of;
  std::vector<Eigen::Vector3d> position, normal;
  struct Occurrence {
    int point, face;
    Eigen::Vector2d uv;
    bool on_border;  // on an edge or vertex of the face (found in its neighbours too)
  };
  std::vector<Occurrence> occurrences;
  for (size_t f = 0; f < faces.size(); ++f) {
    const Face& face = faces[f];
    if (!(face.area > 0.0)) continue;
    Eigen::Vector2d lo = face.uv[0], hi = face.uv[0];
    for (int k = 1; k < 3; ++k) lo = lo.cwiseMin(face.uv[k]), hi = hi.cwiseMax(face.uv[k]);
    for (double i = std::ceil(lo.x() - 1e-9); i <= hi.x() + 1e-9; ++i)
      for (double j = std::ceil(lo.y() - 1e-9); j <= hi.y() + 1e-9; ++j) {
        const Eigen::Vector2d x(i, j);
        if (face.Barycentric(x).minCoeff() < -kOnBorder) continue;
        const PointKey key = key_of(static_cast<int>(f), x);
        auto [it, added] = point_of.emplace(key, static_cast<int>(position.size()));
        if (added) {
          position.push_back(face.At(x));
          normal.push_back(face.normal);
        }
        occurrences.push_back({it->second, static_cast<int>(f), x, std::get<0>(key) != 2});
      }
  }
  out.grid_points = static_cast<int>(position.size());
  // Trace every iso-line segment from each occurrence into its face.
  std::vector<HalfEdge> traced;
  const Eigen::Vector2d axes[4] = {{1, 0}, {0, 1}, {-1, 0}, {0, -1}};
  for (const Occurrence& o : occurrences)
    for (const Eigen::Vector2d& axis : axes) {
      // A point inside the face starts all four lines there (one that leaves at once, near an
      // edge, crosses it); a point on an edge or vertex starts each line from the face it
      // enters.
      if (o.on_border && faces[o.face].Barycentric(o.uv + 1e-6 * axis).minCoeff() < -1e-12)
        continue;
      int f = o.face, entered = -1;
      Eigen::Vector2d p = o.uv, d = axis;
      bool ended = false;
      for (int step = 0; step < 1000000 && !ended; ++step) {
        const Face& face = faces[f];
        const Eigen::Vector2d q = p + d;
        const Eigen::Vector3d lq = face.Barycentric(q);
        if (lq.minCoeff() >= -kOnBorder) {
          ended = true;
          if (!(face.area > 0.0)) break;
          const auto it = point_of.find(key_of(f, q));
          if (it == point_of.end() || it->second == o.point) break;
          HalfEdge h;
          h.from = o.point;
          h.to = it->second;
          h.triangle = o.face;
          h.out = (faces[o.face].At(o.uv + 1e-3 * axis) - position[o.point]).normalized();
          h.back = (face.At(q - 1e-3 * d) - position[h.to]).normalized();
          traced.push_back(h);
          ended = true;
          continue;
        }
        // Leave through the edge the segment crosses first (not the one it came in by).
        const Eigen::Vector3d lp = face.Barycentric(p);
        int exit = -1;
        double first = std::numeric_limits<double>::infinity();
        for (int k = 0; k < 3; ++k) {
          const int edge = (k + 1) % 3;  // the edge opposite corner k runs from k + 1 to k + 2
          if (edge == entered || !(lq[k] < lp[k]) || !(lq[k] < -kOnBorder)) continue;
          const double s = lp[k] / (lp[k] - lq[k]);
          if (s < first) first = s, exit = edge;
        }
        if (exit < 0) break;
        // Through a corner of the face (an iso-line along a mesh edge, or through a vertex):
        // continue in the face around that vertex that holds the line just beyond it.
        const Eigen::Vector3d at = face.Barycentric(p + first * (q - p));
        int corner = -1;
        for (int k = 0; k < 3; ++k)
          if (at[k] > 1.0 - kOnBorder) corner = k;
        if (corner >= 0) {
          const Eigen::Vector2d beyond = p + first * (q - p) + 1e-7 * d;
          Chart next{-1, p, d};
          if (!AcrossVertex(mesh, faces, transition, f, face.vertex[corner], beyond, &next)) break;
          f = next.face;
          p = next.p;
          d = next.d;
          entered = -1;
          continue;
        }
        const auto h = face.halfedge[exit];
        if (mesh.is_boundary(mesh.opposite_halfedge_handle(h))) break;
        Eigen::Matrix2d r;
        Eigen::Vector2d t;
        transition(h, &r, &t);
        p = r * p + t;
        d = r * d;
        f = mesh.opposite_face_handle(h).idx();
        const auto back = mesh.opposite_halfedge_handle(h);
        for (int k = 0; k < 3; ++k)
          if (faces[f].halfedge[k] == back) entered = k;
      }
      if (!ended) ++out.open_edges;
    }
  // Per point its outgoing halfedges (one per direction) in counter-clockwise order.
  std::vector<std::vector<int>> outgoing(position.size());
  std::vector<HalfEdge> edges;
  for (const HalfEdge& h : traced) {
    bool repeated = false;
    for (int g : outgoing[h.from])
      if (edges[g].to == h.to && edges[g].out.dot(h.out) > 0.99) repeated = true;
    if (repeated) continue;
    outgoing[h.from].push_back(static_cast<int>(edges.size()));
    edges.push_back(h);
  }
  std::vector<int> twin(edges.size(), -1);
  for (size_t h = 0; h < edges.size(); ++h) {
    double best = 0.9;
    for (int g : outgoing[edges[h].to])
      if (edges[g].to == edges[h].from && edges[g].out.dot(edges[h].back) > best)
        best = edges[g].out.dot(edges[h].back), twin[h] = g;
  }
  for (size_t h = 0; h < edges.size(); ++h)
    if (twin[h] < 0 || twin[twin[h]] != static_cast<int>(h)) ++out.open_edges, twin[h] = -1;
  std::vector<double> angle(edges.size(), 0.0);
  for (size_t v = 0; v < position.size(); ++v) {
    auto& list = outgoing[v];
    list.erase(std::remove_if(list.begin(), list.end(), [&](int h) { return twin[h] < 0; }),
               list.end());
    const Eigen::Vector3d t1 = normal[v].unitOrthogonal(), t2 = normal[v].cross(t1);
    for (int h : list) angle[h] = std::atan2(edges[h].out.dot(t2), edges[h].out.dot(t1));
    std::sort(list.begin(), list.end(), [&](int a, int b) { return angle[a] < angle[b]; });
  }
  // The face on the left of h continues at its end with the outgoing halfedge just before
  // twin(h) counter-clockwise.
  auto next = [&](int h) {
    const auto& list = outgoing[edges[h].to];
    const auto it = std::find(list.begin(), list.end(), twin[h]);
    return it == list.begin() ? list.back() : *(it - 1);
  };
  std::vector<char> visited(edges.size(), 0);
  std::vector<std::vector<int>> cycles;  // the quads, as their first halfedges
  PolyMesh trial;  // every point, to find the quads that fit together as a manifold
  for (const Eigen::Vector3d& p : position) trial.add_vertex(PolyMesh::Point(p.x(), p.y(), p.z()));
  for (size_t start = 0; start < edges.size(); ++start) {
    if (twin[start] < 0 || visited[start]) continue;
    std::vector<int> cycle;
    int h = static_cast<int>(start);
    while (!visited[h]) {
      visited[h] = 1;
      cycle.push_back(h);
      h = next(h);
    }
    bool quad = cycle.size() == 4 && h == static_cast<int>(start);
    std::vector<int> corner;
    for (int g : cycle) corner.push_back(edges[g].from);
    if (quad) {
      std::vector<int> sorted = corner;
      std::sort(sorted.begin(), sorted.end());
      quad = std::unique(sorted.begin(), sorted.end()) == sorted.end();
    }
    if (quad) {
      const Eigen::Vector3d n = (position[corner[2]] - position[corner[0]])
                                    .cross(position[corner[3]] - position[corner[1]]);
      quad = n.dot(normal[corner[0]]) > 0.0;
    }
    if (quad) {
      std::vector<PolyMesh::VertexHandle> handles;
      for (int c : corner) handles.push_back(trial.vertex_handle(c));
      quad = trial.add_face(handles).is_valid();
    }
    if (quad)
      cycles.push_back(cycle);
    else
      ++out.dropped_cycles;
  }
  std::vector<int> used(position.size(), -1);
  std::vector<char> in_quad(edges.size(), 0);
  for (const std::vector<int>& cycle : cycles) {
    std::vector<PolyMesh::VertexHandle> handles;
    for (int h : cycle) {
      const int c = edges[h].from;
      in_quad[h] = in_quad[twin[h]] = 1;
      if (used[c] < 0) {
        used[c] = static_cast<int>(out.quads.n_vertices());
        out.quads.add_vertex(PolyMesh::Point(position[c].x(), position[c].y(), position[c].z()));
      }
      handles.push_back(out.quads.vertex_handle(used[c]));
    }
    out.quads.add_face(handles);
  }
  for (size_t h = 0; h < edges.size(); ++h)
    if (in_quad[h] && edges[h].from < edges[h].to)
      out.edges.push_back({used[edges[h].from], used[edges[h].to], edges[h].triangle});
  return out;
}

}  // namespace gproj
