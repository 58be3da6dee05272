#include "gproj/problems/marionette/marionette_mesh.h"

#include <Eigen/Geometry>
#include <algorithm>
#include <array>
#include <cmath>
#include <map>

#include "gproj/constraints/line_quad_planarity.h"
#include "gproj/constraints/marionette_planarity.h"
#include "gproj/constraints/quad_planarity.h"
#include "gproj/constraints/scalar_target.h"

namespace gproj::marionette {
namespace {

using HalfedgeHandle = PolyMesh::HalfedgeHandle;
using VertexHandle = PolyMesh::VertexHandle;

// The four halfedges of face f, from its first one; vertex j is from_vertex(h[j]) and edge j
// joins vertices j and j + 1.
std::array<HalfedgeHandle, 4> FaceHalfedges(const PolyMesh& mesh, int f) {
  std::array<HalfedgeHandle, 4> h;
  h[0] = mesh.halfedge_handle(PolyMesh::FaceHandle(f));
  for (int j = 1; j < 4; ++j) h[j] = mesh.next_halfedge_handle(h[j - 1]);
  return h;
}

std::array<int, 4> FaceVertices(const PolyMesh& mesh, int f) {
  std::array<int, 4> v;
  const auto h = FaceHalfedges(mesh, f);
  for (int j = 0; j < 4; ++j) v[j] = mesh.from_vertex_handle(h[j]).idx();
  return v;
}

// Next outgoing halfedge of from_vertex(h) in rotation order (h must have a face).
HalfedgeHandle Rotate(const PolyMesh& mesh, HalfedgeHandle h) {
  return mesh.next_halfedge_handle(mesh.opposite_halfedge_handle(h));
}

// The halfedge that continues h straight on through to_vertex(h), or an invalid handle.
HalfedgeHandle Straight(const PolyMesh& mesh, HalfedgeHandle h) {
  const VertexHandle w = mesh.to_vertex_handle(h);
  const int valence = static_cast<int>(mesh.valence(w));
  if (!mesh.is_boundary(w)) {
    if (valence % 2 != 0) return HalfedgeHandle();
    HalfedgeHandle out = mesh.opposite_halfedge_handle(h);
    for (int k = 0; k < valence / 2; ++k) out = Rotate(mesh, out);
    return out;
  }
  if (valence != 3 || !mesh.is_boundary(mesh.edge_handle(h))) return HalfedgeHandle();
  for (auto out : mesh.voh_range(w))
    if (mesh.is_boundary(mesh.edge_handle(out)) && mesh.edge_handle(out) != mesh.edge_handle(h))
      return out;
  return HalfedgeHandle();
}

std::string JoinIds(const std::vector<int>& ids, size_t limit = 8) {
  std::string s;
  for (size_t k = 0; k < ids.size() && k < limit; ++k)
    s += (k ? ", " : "") + std::to_string(ids[k]);
  if (ids.size() > limit) s += ", ...";
  return s;
}

// |det(p1 − p0, p2 − p0, p3 − p0)| / (|p1 − p0| |p2 − p0| |p3 − p0|).
double QuadResidual(const Eigen::Vector3d& p0, const Eigen::Vector3d& p1, const Eigen::Vector3d& p2,
                    const Eigen::Vector3d& p3) {
  const Eigen::Vector3d a = p1 - p0, b = p2 - p0, c = p3 - p0;
  const double scale = a.norm() * b.norm() * c.norm();
  return scale > 0.0 ? std::abs(a.cross(b).dot(c)) / scale : 0.0;
}

}  // namespace

const char* MarionetteProjectionName(MarionetteProjection projection) {
  switch (projection) {
    case MarionetteProjection::kVertical:
      return "vertical";
    case MarionetteProjection::kCylindrical:
      return "cylindrical";
    case MarionetteProjection::kCentral:
      return "central";
  }
  return "?";
}

bool ParseMarionetteProjection(const std::string& name, MarionetteProjection* projection) {
  for (MarionetteProjection p :
       {MarionetteProjection::kVertical, MarionetteProjection::kCylindrical,
        MarionetteProjection::kCentral})
    if (name == MarionetteProjectionName(p)) {
      *projection = p;
      return true;
    }
  return false;
}

bool MarionetteProjectionOptions::IsValid(std::string* why) const {
  if (!axis_point.allFinite() || !axis_direction.allFinite() || !centre.allFinite()) {
    *why = "the axis and the centre must be finite";
    return false;
  }
  if (type == MarionetteProjection::kCylindrical && !(axis_direction.norm() > 0.0)) {
    *why = "the axis direction must not be zero";
    return false;
  }
  return true;
}

MarionetteLines MakeMarionetteLines(const PolyMesh& plan,
                                    const MarionetteProjectionOptions& options,
                                    const std::string& path) {
  const std::string prefix = path.empty() ? "" : path + ": ";
  std::string why;
  if (!options.IsValid(&why)) throw InputError(prefix + why);
  MarionetteLines lines;
  lines.mesh = plan;
  lines.projection = options.type;
  const int n = static_cast<int>(plan.n_vertices());
  lines.origin.resize(n);
  lines.direction.resize(n);
  lines.plan_parameters = Eigen::VectorXd::Zero(n);
  const Eigen::Vector3d axis = options.axis_direction.normalized();
  for (auto vh : plan.vertices()) {
    const int v = vh.idx();
    const Eigen::Vector3d p(plan.point(vh)[0], plan.point(vh)[1], plan.point(vh)[2]);
    Eigen::Vector3d o, r;
    switch (options.type) {
      case MarionetteProjection::kVertical:
        lines.origin[v] = Eigen::Vector3d(p.x(), p.y(), 0.0);
        lines.direction[v] = Eigen::Vector3d::UnitZ();
        continue;
      case MarionetteProjection::kCylindrical:
        o = options.axis_point + (p - options.axis_point).dot(axis) * axis;
        break;
      case MarionetteProjection::kCentral:
        o = options.centre;
        break;
    }
    r = p - o;
    const double length = r.norm();
    const double scale = std::max(p.norm(), o.norm()) + 1.0;
    if (!(length > 1e-12 * scale))
      throw InputError(prefix + "vertex " + std::to_string(v) +
                       (options.type == MarionetteProjection::kCylindrical
                            ? " lies on the axis, so it has no line perpendicular to it"
                            : " lies at the centre, so it has no line through it"));
    lines.origin[v] = o;
    lines.direction[v] = r / length;
    lines.plan_parameters[v] = length;
  }
  return lines;
}

PolyMesh MarionetteLiftedMesh(const MarionetteLines& lines, const Eigen::VectorXd& t) {
  PolyMesh out = lines.mesh;
  for (auto v : out.vertices()) {
    const Eigen::Vector3d p = lines.Point(v.idx(), t[v.idx()]);
    out.set_point(v, PolyMesh::Point(p.x(), p.y(), p.z()));
  }
  return out;
}

double MaxLiftPlanarity(const MarionetteLines& lines, const Eigen::VectorXd& t) {
  double worst = 0.0;
  for (int f = 0; f < static_cast<int>(lines.mesh.n_faces()); ++f) {
    const auto v = FaceVertices(lines.mesh, f);
    worst = std::max(worst, QuadResidual(lines.Point(v[0], t[v[0]]), lines.Point(v[1], t[v[1]]),
                                         lines.Point(v[2], t[v[2]]), lines.Point(v[3], t[v[3]])));
  }
  return worst;
}

std::vector<int> TraceMeshPolyline(const PolyMesh& mesh, int start, int next, int max_vertices) {
  std::vector<int> poly = {start};
  if (max_vertices < 2) return poly;
  HalfedgeHandle h =
      mesh.find_halfedge(PolyMesh::VertexHandle(start), PolyMesh::VertexHandle(next));
  if (!h.is_valid()) return poly;
  while (static_cast<int>(poly.size()) < max_vertices) {
    const int w = mesh.to_vertex_handle(h).idx();
    if (w == start) break;
    poly.push_back(w);
    if (static_cast<int>(poly.size()) == max_vertices) break;
    h = Straight(mesh, h);
    if (!h.is_valid()) break;
  }
  return poly;
}

namespace {

// What the steps of DecomposeIntoPatches share.
struct Decomposition {
  std::vector<char> on_separatrix, separatrix_edge;  // per vertex, per edge
  std::vector<int> strip_of;                         // (face, direction) → face strip
  std::vector<std::vector<int>> strip_patches;       // per face strip, the patches it crosses
  std::vector<char> strip_closed;                    // per face strip
};

// Singular vertices and the separatrices traced from them along straight mesh lines.
void TraceSeparatrices(const PolyMesh& mesh, MarionettePatchLayout* layout, Decomposition* d) {
  const int nv = static_cast<int>(mesh.n_vertices()), ne = static_cast<int>(mesh.n_edges());
  d->on_separatrix.assign(nv, 0);
  d->separatrix_edge.assign(ne, 0);
  std::vector<char>& on_separatrix = d->on_separatrix;
  std::vector<char>& separatrix_edge = d->separatrix_edge;
  for (auto v : mesh.vertices()) {
    const int valence = static_cast<int>(mesh.valence(v));
    const bool boundary = mesh.is_boundary(v);
    if (boundary) on_separatrix[v.idx()] = 1;
    if ((!boundary && valence != 4) || (boundary && (valence == 2 || valence >= 4)))
      layout->singular_vertices.push_back(v.idx());
  }
  for (int v : layout->singular_vertices) on_separatrix[v] = 1;
  for (auto e : mesh.edges())
    if (mesh.is_boundary(e)) separatrix_edge[e.idx()] = 1;
  for (int s : layout->singular_vertices) {
    for (auto out : mesh.voh_range(PolyMesh::VertexHandle(s))) {
      if (separatrix_edge[mesh.edge_handle(out).idx()]) continue;
      std::vector<int> poly = {s};
      HalfedgeHandle h = out;
      while (true) {
        separatrix_edge[mesh.edge_handle(h).idx()] = 1;
        const int w = mesh.to_vertex_handle(h).idx();
        poly.push_back(w);
        if (on_separatrix[w]) break;
        on_separatrix[w] = 1;
        h = Straight(mesh, h);  // w is an inner valence-4 vertex
      }
      layout->separatrices.push_back(std::move(poly));
    }
  }
}

// Patches: faces connected across edges that are not on a separatrix; a patch whose corners
// and boundary make a grid gets its rows and columns.
void FloodPatches(const PolyMesh& mesh, const Decomposition& d, MarionettePatchLayout* layout) {
  const int nf = static_cast<int>(mesh.n_faces());
  const std::vector<char>& on_separatrix = d.on_separatrix;
  const std::vector<char>& separatrix_edge = d.separatrix_edge;
  layout->patch_of_face.assign(nf, -1);
  for (int seed = 0; seed < nf; ++seed) {
    if (layout->patch_of_face[seed] >= 0) continue;
    const int id = static_cast<int>(layout->patches.size());
    MarionettePatch patch;
    std::vector<int> stack = {seed};
    layout->patch_of_face[seed] = id;
    while (!stack.empty()) {
      const int f = stack.back();
      stack.pop_back();
      patch.faces.push_back(f);
      for (auto h : FaceHalfedges(mesh, f)) {
        if (separatrix_edge[mesh.edge_handle(h).idx()]) continue;
        const int g = mesh.face_handle(mesh.opposite_halfedge_handle(h)).idx();
        if (g >= 0 && layout->patch_of_face[g] < 0) {
          layout->patch_of_face[g] = id;
          stack.push_back(g);
        }
      }
    }
    std::sort(patch.faces.begin(), patch.faces.end());
    // Corners: vertices with one face of the patch; a grid has 4, and its boundary edges
    // (rows + cols) * 2 and rows * cols faces.
    std::map<int, int> incidence;
    int boundary_edges = 0;
    for (int f : patch.faces)
      for (auto h : FaceHalfedges(mesh, f)) {
        ++incidence[mesh.from_vertex_handle(h).idx()];
        if (separatrix_edge[mesh.edge_handle(h).idx()]) ++boundary_edges;
      }
    bool concave = false;
    for (const auto& [v, count] : incidence) {
      if (count == 1) patch.corners.push_back(v);
      if (count == 3 || (count > 4) || (count == 4 && on_separatrix[v])) concave = true;
    }
    const int half = boundary_edges / 2, faces = static_cast<int>(patch.faces.size());
    if (!concave && patch.corners.size() == 4 && boundary_edges % 2 == 0) {
      const double disc = static_cast<double>(half) * half - 4.0 * faces;
      const int rows = disc >= 0 ? static_cast<int>(std::lround((half - std::sqrt(disc)) / 2)) : 0;
      if (rows > 0 && rows * (half - rows) == faces) {
        patch.rows = rows;
        patch.cols = half - rows;
      }
    }
    layout->patches.push_back(std::move(patch));
  }
}

// Face strips: (face, direction) → strip, walking through opposite edges.
void TraceFaceStrips(const PolyMesh& mesh, MarionettePatchLayout* layout, Decomposition* d) {
  const int nf = static_cast<int>(mesh.n_faces()), ne = static_cast<int>(mesh.n_edges());
  d->strip_of.assign(2 * nf, -1);
  std::vector<int>& strip_of = d->strip_of;
  std::vector<std::vector<int>>& strip_patches = d->strip_patches;
  std::vector<char>& strip_closed = d->strip_closed;
  layout->face_strip_of_edge.assign(ne, -1);
  for (int f0 = 0; f0 < nf; ++f0)
    for (int k0 = 0; k0 < 2; ++k0) {
      if (strip_of[2 * f0 + k0] >= 0) continue;
      const int s = layout->num_face_strips++;
      bool closed = false;
      std::vector<int> sequence[2];  // patches met leaving through edge k0 and through k0 + 2
      strip_of[2 * f0 + k0] = s;
      for (int side = 0; side < 2 && !closed; ++side) {
        int f = f0, j = k0 + 2 * side;
        while (true) {
          const HalfedgeHandle h = FaceHalfedges(mesh, f)[j];
          layout->face_strip_of_edge[mesh.edge_handle(h).idx()] = s;
          const HalfedgeHandle o = mesh.opposite_halfedge_handle(h);
          const int g = mesh.face_handle(o).idx();
          if (g < 0) break;
          const auto hg = FaceHalfedges(mesh, g);
          const int jg = static_cast<int>(std::find(hg.begin(), hg.end(), o) - hg.begin());
          if (strip_of[2 * g + jg % 2] == s) {
            closed = true;
            break;
          }
          strip_of[2 * g + jg % 2] = s;
          const int p = layout->patch_of_face[g];
          if (sequence[side].empty() || sequence[side].back() != p) sequence[side].push_back(p);
          f = g;
          j = (jg + 2) % 4;
        }
      }
      if (closed) ++layout->num_closed_face_strips;
      // The patches along the strip, from one end to the other.
      std::vector<int> patches(sequence[1].rbegin(), sequence[1].rend());
      if (patches.empty() || patches.back() != layout->patch_of_face[f0])
        patches.push_back(layout->patch_of_face[f0]);
      for (int p : sequence[0])
        if (patches.back() != p) patches.push_back(p);
      strip_patches.push_back(std::move(patches));
      strip_closed.push_back(closed);
    }
}

// Strips of patches: face strips side by side across an edge that is not a separatrix.
void GroupPatchStrips(const PolyMesh& mesh, const Decomposition& d, MarionettePatchLayout* layout) {
  const std::vector<char>& separatrix_edge = d.separatrix_edge;
  const std::vector<int>& strip_of = d.strip_of;
  const std::vector<std::vector<int>>& strip_patches = d.strip_patches;
  const std::vector<char>& strip_closed = d.strip_closed;
  std::vector<int> parent(layout->num_face_strips);
  for (int s = 0; s < layout->num_face_strips; ++s) parent[s] = s;
  auto find = [&](int s) {
    while (parent[s] != s) s = parent[s] = parent[parent[s]];
    return s;
  };
  for (auto e : mesh.edges()) {
    if (separatrix_edge[e.idx()]) continue;
    int side[2];
    for (int k = 0; k < 2; ++k) {
      const HalfedgeHandle h = mesh.halfedge_handle(e, k);
      const int f = mesh.face_handle(h).idx();
      const auto hf = FaceHalfedges(mesh, f);
      const int j = static_cast<int>(std::find(hf.begin(), hf.end(), h) - hf.begin());
      side[k] = find(strip_of[2 * f + (j + 1) % 2]);
    }
    parent[side[0]] = side[1];
  }
  std::vector<int> patch_strip_of_root(layout->num_face_strips, -1);
  for (int s = 0; s < layout->num_face_strips; ++s) {
    int& id = patch_strip_of_root[find(s)];
    if (id < 0) {
      id = static_cast<int>(layout->patch_strips.size());
      layout->patch_strips.push_back({strip_patches[s], {}, false});
    }
    layout->patch_strips[id].face_strips.push_back(s);
    layout->patch_strips[id].closed = layout->patch_strips[id].closed || strip_closed[s];
    layout->patch_strip_of_face_strip.push_back(id);
  }
}

}  // namespace

MarionettePatchLayout DecomposeIntoPatches(const PolyMesh& mesh) {
  MarionettePatchLayout layout;
  Decomposition d;
  TraceSeparatrices(mesh, &layout, &d);
  FloodPatches(mesh, d, &layout);
  TraceFaceStrips(mesh, &layout, &d);
  GroupPatchStrips(mesh, d, &layout);
  return layout;
}

std::vector<MarionetteTarget> ResolveMarionetteGuides(const PolyMesh& mesh,
                                                      const std::vector<MarionetteGuide>& guides,
                                                      const std::vector<MarionetteTarget>& single) {
  const int nv = static_cast<int>(mesh.n_vertices());
  std::vector<double> value(nv, 0.0);
  std::vector<std::string> source(nv);
  std::vector<MarionetteTarget> out;
  auto set = [&](int v, double h, const std::string& where) {
    if (!std::isfinite(h))
      throw InputError(where + ": the value of vertex " + std::to_string(v) + " is not finite");
    if (!source[v].empty()) {
      if (std::abs(value[v] - h) > 1e-12 * (1.0 + std::abs(h)))
        throw InputError("incompatible guides: vertex " + std::to_string(v) + " gets " +
                         std::to_string(value[v]) + " from " + source[v] + " and " +
                         std::to_string(h) + " from " + where);
      return;
    }
    value[v] = h;
    source[v] = where;
    out.push_back({v, h});
  };
  for (size_t g = 0; g < guides.size(); ++g) {
    const MarionetteGuide& guide = guides[g];
    const std::string where = guide.where.empty() ? "guide " + std::to_string(g) : guide.where;
    for (int v : {guide.start, guide.next})
      if (v < 0 || v >= nv)
        throw InputError(where + ": vertex " + std::to_string(v) +
                         " is out of range (the plan has " + std::to_string(nv) + " vertices)");
    if (guide.values.size() < 2)
      throw InputError(where + ": a guide polyline needs at least two values");
    if (!mesh.find_halfedge(PolyMesh::VertexHandle(guide.start), PolyMesh::VertexHandle(guide.next))
             .is_valid())
      throw InputError(where + ": vertices " + std::to_string(guide.start) + " and " +
                       std::to_string(guide.next) + " are not joined by an edge");
    const int count = static_cast<int>(guide.values.size());
    const std::vector<int> poly = TraceMeshPolyline(mesh, guide.start, guide.next, count);
    if (static_cast<int>(poly.size()) < count)
      throw InputError(where + ": the polyline from vertex " + std::to_string(guide.start) +
                       " through " + std::to_string(guide.next) + " has only " +
                       std::to_string(poly.size()) + " vertices (it stops at vertex " +
                       std::to_string(poly.back()) +
                       ": boundary, odd valence or back at its start), but " +
                       std::to_string(count) + " values are given");
    for (int k = 0; k < count; ++k) set(poly[k], guide.values[k], where);
  }
  for (const MarionetteTarget& t : single) {
    if (t.vertex < 0 || t.vertex >= nv)
      throw InputError("vertex " + std::to_string(t.vertex) + " is out of range (the plan has " +
                       std::to_string(nv) + " vertices)");
    set(t.vertex, t.height, "the value of vertex " + std::to_string(t.vertex));
  }
  return out;
}

namespace {

// Why face f cannot propagate the parameter of its vertex u from a, b, c.
std::string DegenerateFaceMessage(const MarionetteLines& lines, const MarionettePatchLayout& layout,
                                  int f, int u, int a, int b, int c) {
  return "face " + std::to_string(f) + " (patch " + std::to_string(layout.patch_of_face[f]) +
         (lines.projection == MarionetteProjection::kVertical
              ? ") has a degenerate plan view: its vertices " + std::to_string(a) + ", " +
                    std::to_string(b) + " and " + std::to_string(c) +
                    " are collinear in x, y, so the height of vertex " + std::to_string(u) +
                    " cannot be propagated"
              : "): the line of vertex " + std::to_string(u) +
                    " is parallel to the plane through vertices " + std::to_string(a) + ", " +
                    std::to_string(b) + " and " + std::to_string(c) +
                    " (or they are collinear), so its parameter cannot be propagated");
}

// The error for guides that leave vertices without a value: the patches concerned and the
// strips of patches no guide crosses.
[[noreturn]] void ThrowUnderDetermined(const PolyMesh& mesh, const MarionettePatchLayout& layout,
                                       const std::vector<char>& known,
                                       const std::vector<char>& done,
                                       const std::vector<int>& missing, size_t num_prescribed) {
  const int nf = static_cast<int>(mesh.n_faces());
  std::vector<int> patches;
  for (int f = 0; f < nf; ++f)
    if (!done[f]) {
      const int p = layout.patch_of_face[f];
      if (std::find(patches.begin(), patches.end(), p) == patches.end()) patches.push_back(p);
    }
  std::sort(patches.begin(), patches.end());
  // Strips of patches with a face strip that no prescribed edge crosses.
  std::vector<char> crossed(layout.num_face_strips, 0);
  for (auto e : mesh.edges()) {
    const auto h = mesh.halfedge_handle(e, 0);
    if (known[mesh.from_vertex_handle(h).idx()] && known[mesh.to_vertex_handle(h).idx()] &&
        layout.face_strip_of_edge[e.idx()] >= 0)
      crossed[layout.face_strip_of_edge[e.idx()]] = 1;
  }
  std::vector<int> uncrossed;
  for (int s = 0; s < layout.num_face_strips; ++s) {
    const int ps = layout.patch_strip_of_face_strip[s];
    if (!crossed[s] && std::find(uncrossed.begin(), uncrossed.end(), ps) == uncrossed.end())
      uncrossed.push_back(ps);
  }
  std::string strips;
  for (size_t k = 0; k < uncrossed.size() && k < 4; ++k)
    strips += std::string(k ? "; " : "") + "strip of patches " +
              JoinIds(layout.patch_strips[uncrossed[k]].patches);
  throw InputError(
      "the guides do not determine patch" + std::string(patches.size() > 1 ? "es " : " ") +
      JoinIds(patches) + ": " + std::to_string(missing.size()) + " vertices have no value (" +
      JoinIds(missing) + ")" + (strips.empty() ? "" : "; no guide crosses " + strips) +
      " (a lift needs " + std::to_string(layout.design_dimension()) +
      " values on guides across every strip, got " + std::to_string(num_prescribed) + ")");
}

}  // namespace

MarionetteMeshLift LiftMarionetteMesh(const MarionetteLines& lines,
                                      const MarionettePatchLayout& layout,
                                      const std::vector<MarionetteTarget>& prescribed,
                                      double compatibility_tolerance) {
  const PolyMesh& mesh = lines.mesh;
  const int nv = lines.num_vertices(), nf = static_cast<int>(mesh.n_faces());
  std::vector<std::array<int, 4>> faces(nf);
  for (int f = 0; f < nf; ++f) faces[f] = FaceVertices(mesh, f);
  MarionetteMeshLift lift;
  lift.t = Eigen::VectorXd::Zero(nv);
  std::vector<char> known(nv, 0), done(nf, 0);
  std::vector<int> known_count(nf, 0), queue;
  std::vector<int> faces_left(layout.patches.size());
  for (size_t p = 0; p < layout.patches.size(); ++p)
    faces_left[p] = static_cast<int>(layout.patches[p].faces.size());
  auto finish_face = [&](int f) {
    done[f] = 1;
    if (--faces_left[layout.patch_of_face[f]] == 0)
      lift.patch_order.push_back(layout.patch_of_face[f]);
  };
  auto point = [&](int v) { return lines.Point(v, lift.t[v]); };
  // A face whose four vertices were all determined elsewhere: check it.
  auto check_redundant = [&](int f) {
    const auto& q = faces[f];
    const double r = QuadResidual(point(q[0]), point(q[1]), point(q[2]), point(q[3]));
    const int p = layout.patch_of_face[f];
    if (!(r <= compatibility_tolerance)) {
      throw InputError("incompatible guides: face " + std::to_string(f) + " (patch " +
                       std::to_string(p) + ", vertices " + JoinIds({q[0], q[1], q[2], q[3]}) +
                       ") has all four vertices determined by other faces or guides and is not "
                       "planar (residual " +
                       std::to_string(r) +
                       "); the guides over-determine it: give one guide across each strip of "
                       "patches");
    }
    lift.redundant_faces.push_back(f);
    if (std::find(lift.over_determined_patches.begin(), lift.over_determined_patches.end(), p) ==
        lift.over_determined_patches.end())
      lift.over_determined_patches.push_back(p);
    finish_face(f);
  };
  auto make_known = [&](int v, double t, int determining_face) {
    known[v] = 1;
    lift.t[v] = t;
    for (auto fh : mesh.vf_range(VertexHandle(v))) {
      const int g = fh.idx();
      const int c = ++known_count[g];
      if (c == 3) queue.push_back(g);
      if (c == 4 && g != determining_face && !done[g]) check_redundant(g);
    }
  };
  for (const MarionetteTarget& t : prescribed) {
    if (known[t.vertex])
      throw InputError("vertex " + std::to_string(t.vertex) + " is prescribed twice");
    make_known(t.vertex, t.height, -1);
  }
  for (size_t next = 0; next < queue.size(); ++next) {
    const int f = static_cast<int>(queue[next]);
    if (done[f] || known_count[f] != 3) continue;
    const auto& q = faces[f];
    int j = 0;
    while (known[q[j]]) ++j;
    const int u = q[j], a = q[(j + 1) % 4], b = q[(j + 2) % 4], c = q[(j + 3) % 4];
    const Eigen::Vector3d pa = point(a), pb = point(b), pc = point(c);
    const Eigen::Vector3d n = (pa - pb).cross(pc - pb);
    const double nd = n.dot(lines.direction[u]);
    if (!(std::abs(nd) > 1e-12 * (pa - pb).norm() * (pc - pb).norm()))
      throw InputError(DegenerateFaceMessage(lines, layout, f, u, a, b, c));
    const double t = n.dot(pb - lines.origin[u]) / nd;
    finish_face(f);
    make_known(u, t, f);
  }
  // Under-determined: patches with vertices left.
  std::vector<int> missing;
  for (int v = 0; v < nv; ++v)
    if (!known[v]) missing.push_back(v);
  if (!missing.empty()) ThrowUnderDetermined(mesh, layout, known, done, missing, prescribed.size());
  return lift;
}

Problem MakeMarionetteMeshProblem(const MarionetteLines& lines,
                                  const std::vector<MarionetteTarget>& prescribed) {
  const PolyMesh& mesh = lines.mesh;
  const int nv = lines.num_vertices(), nf = static_cast<int>(mesh.n_faces());
  const bool vertical = lines.projection == MarionetteProjection::kVertical;
  Problem problem;
  const int t_block = problem.layout().AddBlock("parameters", nv, 1);
  const int n_block = vertical ? -1 : problem.layout().AddBlock("normals", nf, 3, true);
  problem.ResizeToLayout();
  Eigen::VectorXd t = lines.plan_parameters;
  for (const MarionetteTarget& g : prescribed) t[g.vertex] = g.height;
  problem.x().segment(problem.layout().Index(t_block, 0, 0), nv) = t;
  const BlockItems item(problem.layout(), t_block);
  if (vertical) {
    auto* planarity = problem.AddFamily<MarionettePlanarity>();
    for (int f = 0; f < nf; ++f) {
      const auto q = FaceVertices(mesh, f);
      // The corner whose neighbours span the largest plan parallelogram.
      int best = -1;
      double best_area = 0.0;
      for (int k = 0; k < 4; ++k) {
        const Eigen::Vector2d a = lines.origin[q[k]].head<2>();
        const Eigen::Vector2d ab = lines.origin[q[(k + 1) % 4]].head<2>() - a;
        const Eigen::Vector2d ad = lines.origin[q[(k + 3) % 4]].head<2>() - a;
        const double area = std::abs(ab.x() * ad.y() - ab.y() * ad.x()) / (ab.norm() * ad.norm());
        if (area > best_area) best_area = area, best = k;
      }
      double alpha = 0.0, beta = 0.0;
      if (best < 0 ||
          !MarionettePlanarity::PlanCoefficients(
              lines.origin[q[best]].head<2>(), lines.origin[q[(best + 1) % 4]].head<2>(),
              lines.origin[q[(best + 2) % 4]].head<2>(), lines.origin[q[(best + 3) % 4]].head<2>(),
              &alpha, &beta))
        throw InputError("face " + std::to_string(f) +
                         " has a degenerate plan view: its vertices are collinear in x, y");
      planarity->AddQuad(item[q[best]], item[q[(best + 1) % 4]], item[q[(best + 2) % 4]],
                         item[q[(best + 3) % 4]], alpha, beta);
    }
  } else {
    auto* planarity = problem.AddFamily<LineQuadPlanarity>();
    for (int f = 0; f < nf; ++f) {
      const auto q = FaceVertices(mesh, f);
      std::array<int, 4> items;
      std::array<Eigen::Vector3d, 4> o, d, p;
      for (int j = 0; j < 4; ++j) {
        items[j] = item[q[j]];
        o[j] = lines.origin[q[j]];
        d[j] = lines.direction[q[j]];
        p[j] = lines.Point(q[j], t[q[j]]);
      }
      const Eigen::Vector3d n = QuadPlanarity::InitialNormal(p[0], p[1], p[2], p[3]);
      problem.x().segment<3>(problem.layout().Index(n_block, f, 0)) = n;
      planarity->AddQuad(BlockItems(problem.layout(), n_block)[f], items, o, d);
    }
  }
  if (!prescribed.empty()) {
    auto* guides = problem.AddFamily<ScalarTarget>("guides", FamilyRole::kConstraint);
    for (const MarionetteTarget& g : prescribed) guides->AddTarget(item[g.vertex], g.height);
  }
  return problem;
}

SolverOptions MarionetteMeshSolverOptions(MarionetteProjection projection, int max_iterations,
                                          double tolerance) {
  if (projection == MarionetteProjection::kVertical) return MarionetteSolverOptions();
  SolverOptions options;
  options.max_iterations = max_iterations;
  options.residual_tolerance = tolerance;
  options.epsilon = 1e-3;
  return options;
}

Eigen::VectorXd MarionetteMeshParameters(const Problem& problem) {
  const int block = problem.layout().FindBlock("parameters");
  const VariableBlock& b = problem.layout().block(block);
  return problem.x().segment(b.offset, b.num_items);
}

}  // namespace gproj::marionette
