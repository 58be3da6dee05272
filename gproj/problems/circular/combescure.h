#pragma once
// Combescure transformations of quad meshes (000 §2.4–2.5): a mesh with the same connectivity
// and every edge parallel to the reference's. Circular meshes stay circular (angles are kept).
// Up to a translation, the lengths of the edges along one row and one column of a regular grid
// determine the whole parallel mesh (000 Fig. 3): each quad with two known sides gets its fourth
// vertex by intersecting the two lines parallel to the reference's other sides (000 eq. 4).
//
// Grids are in `gproj grid` order (see gproj/geometry/mesh/quad_grid.h): row polyline = vertices
// (0, j), column polyline = vertices (i, 0).

#include <Eigen/Core>
#include <string>
#include <vector>

#include "gproj/geometry/io/mesh_io.h"
#include "gproj/geometry/mesh/quad_grid.h"
#include "gproj/problems/run/guided_problem.h"
#include "gproj/solver/problem.h"

namespace gproj::circular {

struct CombescureLengths {
  // Signed lengths of the new mesh's edges (0, j) → (0, j + 1), j = 0..cols − 1 (positive: the
  // reference's direction; negative: reversed).
  std::vector<double> row;
  // Signed lengths of the edges (i, 0) → (i + 1, 0), i = 0..rows − 1.
  std::vector<double> column;
  // Position of vertex (0, 0) in the new mesh.
  Eigen::Vector3d origin = Eigen::Vector3d::Zero();
};

// The lengths of the reference itself (so that the transformation is the identity), each
// multiplied by `scale`.
CombescureLengths ReferenceLengths(const PolyMesh& reference, const GridShape& shape,
                                   double scale = 1.0);

// Checks that the reference can carry a Combescure transformation: quads planar to `tolerance`
// (diagonal distance / mean edge length) and no two adjacent sides parallel. Checks the length
// counts against the grid. Throws InputError naming the face or the list.
void CheckCombescureInput(const PolyMesh& reference, const GridShape& shape,
                          const CombescureLengths& lengths, double tolerance = 1e-6);

// Propagation (000 eq. 4), linear in the number of faces. Calls CheckCombescureInput.
PolyMesh CombescureByPropagation(const PolyMesh& reference, const GridShape& shape,
                                 const CombescureLengths& lengths, double tolerance = 1e-6);

// The same as a gproj problem: one vertex item per vertex (x starts at the reference moved to
// the origin), edge-parallelism rows for every edge, edge-vector rows along the row and column
// polylines, and vertex (0, 0) held at the origin. The problem is linear, so the solver reaches
// it in one or two iterations (CombescureSolverDefaults). Calls CheckCombescureInput.
Problem MakeCombescureProblem(const PolyMesh& reference, const GridShape& shape,
                              const CombescureLengths& lengths, double tolerance = 1e-6);

// Guided projection's defaults for Combescure: the rows are linear, so each step solves the
// regularised least squares exactly and the proximal term ε² = 1e-12 shrinks the remaining
// error by ~ε² per step: 5 iterations at most, stopping at max |φ| ≤ 1e-11.
SolverOptions CombescureSolverDefaults();

struct CombescureOptions {
  // Guided projection (Run); RunPropagation does not use it.
  SolverOptions solver = CombescureSolverDefaults();
  // Largest planarity of the reference accepted (diagonal distance / mean edge length).
  double reference_tolerance = 1e-6;
  // Converged when the max edge-parallelism angle (radians) and the max guide error (per mean
  // guide length) are ≤ this. One step leaves ~1e-9 of an O(1) error, so guided projection
  // takes its second step as its own residual rule does; rounding stays below this while the
  // coordinates are under ~1e4 mean edge lengths.
  double tolerance = 1e-11;
  // The same bound for a propagation, whose only error is rounding.
  double propagation_tolerance = 1e-8;
  bool IsValid(std::string* why) const;
};

struct ParallelismMeasures {
  double max_angle = 0.0;  // max over edges of the angle between the edge lines (radians)
  int worst_edge = -1;
  double min_length_ratio = 0.0;  // min over edges of signed length ratio new / reference
};
// Edge i of `mesh` against edge i of `reference` (same connectivity).
ParallelismMeasures MeasureParallelism(const PolyMesh& reference, const PolyMesh& mesh);

// A Combescure transformation as a guided problem. Run() is guided projection on the rows of
// MakeCombescureProblem, RunCeres() the Ceres cross-check on the same rows, RunPropagation()
// the direct construction (000 eq. 4); each leaves the result in problem().x().
class Combescure : public GuidedProblem {
 public:
  // Throws InputError (CheckCombescureInput, invalid options).
  Combescure(const PolyMesh& reference, const GridShape& shape, const CombescureLengths& lengths,
             const CombescureOptions& options);

  Problem& problem() override { return problem_; }
  SolverOptions solver_options() const override { return options_.solver; }
  CeresOptions ceres_options(int max_iterations) const override;
  // MeasureCircularMesh's measures of the iterate, and against the reference:
  // max_edge_parallelism_angle, worst_parallel_edge, min_edge_length_ratio; max_guide_error:
  // the largest distance of a row or column edge vector (and of vertex (0, 0)) from the one
  // asked, per mean asked length.
  NamedValues MeasureAt(const Eigen::VectorXd& x) const override;
  bool MeetsTolerance(const NamedValues& m) const override {
    return WithinTolerance(m, options_.tolerance);
  }

  // Propagation instead of guided projection (solver "propagation", no iterations); converged
  // when the measures are within options.propagation_tolerance.
  RunReport RunPropagation();
  // The current vertices as a mesh.
  PolyMesh Result() const { return MeshAt(problem_.x()); }

 private:
  static bool WithinTolerance(const NamedValues& m, double tolerance);
  int VertexOffset(int v) const;  // of vertex v's item in x
  PolyMesh MeshAt(const Eigen::VectorXd& x) const;
  double GuideErrorAt(const PolyMesh& mesh) const;

  CombescureOptions options_;
  PolyMesh reference_;
  GridShape shape_;
  CombescureLengths lengths_;
  Problem problem_;
};

}  // namespace gproj::circular
