#include "gproj/problems/mesh/planarity_measures.h"

#include <algorithm>
#include <vector>

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
  const std::vector<QuadShape> shapes = MeasureQuadShapes(mesh);  // quads only (checked)
  double sum = 0.0;
  for (const QuadShape& shape : shapes) {
    const double d = shape.diagonal_distance / m.mean_edge_length;
    m.max_planarity = std::max(m.max_planarity, d);
    sum += d;
  }
  m.mean_planarity = mesh.n_faces() > 0 ? sum / mesh.n_faces() : 0.0;
  m.max_displacement = MaxDisplacement(mesh, reference);
  m.shape = Summarize(shapes);
  return m;
}

}  // namespace gproj
