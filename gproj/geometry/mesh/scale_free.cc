#include "gproj/geometry/mesh/scale_free.h"

#include <cmath>
#include <string>

namespace gproj {

double MeanEdgeLength(const PolyMesh& mesh) {
  double sum = 0.0;
  for (auto e : mesh.edges()) {
    const auto h = mesh.halfedge_handle(e, 0);
    const auto a = mesh.point(mesh.from_vertex_handle(h)), b = mesh.point(mesh.to_vertex_handle(h));
    sum += Eigen::Vector3d(b[0] - a[0], b[1] - a[1], b[2] - a[2]).stableNorm();
  }
  return mesh.n_edges() > 0 ? sum / static_cast<double>(mesh.n_edges()) : 0.0;
}

PolyMesh UnitScaleCopy(const PolyMesh& mesh) {
  PolyMesh copy = mesh;
  const double length = MeanEdgeLength(mesh);
  if (!(length > 0.0) || !std::isfinite(length) || copy.n_vertices() == 0) return copy;
  const PolyMesh::Point origin = mesh.point(*mesh.vertices_begin());
  for (auto v : copy.vertices()) copy.set_point(v, (mesh.point(v) - origin) / length);
  return copy;
}

PolyMesh UnitScaleCopy(const PolyMesh& mesh, UnitFrame* frame) {
  const double length = MeanEdgeLength(mesh);
  if (!(length > 0.0) || !std::isfinite(length) || mesh.n_vertices() == 0)
    throw InputError("the mesh's edge lengths are zero or not finite");
  const PolyMesh::Point origin = mesh.point(*mesh.vertices_begin());
  frame->origin = Eigen::Vector3d(origin[0], origin[1], origin[2]);
  frame->length = length;
  PolyMesh copy = mesh;
  for (auto v : copy.vertices()) {
    const PolyMesh::Point p = (mesh.point(v) - origin) / length;
    if (!std::isfinite(p[0]) || !std::isfinite(p[1]) || !std::isfinite(p[2]))
      throw InputError("vertex " + std::to_string(v.idx()) + " has coordinates too far from the " +
                       "others to measure");
    copy.set_point(v, p);
  }
  return copy;
}

void FromUnitScale(const UnitFrame& frame, PolyMesh* mesh) {
  for (auto v : mesh->vertices()) {
    const PolyMesh::Point& p = mesh->point(v);
    const Eigen::Vector3d q = Eigen::Vector3d(p[0], p[1], p[2]) * frame.length + frame.origin;
    mesh->set_point(v, PolyMesh::Point(q.x(), q.y(), q.z()));
  }
}

double NormalizePolygon(Eigen::Vector3d* p, int n) {
  const Eigen::Vector3d origin = p[0];
  double extent = 0.0;
  for (int i = 0; i < n; ++i) {
    p[i] -= origin;
    extent = std::max(extent, p[i].cwiseAbs().maxCoeff());
  }
  if (extent > 0.0)
    for (int i = 0; i < n; ++i) p[i] /= extent;
  return extent;
}

}  // namespace gproj
