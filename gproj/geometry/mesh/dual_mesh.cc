#include "gproj/geometry/mesh/dual_mesh.h"

#include <Eigen/Geometry>
#include <Eigen/SVD>
#include <algorithm>
#include <cmath>
#include <vector>

#include "gproj/common/input_error.h"

namespace gproj {
namespace {

Eigen::Vector3d P(const PolyMesh& mesh, PolyMesh::VertexHandle v) {
  const auto& q = mesh.point(v);
  return {q[0], q[1], q[2]};
}

// Angle-weighted vertex normals (zero for an isolated vertex).
std::vector<Eigen::Vector3d> VertexNormals(const PolyMesh& mesh) {
  std::vector<Eigen::Vector3d> normals(mesh.n_vertices(), Eigen::Vector3d::Zero());
  for (auto f : mesh.faces()) {
    Eigen::Vector3d p[3];
    PolyMesh::VertexHandle v[3];
    int k = 0;
    for (auto fv : mesh.fv_range(f)) v[k] = fv, p[k++] = P(mesh, fv);
    const Eigen::Vector3d n = (p[1] - p[0]).cross(p[2] - p[0]);
    if (!(n.norm() > 0.0)) continue;
    for (int i = 0; i < 3; ++i) {
      const Eigen::Vector3d a = p[(i + 1) % 3] - p[i], b = p[(i + 2) % 3] - p[i];
      normals[v[i].idx()] += std::atan2(a.cross(b).norm(), a.dot(b)) * n.normalized();
    }
  }
  for (Eigen::Vector3d& n : normals)
    if (n.norm() > 0.0) n.normalize();
  return normals;
}

}  // namespace

PolyMesh DualMesh(const PolyMesh& mesh, const DualOptions& options, DualStats* stats) {
  DualStats local;
  DualStats& s = stats ? *stats : local;
  s = DualStats();
  for (auto f : mesh.faces())
    if (mesh.valence(f) != 3)
      throw InputError("face " + std::to_string(f.idx()) + " has " +
                       std::to_string(mesh.valence(f)) +
                       " vertices; the dual is taken of a triangle mesh");
  if (mesh.n_faces() == 0) throw InputError("the mesh has no faces");

  // One dual vertex per triangle.
  std::vector<Eigen::Vector3d> points(mesh.n_faces());
  const std::vector<Eigen::Vector3d> normals = options.start == DualStart::kTangentPlanes
                                                   ? VertexNormals(mesh)
                                                   : std::vector<Eigen::Vector3d>();
  for (auto f : mesh.faces()) {
    Eigen::Vector3d p[3];
    PolyMesh::VertexHandle v[3];
    int k = 0;
    for (auto fv : mesh.fv_range(f)) v[k] = fv, p[k++] = P(mesh, fv);
    const Eigen::Vector3d centroid = (p[0] + p[1] + p[2]) / 3.0;
    points[f.idx()] = centroid;
    if (options.start != DualStart::kTangentPlanes) continue;
    Eigen::Matrix3d a;
    Eigen::Vector3d b;
    for (int i = 0; i < 3; ++i) {
      a.row(i) = normals[v[i].idx()].transpose();
      b[i] = normals[v[i].idx()].dot(p[i] - centroid);
    }
    // The least-squares solution nearest the centroid: the point where the planes meet, or on
    // the line (the plane) they share when their normals are (numerically) dependent.
    const Eigen::JacobiSVD<Eigen::Matrix3d> svd(a, Eigen::ComputeFullU | Eigen::ComputeFullV);
    const Eigen::Vector3d sigma = svd.singularValues();
    const Eigen::Vector3d ub = svd.matrixU().transpose() * b;
    int rank = 0;
    while (rank < 3 && sigma[rank] > options.rank_tolerance * sigma[0]) ++rank;
    // The damped solution Σ v_i σ_i (u_i · b) / (σ_i² + μ²): μ = 0 where the planes meet.
    auto damped = [&](double mu) {
      Eigen::Vector3d o = Eigen::Vector3d::Zero();
      for (int i = 0; i < rank; ++i)
        o += svd.matrixV().col(i) * (sigma[i] * ub[i] / (sigma[i] * sigma[i] + mu * mu));
      return o;
    };
    const double reach =
        std::max({(p[1] - p[0]).norm(), (p[2] - p[1]).norm(), (p[0] - p[2]).norm()});
    Eigen::Vector3d offset = damped(0.0);
    if (rank == 0 || !offset.allFinite()) {
      ++s.centroid_fallbacks;
      continue;
    }
    if (offset.norm() > reach) {
      // Farther than the reach: the point at the reach's distance nearest the three planes
      // (|damped(μ)| falls as μ grows; bisection on log μ).
      double low = 1e-12 * sigma[0], high = 1e6 * sigma[0];
      for (int k = 0; k < 100; ++k) {
        const double mu = std::sqrt(low * high);
        (damped(mu).norm() > reach ? low : high) = mu;
      }
      offset = damped(high);
      ++s.held_within_reach;
    } else {
      ++s.tangent_plane_vertices;
      s.rank_deficient += rank < 3 ? 1 : 0;
    }
    points[f.idx()] = centroid + offset;
  }

  // Where the planes of two neighbouring triangles meet in (nearly) one point (four vertices on
  // one circle of a sphere, symmetric configurations), the dual edge between them would be
  // shorter than a hundredth of the edge it crosses, or of no length at all: both stay at their
  // centroids (such an edge is no panel edge, and a reader refuses one of no length).
  if (options.start == DualStart::kTangentPlanes) {
    std::vector<bool> collapse(mesh.n_faces(), false);
    for (auto e : mesh.edges()) {
      if (mesh.is_boundary(e)) continue;
      const int f = mesh.face_handle(mesh.halfedge_handle(e, 0)).idx();
      const int g = mesh.face_handle(mesh.halfedge_handle(e, 1)).idx();
      if ((points[f] - points[g]).norm() < 0.01 * mesh.calc_edge_length(e))
        collapse[f] = collapse[g] = true;
    }
    for (auto f : mesh.faces()) {
      if (!collapse[f.idx()]) continue;
      Eigen::Vector3d centroid = Eigen::Vector3d::Zero();
      for (auto fv : mesh.fv_range(f)) centroid += P(mesh, fv) / 3.0;
      points[f.idx()] = centroid;
      ++s.coincident;
    }
  }

  // One face per vertex: the triangles around it, counter-clockwise as the input's faces are.
  std::vector<int> index(mesh.n_faces(), -1);  // triangle -> dual vertex
  PolyMesh dual;
  auto dual_vertex = [&](int triangle) {
    if (index[triangle] < 0) {
      const Eigen::Vector3d& q = points[triangle];
      index[triangle] = dual.add_vertex(PolyMesh::Point(q[0], q[1], q[2])).idx();
    }
    return dual.vertex_handle(index[triangle]);
  };
  std::vector<PolyMesh::VertexHandle> midpoint(mesh.n_edges());
  auto edge_midpoint = [&](PolyMesh::HalfedgeHandle h) {
    const auto e = mesh.edge_handle(h);
    if (!midpoint[e.idx()].is_valid()) {
      const Eigen::Vector3d q =
          0.5 * (P(mesh, mesh.from_vertex_handle(h)) + P(mesh, mesh.to_vertex_handle(h)));
      midpoint[e.idx()] = dual.add_vertex(PolyMesh::Point(q[0], q[1], q[2]));
    }
    return midpoint[e.idx()];
  };
  int faces = 0;
  for (auto v : mesh.vertices()) {
    if (mesh.is_isolated(v)) continue;
    std::vector<PolyMesh::VertexHandle> ring;
    if (!mesh.is_boundary(v)) {
      for (auto f : mesh.vf_ccw_range(v)) ring.push_back(dual_vertex(f.idx()));
    } else {
      if (options.boundary == DualBoundary::kDrop) continue;
      // From the outgoing boundary halfedge clockwise through the triangles to the incoming
      // one, then reversed: counter-clockwise.
      const auto out = mesh.halfedge_handle(v);  // a boundary halfedge (no face)
      ring.push_back(edge_midpoint(out));
      auto h = out;
      while (true) {
        const auto inner = mesh.opposite_halfedge_handle(h);
        if (mesh.is_boundary(inner)) {
          ring.push_back(edge_midpoint(inner));
          break;
        }
        ring.push_back(dual_vertex(mesh.face_handle(inner).idx()));
        h = mesh.next_halfedge_handle(inner);
        if (h == out) break;  // not reached on a manifold boundary vertex
      }
      // The vertex itself closes the ring where the outline has a corner (its boundary edges
      // meet at less than kOutlineCornerDeg); where the boundary runs (nearly) straight through
      // it, it is left out: a corner of nearly 180° is no corner of a panel, and on a curved
      // outline it would be a reflex one as often as not.
      const Eigen::Vector3d q = P(mesh, v);
      const auto& m0 = dual.point(ring.front());
      const auto& m1 = dual.point(ring.back());
      const Eigen::Vector3d a = Eigen::Vector3d(m0[0], m0[1], m0[2]) - q,
                            b = Eigen::Vector3d(m1[0], m1[1], m1[2]) - q;
      if (std::atan2(a.cross(b).norm(), a.dot(b)) * 180.0 / M_PI < kOutlineCornerDeg)
        ring.push_back(dual.add_vertex(PolyMesh::Point(q[0], q[1], q[2])));
      std::reverse(ring.begin(), ring.end());
      ++s.boundary_faces;
    }
    if (ring.size() < 3) continue;
    if (!dual.add_face(ring).is_valid())
      throw InputError("vertex " + std::to_string(v.idx()) +
                       ": its ring of triangles gives a face the dual cannot take (a "
                       "non-manifold neighbourhood)");
    ++faces;
  }
  if (faces == 0)
    throw InputError(
        "the mesh has no interior vertex, so its dual has no faces (`boundary` keep gives the "
        "boundary vertices faces too)");
  return dual;
}

}  // namespace gproj
