#pragma once
// How planar a quad mesh is, and how far it moved: the measures every problem that makes planar
// quads reports (PQ planarisation, Marionette meshes, the circular constructions).

#include "gproj/geometry/io/mesh_io.h"
#include "gproj/geometry/mesh/quad_shape.h"
#include "gproj/problems/run/guided_problem.h"

namespace gproj {

// The planarity measures of a quad mesh (PQ planarisation's, and every problem's that makes
// planar quads); as named values (the report's keys): max_planarity,
// mean_planarity, max_displacement, mean_edge_length, the ShapeValues (non_convex_quads,
// min_corner_angle_deg, max_kink_deg, max_planarity_abs) and, for circular problems,
// max_concyclicity.
struct PlanarityMeasures {
  double max_planarity = 0.0;     // max over faces of (diagonal distance) / (mean edge length)
  double mean_planarity = 0.0;    // mean of the same
  double max_displacement = 0.0;  // max vertex displacement / bbox diagonal of the input
  double mean_edge_length = 0.0;  // of the measured mesh, in input units
  // Max over faces of the vertices' distance to their fitted circle / mean edge length; only
  // measured for circular problems (−1 otherwise).
  double max_concyclicity = -1.0;
  // Convexity, corner angles, kinks and the planarity in input units.
  QuadShapeSummary shape;
  // Max distance of a gliding boundary vertex from the input boundary / bbox diagonal (−1:
  // no gliding).
  double max_glide_distance = -1.0;
};

NamedValues ToNamedValues(const PlanarityMeasures& m);

// Planarity of `mesh` (quads), displacement against `reference` (same connectivity; may be
// the mesh itself).
PlanarityMeasures MeasurePlanarity(const PolyMesh& mesh, const PolyMesh& reference);

}  // namespace gproj
