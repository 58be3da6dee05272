#include "geometry/scale_free.h"

#include <cmath>

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
