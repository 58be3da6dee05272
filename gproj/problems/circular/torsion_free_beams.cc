#include "gproj/problems/circular/torsion_free_beams.h"

#include <ceres/ceres.h>
#include <ceres/manifold.h>

#include <Eigen/Geometry>
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <deque>
#include <sstream>

#include "gproj/geometry/mesh/scale_free.h"

namespace gproj::circular {
namespace {

Eigen::Vector3d Point(const PolyMesh& mesh, PolyMesh::VertexHandle v) {
  const auto& p = mesh.point(v);
  return Eigen::Vector3d(p[0], p[1], p[2]);
}

// The mirror image in the plane through the origin orthogonal to the unit vector e.
Eigen::Matrix3d Reflection(const Eigen::Vector3d& e) {
  return Eigen::Matrix3d::Identity() - 2.0 * e * e.transpose();
}

// Squared sine of the angle between the axis M n and the unit edge direction e.
template <typename T>
T SineSquared(const Eigen::Matrix3d& m, const Eigen::Vector3d& e, const T* n) {
  T a[3];
  for (int r = 0; r < 3; ++r) a[r] = m(r, 0) * n[0] + m(r, 1) * n[1] + m(r, 2) * n[2];
  const T along = a[0] * e[0] + a[1] * e[1] + a[2] * e[2];
  return a[0] * a[0] + a[1] * a[1] + a[2] * a[2] - along * along;
}

// The gap between two beams at a node, in units of h: 1 / sin θ_e − 1 / sin θ_f, with the axis
// M n_0 of the node (a reflection keeps the angle, so either end of an edge gives θ_e).
struct GapResidual {
  Eigen::Matrix3d m;
  Eigen::Vector3d e, f;
  template <typename T>
  bool operator()(const T* n, T* r) const {
    using std::sqrt;
    r[0] = 1.0 / sqrt(SineSquared(m, e, n)) - 1.0 / sqrt(SineSquared(m, f, n));
    return true;
  }
};

// The rotation angle of r (from its skew part, accurate near 0); π when r is not a rotation
// (an odd number of mirror images around a face never closes).
double MismatchAngle(const Eigen::Matrix3d& r) {
  if (r.determinant() < 0.0) return M_PI;
  const Eigen::Vector3d skew(r(2, 1) - r(1, 2), r(0, 2) - r(2, 0), r(1, 0) - r(0, 1));
  return std::atan2(0.5 * skew.norm(), 0.5 * (r.trace() - 1.0));
}

struct Layout {
  std::vector<Eigen::Matrix3d> to_root;  // axis of vertex v = to_root[v] · axis of the root
  std::vector<int> order;                // vertices in breadth-first order
};

// Breadth-first over the edges from `root`: each vertex's reflection product.
Layout Propagate(const PolyMesh& mesh, int root) {
  Layout l;
  l.to_root.assign(mesh.n_vertices(), Eigen::Matrix3d::Zero());
  std::vector<bool> seen(mesh.n_vertices(), false);
  std::deque<int> queue{root};
  seen[root] = true;
  l.to_root[root] = Eigen::Matrix3d::Identity();
  while (!queue.empty()) {
    const int i = queue.front();
    queue.pop_front();
    l.order.push_back(i);
    const auto vi = mesh.vertex_handle(i);
    for (auto vv = mesh.cvv_iter(vi); vv.is_valid(); ++vv) {
      const int j = vv->idx();
      if (seen[j]) continue;
      seen[j] = true;
      const Eigen::Vector3d e = (Point(mesh, *vv) - Point(mesh, vi)).normalized();
      l.to_root[j] = Reflection(e) * l.to_root[i];
      queue.push_back(j);
    }
  }
  if (l.order.size() != mesh.n_vertices())
    throw InputError("the mesh is not connected: node axes reach " +
                     std::to_string(l.order.size()) + " of " + std::to_string(mesh.n_vertices()) +
                     " vertices from vertex " + std::to_string(root));
  return l;
}

// The root: the vertex nearest the centroid (short reflection chains to every node).
int CentralVertex(const PolyMesh& mesh) {
  Eigen::Vector3d centre = Eigen::Vector3d::Zero();
  for (auto v : mesh.vertices()) centre += Point(mesh, v) / mesh.n_vertices();
  int best = 0;
  double nearest = HUGE_VAL;
  for (auto v : mesh.vertices()) {
    const double d = (Point(mesh, v) - centre).squaredNorm();
    if (d < nearest && !mesh.is_isolated(v)) nearest = d, best = v.idx();
  }
  return best;
}

// Unit mean of the normals of the faces around v (Newell's normal of each face).
Eigen::Vector3d MeanFaceNormal(const PolyMesh& mesh, PolyMesh::VertexHandle v) {
  Eigen::Vector3d sum = Eigen::Vector3d::Zero();
  for (auto f = mesh.cvf_iter(v); f.is_valid(); ++f) {
    std::vector<Eigen::Vector3d> p;
    for (auto fv = mesh.cfv_iter(*f); fv.is_valid(); ++fv) p.push_back(Point(mesh, *fv));
    Eigen::Vector3d n = Eigen::Vector3d::Zero();
    for (size_t k = 1; k + 1 < p.size(); ++k) n += (p[k] - p[0]).cross(p[k + 1] - p[0]);
    sum += n.normalized();
  }
  return sum.normalized();
}

// max over nodes of max λ − min λ, and its mean, for axes M_v n (in units of h).
struct Gaps {
  std::vector<double> lift, gap;
  double max = 0.0, mean = 0.0;
};
Gaps MeasureGaps(const PolyMesh& mesh, const std::vector<Eigen::Vector3d>& axis) {
  Gaps g;
  g.lift.assign(mesh.n_edges(), 0.0);
  for (auto e : mesh.edges()) {
    const auto h = mesh.halfedge_handle(e, 0);
    const auto a = mesh.from_vertex_handle(h), b = mesh.to_vertex_handle(h);
    const Eigen::Vector3d dir = (Point(mesh, b) - Point(mesh, a)).normalized();
    const double sine = axis[a.idx()].cross(dir).norm();
    if (!(sine > 1e-9))
      throw InputError("the node axis at vertex " + std::to_string(a.idx()) + " runs along edge " +
                       std::to_string(e.idx()) + ": a beam there would have no height");
    g.lift[e.idx()] = 1.0 / sine;
  }
  g.gap.assign(mesh.n_vertices(), 0.0);
  for (auto v : mesh.vertices()) {
    double lo = HUGE_VAL, hi = -HUGE_VAL;
    for (auto e = mesh.cve_iter(v); e.is_valid(); ++e) {
      lo = std::min(lo, g.lift[e->idx()]);
      hi = std::max(hi, g.lift[e->idx()]);
    }
    g.gap[v.idx()] = hi > lo ? hi - lo : 0.0;
    g.max = std::max(g.max, g.gap[v.idx()]);
    g.mean += g.gap[v.idx()] / mesh.n_vertices();
  }
  return g;
}

// The first axis minimising the squared gaps between every two beams at every node.
Eigen::Vector3d OptimiseRootAxis(const PolyMesh& mesh, const Layout& layout,
                                 const Eigen::Vector3d& start) {
  ceres::Problem problem;
  double n[3] = {start.x(), start.y(), start.z()};
  for (auto v : mesh.vertices()) {
    std::vector<Eigen::Vector3d> dirs;
    for (auto h = mesh.cvoh_iter(v); h.is_valid(); ++h)
      dirs.push_back((Point(mesh, mesh.to_vertex_handle(*h)) - Point(mesh, v)).normalized());
    for (size_t a = 0; a < dirs.size(); ++a)
      for (size_t b = a + 1; b < dirs.size(); ++b)
        problem.AddResidualBlock(new ceres::AutoDiffCostFunction<GapResidual, 1, 3>(
                                     new GapResidual{layout.to_root[v.idx()], dirs[a], dirs[b]}),
                                 nullptr, n);
  }
  if (problem.NumResidualBlocks() == 0) return start;
  problem.SetManifold(n, new ceres::SphereManifold<3>());
  ceres::Solver::Options options;
  options.max_num_iterations = 100;
  options.logging_type = ceres::SILENT;
  ceres::Solver::Summary summary;
  ceres::Solve(options, &problem, &summary);
  const Eigen::Vector3d result = Eigen::Vector3d(n[0], n[1], n[2]).normalized();
  // Either sign is the same layout; keep the side of the start.
  return result.allFinite() ? (result.dot(start) < 0.0 ? -result : result) : start;
}

// The beam on edge (a, b) as a box: its plane quad a, b, b + λ n_b, a + λ n_a, thickened by
// `width` across the plane.
void AddBeam(const Eigen::Vector3d& a, const Eigen::Vector3d& b, const Eigen::Vector3d& na,
             const Eigen::Vector3d& nb, double lift, double width, PolyMesh* beams) {
  const Eigen::Vector3d across = (b - a).cross(na).normalized() * (0.5 * width);
  const Eigen::Vector3d corner[4] = {a, b, b + lift * nb, a + lift * na};
  PolyMesh::VertexHandle v[8];
  for (int k = 0; k < 4; ++k) {
    const Eigen::Vector3d p = corner[k] - across, q = corner[k] + across;
    v[k] = beams->add_vertex(PolyMesh::Point(p.x(), p.y(), p.z()));
    v[k + 4] = beams->add_vertex(PolyMesh::Point(q.x(), q.y(), q.z()));
  }
  const int faces[6][4] = {{0, 3, 2, 1}, {4, 5, 6, 7}, {0, 1, 5, 4},
                           {1, 2, 6, 5}, {2, 3, 7, 6}, {3, 0, 4, 7}};
  for (const auto& f : faces) beams->add_face({v[f[0]], v[f[1]], v[f[2]], v[f[3]]});
}

// Distance of the fourth corner from the plane of the other three, over the mean edge.
double QuadPlanarity(const Eigen::Vector3d& a, const Eigen::Vector3d& b, const Eigen::Vector3d& c,
                     const Eigen::Vector3d& d, double unit) {
  const Eigen::Vector3d normal = (b - a).cross(c - a);
  const double length = normal.norm();
  return length > 0.0 ? std::abs((d - a).dot(normal / length)) / unit : 0.0;
}

}  // namespace

bool BeamOptions::IsValid(std::string* why) const {
  if (!(height > 0.0) || !std::isfinite(height)) {
    *why = "the beam height must be a finite number > 0";
    return false;
  }
  if (!(width >= 0.0) || !std::isfinite(width)) {
    *why = "the beam width must be a finite number >= 0";
    return false;
  }
  if (!(circularity_tolerance > 0.0 && circularity_tolerance <= 1e-2)) {
    *why =
        "the circularity tolerance must be in (0, 0.01] rad (a looser one gives beams that "
        "are not planar)";
    return false;
  }
  return true;
}

namespace {

// The layout of a mesh scaled to unit mean edge length (h and width in those units).
BeamLayout BeamsAtUnitScale(const PolyMesh& mesh, double h, double width,
                            const BeamOptions& options) {
  BeamLayout out;
  out.root = CentralVertex(mesh);
  const Layout layout = Propagate(mesh, out.root);
  // The axes must close around every face: compare each edge's mirror image with the axis the
  // spanning tree gave its far end.
  double closing = 0.0;
  int worst_face = -1;
  for (auto f : mesh.faces())
    for (auto h = mesh.cfh_iter(f); h.is_valid(); ++h) {
      const auto a = mesh.from_vertex_handle(*h), b = mesh.to_vertex_handle(*h);
      const Eigen::Vector3d e = (Point(mesh, b) - Point(mesh, a)).normalized();
      const double angle = MismatchAngle(layout.to_root[b.idx()].transpose() * Reflection(e) *
                                         layout.to_root[a.idx()]);
      if (angle > closing) closing = angle, worst_face = f.idx();
    }
  if (closing > options.circularity_tolerance) {
    char text[200];
    std::snprintf(text, sizeof(text),
                  "face %d is not inscribed in a circle: the node axes do not close around it "
                  "(mismatch %.3g rad > %.3g); torsion-free beams need a circular mesh",
                  worst_face, closing, options.circularity_tolerance);
    throw InputError(text);
  }
  const Eigen::Vector3d start = MeanFaceNormal(mesh, mesh.vertex_handle(out.root));
  auto axes_of = [&](const Eigen::Vector3d& n0) {
    std::vector<Eigen::Vector3d> axis(mesh.n_vertices());
    for (int v : layout.order) axis[v] = (layout.to_root[v] * n0).normalized();
    return axis;
  };
  const Gaps initial = MeasureGaps(mesh, axes_of(start));
  const Eigen::Vector3d root_axis =
      options.optimise ? OptimiseRootAxis(mesh, layout, start) : start;
  out.axis = axes_of(root_axis);
  const Gaps gaps = MeasureGaps(mesh, out.axis);
  out.node_gap = gaps.gap;
  out.edge_lift.resize(mesh.n_edges());
  for (size_t e = 0; e < gaps.lift.size(); ++e) out.edge_lift[e] = h * gaps.lift[e];

  const double unit = MeanEdgeLength(mesh);
  out.offset = mesh;
  for (auto v : out.offset.vertices()) {
    const Eigen::Vector3d p = Point(mesh, v) + h * out.axis[v.idx()];
    out.offset.set_point(v, PolyMesh::Point(p.x(), p.y(), p.z()));
  }
  double planarity = 0.0, offset_angle = 0.0, distance_error = 0.0;
  for (auto e : mesh.edges()) {
    const auto he = mesh.halfedge_handle(e, 0);
    const auto a = mesh.from_vertex_handle(he), b = mesh.to_vertex_handle(he);
    const Eigen::Vector3d pa = Point(mesh, a), pb = Point(mesh, b);
    const Eigen::Vector3d &na = out.axis[a.idx()], &nb = out.axis[b.idx()];
    const double lift = out.edge_lift[e.idx()];
    AddBeam(pa, pb, na, nb, lift, width, &out.beams);
    planarity = std::max(planarity, QuadPlanarity(pa, pb, pb + lift * nb, pa + lift * na, unit));
    const Eigen::Vector3d edge = pb - pa, moved = Point(out.offset, b) - Point(out.offset, a);
    offset_angle = std::max(offset_angle, std::atan2(edge.cross(moved).norm(), edge.dot(moved)));
  }
  for (auto v : mesh.vertices())
    distance_error =
        std::max(distance_error, std::abs((Point(out.offset, v) - Point(mesh, v)).norm() - h) / h);
  out.measures = {{"max_beam_planarity", planarity},
                  {"max_offset_angle", offset_angle},
                  {"max_offset_distance_error", distance_error},
                  {"max_closing_angle", closing},
                  {"max_height_gap", gaps.max},
                  {"mean_height_gap", gaps.mean},
                  {"initial_max_height_gap", initial.max}};
  return out;
}

}  // namespace

BeamLayout TorsionFreeBeams(const PolyMesh& mesh, const BeamOptions& options) {
  std::string why;
  if (!options.IsValid(&why)) throw InputError(why);
  if (mesh.n_faces() == 0) throw InputError("the mesh has no faces");
  for (auto f : mesh.faces())
    if (mesh.valence(f) % 2 != 0)
      throw InputError("face " + std::to_string(f.idx()) + " has " +
                       std::to_string(mesh.valence(f)) +
                       " vertices: mirror images of the node axes close only around faces with "
                       "an even number of vertices (a circular quad mesh is needed)");
  // Computed at unit scale (scale_free.h), so that far, huge or tiny coordinates lose nothing.
  UnitFrame frame;
  const PolyMesh scaled = UnitScaleCopy(mesh, &frame);
  const double unit = frame.length;
  const double h = options.height / unit;
  if (!(h >= 1e-9 && h <= 1e6)) {
    char text[200];
    std::snprintf(text, sizeof(text),
                  "the beam height %g is %.3g times the mean edge length %g: it must be between "
                  "1e-9 and 1e6 times it",
                  options.height, h, unit);
    throw InputError(text);
  }
  BeamLayout out =
      BeamsAtUnitScale(scaled, h, options.width > 0.0 ? options.width / unit : 0.04, options);
  FromUnitScale(frame, &out.offset);
  FromUnitScale(frame, &out.beams);
  for (double& lift : out.edge_lift) lift *= unit;
  return out;
}

std::string AxesObj(const PolyMesh& mesh, const std::vector<Eigen::Vector3d>& axis, double length) {
  std::vector<std::pair<Eigen::Vector3d, Eigen::Vector3d>> segments;
  segments.reserve(mesh.n_vertices());
  for (auto v : mesh.vertices())
    segments.emplace_back(Point(mesh, v), Point(mesh, v) + length * axis[v.idx()]);
  std::ostringstream comment;
  comment << "gproj node axes: vertex, vertex + " << length << " * axis";
  return SegmentsObj(comment.str(), segments);
}

}  // namespace gproj::circular
