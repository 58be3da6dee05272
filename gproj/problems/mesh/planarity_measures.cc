#include "gproj/problems/mesh/planarity_measures.h"

#include <algorithm>
#include <vector>

#include "gproj/geometry/mesh/polygon_shape.h"
#include "gproj/geometry/mesh/scale_free.h"
#include "gproj/problems/mesh/mesh_variables.h"
#include "gproj/problems/mesh/panel_bounds.h"

namespace gproj {

NamedValues ToNamedValues(const PlanarityMeasures& m) {
  NamedValues values = {{"max_planarity", m.max_planarity},
                        {"mean_planarity", m.mean_planarity},
                        {"max_displacement", m.max_displacement},
                        {"mean_edge_length", m.mean_edge_length}};
  if (m.max_concyclicity >= 0.0) values.push_back({"max_concyclicity", m.max_concyclicity});
  if (m.max_glide_distance >= 0.0) values.push_back({"max_glide_distance", m.max_glide_distance});
  for (NamedValue& v : ShapeValues(m.shape)) values.push_back(std::move(v));
  return values;
}

PlanarityMeasures MeasurePlanarity(const PolyMesh& mesh, const PolyMesh& reference) {
  PlanarityMeasures m;
  m.mean_edge_length = MeanEdgeLength(mesh);
  // Quads by their diagonals; polygons of 5 or more corners by their least-squares plane
  // (polygon_shape.h); triangles are planar and have no panel shape to judge.
  std::vector<QuadShape> shapes;
  double sum = 0.0;
  for (auto f : mesh.faces()) {
    const int n = static_cast<int>(mesh.valence(f));
    if (n < 4) continue;
    QuadShape shape;
    if (n == 4) {  // no allocation: measured at every iterate
      Eigen::Vector3d p[4];
      int k = 0;
      for (auto v : mesh.fv_range(f)) p[k++] = ToEigen(mesh.point(v));
      shape = MeasureQuadShape(p[0], p[1], p[2], p[3]);
    } else {
      const std::vector<Eigen::Vector3d> p = FacePoints(mesh, f);
      const PolygonShape polygon = MeasurePolygonShape(p);
      shape.kink_deg = PolygonKinkDeg(p);
      shape.convex = polygon.convex;
      shape.min_angle_deg = polygon.min_angle_deg;
      shape.diagonal_distance = polygon.planarity;
    }
    const double d = shape.diagonal_distance / m.mean_edge_length;
    m.max_planarity = std::max(m.max_planarity, d);
    sum += d;
    shapes.push_back(shape);
  }
  m.mean_planarity = mesh.n_faces() > 0 ? sum / mesh.n_faces() : 0.0;
  m.max_displacement = MaxDisplacement(mesh, reference);
  m.shape = Summarize(shapes);
  return m;
}

}  // namespace gproj
