#pragma once
// Marionette meshes (002 §2–3): the plan view (x, y of every vertex) of a regular quad grid is
// fixed and only heights are unknown, so quad planarity is linear in the heights (002 eq. 2):
//   z_C = z_A + α (z_B − z_A) + β (z_D − z_A),  AC = α AB + β AD in the plan.
// (002 eq. 2 as printed has the wrong sign on its (z_B − z_A) term; see
// docs/families/marionette.md.) Planar height fields of an N × M-face grid form a vector space of
// dimension N + M + 1: the heights along one row and one column of vertices (the guide curves)
// determine the rest.

#include <Eigen/Core>
#include <string>
#include <utility>
#include <vector>

#include "gproj/geometry/io/mesh_io.h"
#include "gproj/solver/guided_projection.h"
#include "gproj/solver/problem.h"

namespace gproj::marionette {

// A regular grid of (rows + 1) × (cols + 1) vertices; vertex (i, j) has index i * (cols + 1) + j
// and face (i, j) is (i, j), (i+1, j), (i+1, j+1), (i, j+1).
struct MarionettePlan {
  int rows = 0, cols = 0;           // faces per direction (N, M)
  std::vector<Eigen::Vector2d> xy;  // (N + 1)(M + 1)
  // Per face: α, β of the plan (AC = α AB + β AD with A = (i, j), B = (i+1, j), D = (i, j+1)).
  std::vector<double> alpha, beta;

  int num_vertices() const { return static_cast<int>(xy.size()); }
  int Vertex(int i, int j) const { return i * (cols + 1) + j; }
};

// Builds the plan from x, y of a grid mesh in the vertex order above (as `gproj grid` writes).
// Throws InputError naming the face when the mesh is not such a grid, or when a face's plan view
// is degenerate (A, B, D collinear: no unique planar lift).
MarionettePlan MakeMarionettePlan(const PolyMesh& mesh, const std::string& path = "");

// The faces of a plan view (x, y of `mesh`'s quads) that are not convex or are turned over
// against the orientation of the majority: a lift over them overlaps itself, and its heights
// can blow up far beyond the guides'.
std::vector<int> FoldedPlanFaces(const PolyMesh& mesh);

// Refuses a plan view with FoldedPlanFaces (InputError naming `path` and the faces) unless
// `allow`; then returns a warning line naming them (empty when there are none).
std::string CheckPlanView(const PolyMesh& mesh, const std::string& path, bool allow);

// Direct lift by propagation, linear time: `row` holds the heights of vertices (0, j), j = 0..M,
// `column` those of (i, 0), i = 0..N; row[0] must equal column[0] (InputError otherwise).
// Returns all heights.
Eigen::VectorXd LiftMarionette(const MarionettePlan& plan, const Eigen::VectorXd& row,
                               const Eigen::VectorXd& column);

// The (N + 1)(M + 1) × (N + M + 1) matrix of 002 eq. 10 that maps the guide heights
// (row, then column without its first entry) to all heights (eq. 10 prints the size
// transposed).
Eigen::MatrixXd MarionetteGuideMatrix(const MarionettePlan& plan);

// The planarity rows (NM × (N + 1)(M + 1)) as a dense matrix: P z = 0 for planar lifts.
Eigen::MatrixXd MarionettePlanarityMatrix(const MarionettePlan& plan);

// The same lift as a gproj problem: one height item per vertex, a planarity row per face
// (constraint), and soft rows z_v − h_v for prescribed heights (guide curves, boundary heights,
// a target surface) with their own weights.
struct MarionetteTarget {
  int vertex;
  double height;
};
Problem MakeMarionetteProblem(const MarionettePlan& plan, const std::vector<MarionetteTarget>& hard,
                              const std::vector<MarionetteTarget>& soft, double hard_weight,
                              double soft_weight);

// Solver options for the linear problem: one iteration, tiny ε.
SolverOptions MarionetteSolverOptions();

// The least-squares fit of 002 eq. 14: the planar lift closest to the target heights z0 (one
// per vertex), from the guide matrix.
Eigen::VectorXd FitMarionette(const MarionettePlan& plan, const Eigen::VectorXd& z0);

// Hard linear constraints of 002 §3.3, met exactly by a fit.
struct MarionetteConstraints {
  std::vector<std::pair<int, double>> heights;  // (vertex, prescribed height)
  bool with_volume = false;
  double volume = 0.0;  // ∫ z dA over the plan (exact for planar faces: z is affine on each)
  bool with_max_height = false;
  double max_height = 0.0;  // z_v ≤ max_height at every vertex
  bool empty() const { return heights.empty() && !with_volume && !with_max_height; }
};

// ∫ z dA over the plan as a row over the heights (each planar face split into two triangles, on
// which z is affine: area × mean of the three heights); the plan's orientation counts positive.
Eigen::RowVectorXd MarionetteVolumeRow(const MarionettePlan& plan);

// The weighted fit with hard constraints: min Σ_v w_v (z_v − z0_v)² over planar lifts
// z = A z_p (002 eq. 12), w_v = 0 where no target is given (a partial target), subject to the
// constraints, solved exactly by the KKT system of the guide heights; max height by an active
// set (vertices at the bound join as equalities; one whose multiplier turns negative leaves).
// Throws InputError when targets and constraints leave guide heights free, or contradict each
// other or the bound.
Eigen::VectorXd FitMarionette(const MarionettePlan& plan, const Eigen::VectorXd& z0,
                              const Eigen::VectorXd& weights,
                              const MarionetteConstraints& constraints);

// A closed strip (002 §2.5): an inner and an outer closed polyline in the plan, N vertices each,
// quads (P_i, Q_i, Q_{i+1}, P_{i+1}) with indices mod N.
struct ClosedStrip {
  std::vector<Eigen::Vector2d> inner, outer;
};

// Lift of a closed strip from the heights Z of the inner curve. Propagating around the strip
// from z_0* (outer vertex 0) gives z_N* = V·Z + a z_0* (002 eq. 8); closing needs z_N* = z_0*.
// a is the product of the factors each quad applies to z*_i, the reciprocals of 002 eq. 18's
// a_i (Appendix A; a = 1 either way).
//   a ≠ 1: z_0* = V·Z / (1 − a), the only closing lift; the inner heights are kept.
//   a = 1 (|a − 1| ≤ tolerance, e.g. a plan with rotational symmetry): Z must satisfy V·Z = 0,
//          so it is projected onto that hyperplane (N − 1 free heights), and z_0* is free.
struct ClosedStripLift {
  double a = 0.0;
  Eigen::VectorXd v;  // N
  bool a_is_one = false;
  Eigen::VectorXd inner_heights;  // N: Z, projected when a = 1
  Eigen::VectorXd outer_heights;  // N
};
// The first quad of a closed strip whose plan view is degenerate (inner i, outer i and inner
// i + 1 collinear: no unique planar lift), or −1.
int DegenerateClosedStripQuad(const ClosedStrip& strip);

// Throws InputError naming the quad when a plan quad is degenerate.
ClosedStripLift LiftClosedStrip(const ClosedStrip& strip, const Eigen::VectorXd& inner_heights,
                                double outer0_when_free = 0.0, double tolerance = 1e-9);

// The lifted closed strip as a quad mesh: inner vertices 0..N−1, outer N..2N−1, quad i =
// (inner i, outer i, outer i+1, inner i+1).
PolyMesh ClosedStripMesh(const ClosedStrip& strip, const ClosedStripLift& lift);

}  // namespace gproj::marionette
