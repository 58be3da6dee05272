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

namespace {

// A grid point found in a face whose image holds it.
struct Occurrence {
  int point, face;
  Eigen::Vector2d uv;
  bool on_border;  // on an edge or vertex of the face (found in its neighbours too)
};

// The steps of ExtractQuads, sharing the faces with their images and the grid points found.
class Extractor {
 public:
  Extractor(const PolyMesh& mesh, const IntegerGridMap& map, QuadExtraction* out)
      : mesh_(mesh), map_(map), out_(out), faces_(mesh.n_faces()) {
    for (auto f : mesh.faces()) AddFace(f);
  }

  // The map of halfedge h's face, carried into its opposite face: R x + t.
  void Transition(PolyMesh::HalfedgeHandle h, Eigen::Matrix2d* r, Eigen::Vector2d* t) const {
    const Face& f = faces_[mesh_.face_handle(h).idx()];
    const Face& g = faces_[mesh_.opposite_face_handle(h).idx()];
    const int p = mesh_.from_vertex_handle(h).idx();
    *r = QuarterTurns(map_.halfedge_rotation[h.idx()]);
    Eigen::Vector2d uf, ug;
    for (int k = 0; k < 3; ++k) {
      if (f.vertex[k] == p) uf = f.uv[k];
      if (g.vertex[k] == p) ug = g.uv[k];
    }
    *t = ug - *r * uf;
  }

  // Grid points and their occurrences (the faces whose image holds them).
  void FindGridPoints() {
    for (size_t f = 0; f < faces_.size(); ++f) {
      const Face& face = faces_[f];
      if (!(face.area > 0.0)) continue;
      Eigen::Vector2d lo = face.uv[0], hi = face.uv[0];
      for (int k = 1; k < 3; ++k) lo = lo.cwiseMin(face.uv[k]), hi = hi.cwiseMax(face.uv[k]);
      for (double i = std::ceil(lo.x() - 1e-9); i <= hi.x() + 1e-9; ++i)
        for (double j = std::ceil(lo.y() - 1e-9); j <= hi.y() + 1e-9; ++j) {
          const Eigen::Vector2d x(i, j);
          if (face.Barycentric(x).minCoeff() < -kOnBorder) continue;
          const PointKey key = KeyOf(static_cast<int>(f), x);
          auto [it, added] = point_of_.emplace(key, static_cast<int>(position_.size()));
          if (added) {
            position_.push_back(face.At(x));
            normal_.push_back(face.normal);
          }
          occurrences_.push_back({it->second, static_cast<int>(f), x, std::get<0>(key) != 2});
        }
    }
    out_->grid_points = static_cast<int>(position_.size());
  }

  // Traces every iso-line segment from each occurrence into its face.
  void TraceLines() {
    const Eigen::Vector2d axes[4] = {{1, 0}, {0, 1}, {-1, 0}, {0, -1}};
    for (const Occurrence& o : occurrences_)
      for (const Eigen::Vector2d& axis : axes) {
        // A point inside the face starts all four lines there (one that leaves at once, near
        // an edge, crosses it); a point on an edge or vertex starts each line from the face it
        // enters.
        if (o.on_border && faces_[o.face].Barycentric(o.uv + 1e-6 * axis).minCoeff() < -1e-12)
          continue;
        if (!TraceLine(o, axis)) ++out_->open_edges;
      }
  }

  // Keeps one traced halfedge per point and direction, pairs each with its twin, and sorts the
  // halfedges leaving each point counter-clockwise.
  void ConnectHalfedges() {
    outgoing_.assign(position_.size(), {});
    for (const HalfEdge& h : traced_) {
      bool repeated = false;
      for (int g : outgoing_[h.from])
        if (edges_[g].to == h.to && edges_[g].out.dot(h.out) > 0.99) repeated = true;
      if (repeated) continue;
      outgoing_[h.from].push_back(static_cast<int>(edges_.size()));
      edges_.push_back(h);
    }
    twin_.assign(edges_.size(), -1);
    for (size_t h = 0; h < edges_.size(); ++h) {
      double best = 0.9;
      for (int g : outgoing_[edges_[h].to])
        if (edges_[g].to == edges_[h].from && edges_[g].out.dot(edges_[h].back) > best)
          best = edges_[g].out.dot(edges_[h].back), twin_[h] = g;
    }
    for (size_t h = 0; h < edges_.size(); ++h)
      if (twin_[h] < 0 || twin_[twin_[h]] != static_cast<int>(h)) ++out_->open_edges, twin_[h] = -1;
    std::vector<double> angle(edges_.size(), 0.0);
    for (size_t v = 0; v < position_.size(); ++v) {
      auto& list = outgoing_[v];
      list.erase(std::remove_if(list.begin(), list.end(), [&](int h) { return twin_[h] < 0; }),
                 list.end());
      const Eigen::Vector3d t1 = normal_[v].unitOrthogonal(), t2 = normal_[v].cross(t1);
      for (int h : list) angle[h] = std::atan2(edges_[h].out.dot(t2), edges_[h].out.dot(t1));
      std::sort(list.begin(), list.end(), [&](int a, int b) { return angle[a] < angle[b]; });
    }
  }

  // The cycles of halfedges that are quads fitting together as a manifold, as their first
  // halfedges; the other cycles are counted as dropped.
  std::vector<std::vector<int>> FindQuads() {
    std::vector<char> visited(edges_.size(), 0);
    std::vector<std::vector<int>> cycles;
    PolyMesh trial;  // every point, to find the quads that fit together as a manifold
    for (const Eigen::Vector3d& p : position_)
      trial.add_vertex(PolyMesh::Point(p.x(), p.y(), p.z()));
    for (size_t start = 0; start < edges_.size(); ++start) {
      if (twin_[start] < 0 || visited[start]) continue;
      std::vector<int> cycle;
      int h = static_cast<int>(start);
      while (!visited[h]) {
        visited[h] = 1;
        cycle.push_back(h);
        h = Next(h);
      }
      if (cycle.size() == 4 && h == static_cast<int>(start) && IsQuad(cycle, &trial))
        cycles.push_back(cycle);
      else
        ++out_->dropped_cycles;
    }
    return cycles;
  }

  // The quad mesh of `cycles` and its edges.
  void BuildQuadMesh(const std::vector<std::vector<int>>& cycles) {
    std::vector<int> used(position_.size(), -1);
    std::vector<char> in_quad(edges_.size(), 0);
    for (const std::vector<int>& cycle : cycles) {
      std::vector<PolyMesh::VertexHandle> handles;
      for (int h : cycle) {
        const int c = edges_[h].from;
        in_quad[h] = in_quad[twin_[h]] = 1;
        if (used[c] < 0) {
          used[c] = static_cast<int>(out_->quads.n_vertices());
          out_->quads.add_vertex(
              PolyMesh::Point(position_[c].x(), position_[c].y(), position_[c].z()));
        }
        handles.push_back(out_->quads.vertex_handle(used[c]));
      }
      out_->quads.add_face(handles);
    }
    for (size_t h = 0; h < edges_.size(); ++h)
      if (in_quad[h] && edges_[h].from < edges_[h].to)
        out_->edges.push_back({used[edges_[h].from], used[edges_[h].to], edges_[h].triangle});
  }

 private:
  void AddFace(PolyMesh::FaceHandle f) {
    if (mesh_.valence(f) != 3)
      throw InputError("face " + std::to_string(f.idx()) + " is not a triangle");
    Face& face = faces_[f.idx()];
    int i = 0;
    for (auto fv = mesh_.cfv_iter(f); fv.is_valid(); ++fv, ++i) {
      face.vertex[i] = fv->idx();
      const auto& p = mesh_.point(*fv);
      face.point[i] = Eigen::Vector3d(p[0], p[1], p[2]);
      face.uv[i] = map_.corner_uv[f.idx()][i];
    }
    for (auto h : mesh_.fh_range(f))
      for (int k = 0; k < 3; ++k)
        if (mesh_.from_vertex_handle(h).idx() == face.vertex[k]) face.halfedge[k] = h;
    face.normal = (face.point[1] - face.point[0]).cross(face.point[2] - face.point[0]).normalized();
    face.area = MappedArea(map_, f.idx());
    if (!(face.area > 0.0)) ++out_->folded_triangles;
  }

  PointKey KeyOf(int f, const Eigen::Vector2d& x) const {
    const Face& face = faces_[f];
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
          const auto e = mesh_.edge_handle(face.halfedge[a]);
          return {1, e.idx(), std::llround(l[lo] * 1e7), 0};
        }
    }
    return {2, f, std::llround(x.x()), std::llround(x.y())};
  }

  // Follows the iso-line from occurrence `o` along `axis` across faces to the next grid point
  // and records the halfedge; false when the line ends elsewhere (a boundary, a loop).
  bool TraceLine(const Occurrence& o, const Eigen::Vector2d& axis) {
    const auto transition = [this](PolyMesh::HalfedgeHandle h, Eigen::Matrix2d* r,
                                   Eigen::Vector2d* t) { Transition(h, r, t); };
    int f = o.face, entered = -1;
    Eigen::Vector2d p = o.uv, d = axis;
    for (int step = 0; step < 1000000; ++step) {
      const Face& face = faces_[f];
      const Eigen::Vector2d q = p + d;
      const Eigen::Vector3d lq = face.Barycentric(q);
      if (lq.minCoeff() >= -kOnBorder) {
        if (!(face.area > 0.0)) return true;
        const auto it = point_of_.find(KeyOf(f, q));
        if (it == point_of_.end() || it->second == o.point) return true;
        HalfEdge h;
        h.from = o.point;
        h.to = it->second;
        h.triangle = o.face;
        h.out = (faces_[o.face].At(o.uv + 1e-3 * axis) - position_[o.point]).normalized();
        h.back = (face.At(q - 1e-3 * d) - position_[h.to]).normalized();
        traced_.push_back(h);
        return true;
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
      if (exit < 0) return false;
      // Through a corner of the face (an iso-line along a mesh edge, or through a vertex):
      // continue in the face around that vertex that holds the line just beyond it.
      const Eigen::Vector3d at = face.Barycentric(p + first * (q - p));
      int corner = -1;
      for (int k = 0; k < 3; ++k)
        if (at[k] > 1.0 - kOnBorder) corner = k;
      if (corner >= 0) {
        const Eigen::Vector2d beyond = p + first * (q - p) + 1e-7 * d;
        Chart next{-1, p, d};
        if (!AcrossVertex(mesh_, faces_, transition, f, face.vertex[corner], beyond, &next))
          return false;
        f = next.face;
        p = next.p;
        d = next.d;
        entered = -1;
        continue;
      }
      const auto h = face.halfedge[exit];
      if (mesh_.is_boundary(mesh_.opposite_halfedge_handle(h))) return false;
      Eigen::Matrix2d r;
      Eigen::Vector2d t;
      Transition(h, &r, &t);
      p = r * p + t;
      d = r * d;
      f = mesh_.opposite_face_handle(h).idx();
      const auto back = mesh_.opposite_halfedge_handle(h);
      for (int k = 0; k < 3; ++k)
        if (faces_[f].halfedge[k] == back) entered = k;
    }
    return false;
  }

  // The face on the left of h continues at its end with the outgoing halfedge just before
  // twin(h) counter-clockwise.
  int Next(int h) const {
    const auto& list = outgoing_[edges_[h].to];
    const auto it = std::find(list.begin(), list.end(), twin_[h]);
    return it == list.begin() ? list.back() : *(it - 1);
  }

  // Whether a closed cycle of four halfedges is a quad: four distinct corners, facing the
  // surface's side, and a face `trial` (the quads so far) can take.
  bool IsQuad(const std::vector<int>& cycle, PolyMesh* trial) const {
    std::vector<int> corner;
    for (int g : cycle) corner.push_back(edges_[g].from);
    std::vector<int> sorted = corner;
    std::sort(sorted.begin(), sorted.end());
    if (std::unique(sorted.begin(), sorted.end()) != sorted.end()) return false;
    const Eigen::Vector3d n = (position_[corner[2]] - position_[corner[0]])
                                  .cross(position_[corner[3]] - position_[corner[1]]);
    if (!(n.dot(normal_[corner[0]]) > 0.0)) return false;
    std::vector<PolyMesh::VertexHandle> handles;
    for (int c : corner) handles.push_back(trial->vertex_handle(c));
    return trial->add_face(handles).is_valid();
  }

  const PolyMesh& mesh_;
  const IntegerGridMap& map_;
  QuadExtraction* out_;
  std::vector<Face> faces_;
  std::map<PointKey, int> point_of_;
  std::vector<Eigen::Vector3d> position_, normal_;
  std::vector<Occurrence> occurrences_;
  std::vector<HalfEdge> traced_;            // as traced, with repeats
  std::vector<HalfEdge> edges_;             // one per point and direction
  std::vector<std::vector<int>> outgoing_;  // per point its halfedges, counter-clockwise
  std::vector<int> twin_;
};

}  // namespace

QuadExtraction ExtractQuads(const PolyMesh& mesh, const IntegerGridMap& map) {
  if (map.corner_uv.size() != mesh.n_faces() || map.halfedge_rotation.size() != mesh.n_halfedges())
    throw InputError("the integer-grid map does not match the triangle mesh");
  QuadExtraction out;
  Extractor extractor(mesh, map, &out);
  extractor.FindGridPoints();
  extractor.TraceLines();
  extractor.ConnectHalfedges();
  extractor.BuildQuadMesh(extractor.FindQuads());
  return out;
}

}  // namespace gproj
