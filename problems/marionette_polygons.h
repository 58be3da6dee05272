#pragma once
// Marionette plan views of any polygons (002 §4.2, Appendix B): Kagome (triangles and
// hexagons), dual-Kagome and other patterns. Over a fixed plan view (x, y) a face of n vertices
// is planar when n − 3 of its heights follow from three others:
//   z_k − z_0 − α (z_a − z_0) − β (z_b − z_0) = 0,  p_k − p_0 = α (p_a − p_0) + β (p_b − p_0),
// (p the plan points; 0, a, b the face's most spread-out triple). The design space — the
// heights these rows leave free — has dimension N − rank, which 002 eq. 16 estimates as
// N − Σ (n_F − 3) (exact when the rows are independent). Heights prescribed at some vertices
// (guides, isolated points) and the fairness energy of 002 eq. 17,
//   F = Σ_polylines Σ_i (z_i − 2 z_{i+1} + z_{i+2})²
// over the plan's straight polylines (with the plan fixed only the heights vary), fix the rest:
// the lift minimises F under the planarity rows and the prescribed heights (one KKT solve).

#include <Eigen/SparseCore>
#include <array>
#include <string>
#include <utility>
#include <vector>

#include "geometry/mesh_io.h"

namespace gproj {

struct MarionetteDesignSpace {
  int vertices = 0;        // N
  int planarity_rows = 0;  // Σ (n_F − 3)
  int estimate = 0;        // 002 eq. 16: N − Σ (n_F − 3)
  int rank = 0;            // of the planarity rows (sparse QR)
  int dimension = 0;       // N − rank: the heights the planarity leaves free
};

// The planarity rows as a matrix P (Σ (n_F − 3) × N): P z = 0 for planar faces. Throws
// InputError for a face whose plan points are all collinear (naming it).
Eigen::SparseMatrix<double> MarionettePlanarityMatrix(const PolyMesh& plan);

// Throws as MarionettePlanarityMatrix.
MarionetteDesignSpace MeasureMarionetteDesignSpace(const PolyMesh& plan);

// `dimension` vertices whose heights can be prescribed independently, every other height then
// following from the planarity rows (the non-pivot columns of a column-pivoted sparse QR): a
// choice of 002 Fig. 16's guide points.
std::vector<int> IndependentHeights(const PolyMesh& plan);

// The plan's straight polylines as triples (a, v, b): v between neighbours a and b whose edges
// continue each other within `max_turn_deg` in the plan (each triple once).
std::vector<std::array<int, 3>> StraightTriples(const PolyMesh& plan, double max_turn_deg = 30.0);

struct MarionettePolygonLift {
  PolyMesh mesh;  // the plan with the lifted heights as z
  MarionetteDesignSpace space;
  int fairness_triples = 0;
  double fairness = 0.0;          // F of 002 eq. 17 at the result
  double max_planarity = 0.0;     // largest distance of a face vertex from its plane, per mean edge
  double max_height_error = 0.0;  // at the prescribed vertices
};

// Lifts `plan` (its x, y; z ignored) with `heights` (vertex, z) prescribed. Throws InputError
// for a vertex index out of range or given twice, heights that are not finite, prescribed
// heights that no planar lift can meet, or heights that leave the lift undetermined (naming how
// many directions stay free: prescribe more, at least three not on a line).
MarionettePolygonLift LiftPolygonPlan(const PolyMesh& plan,
                                      const std::vector<std::pair<int, double>>& heights);

}  // namespace gproj
