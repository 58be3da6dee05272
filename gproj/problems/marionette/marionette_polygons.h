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

#include <Eigen/Core>
#include <Eigen/SparseCore>
#include <array>
#include <string>
#include <utility>
#include <vector>

#include "gproj/geometry/io/mesh_io.h"

namespace gproj::marionette {

struct MarionetteDesignSpace {
  int vertices = 0;        // N
  int planarity_rows = 0;  // Σ (n_F − 3)
  int estimate = 0;        // 002 eq. 16: N − Σ (n_F − 3)
  int rank = 0;            // of the planarity rows (sparse QR)
  int dimension = 0;       // N − rank: the heights the planarity leaves free
};

// The planarity rows as a matrix P (Σ (n_F − 3) × N): P z = 0 for planar faces. Throws
// InputError for a face whose plan points are all collinear (naming it).
Eigen::SparseMatrix<double> PolygonPlanarityMatrix(const PolyMesh& plan);

// Throws as PolygonPlanarityMatrix.
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

// The heights at the target vertices nearest to `targets` (least squares) that a planar lift can
// have: the targets projected onto the lifts' space (002 §2.5: a closed strip whose plan has
// a = 1 takes only inner curves with V·Z = 0; eq. 9 for several rings). Unchanged when they are
// already reachable. Throws as LiftPolygonPlan for bad indices or values.
std::vector<std::pair<int, double>> NearestPlanarHeights(
    const PolyMesh& plan, const std::vector<std::pair<int, double>>& targets);

// Closed Marionette meshes of several rings (002 §2.5, Figs. 7–8, eq. 9): closed plan curves
// C_0 (inner, heights given) … C_R, N points each, ring r the closed strip between C_r and
// C_{r+1}. Each ring passes its outer heights to the next as its inner ones; a ring whose a
// (002 eq. 8) is not 1 closes in one way, a ring with a = 1 only for V·Z = 0. The inner heights
// are therefore projected onto what all rings can close (NearestPlanarHeights; unchanged when
// every a ≠ 1), and heights the rings leave free (the start of a ring with a = 1) are fixed by
// fairness (LiftPolygonPlan).
struct ClosedRingsLift {
  // Vertex c N + i: curve c, point i; quad (c, i), (c + 1, i), (c + 1, i + 1), (c, i + 1).
  PolyMesh mesh;
  std::vector<double> a, v_norm;  // per ring: a and |V| of 002 eq. 8 (from the plan alone)
  Eigen::VectorXd inner_heights;  // as lifted
  double inner_change = 0.0;      // max |lifted − given| on the inner curve
  double max_planarity = 0.0;     // per mean edge
};
// Throws InputError for fewer than 2 curves or 3 points, curves of different lengths, heights
// not one per inner point, or a degenerate plan quad (naming ring and quad).
ClosedRingsLift LiftClosedRings(const std::vector<std::vector<Eigen::Vector2d>>& curves,
                                const Eigen::VectorXd& inner_heights);

}  // namespace gproj::marionette
