#pragma once
// Combescure transformations of quad meshes (000 §2.4–2.5): a mesh with the same connectivity
// and every edge parallel to the reference's. Circular meshes stay circular (angles are kept).
// Up to a translation, the lengths of the edges along one row and one column of a regular grid
// determine the whole parallel mesh (000 Fig. 3): each quad with two known sides gets its fourth
// vertex by intersecting the two lines parallel to the reference's other sides (000 eq. 4).
//
// Grids are in `gproj grid` order (see geometry/quad_grid.h): row polyline = vertices (0, j),
// column polyline = vertices (i, 0).

#include <Eigen/Core>
#include <string>
#include <vector>

#include "geometry/mesh_io.h"
#include "geometry/quad_grid.h"
#include "solver/guided_projection.h"
#include "solver/problem.h"

namespace gproj {

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
// it in one or two iterations (CombescureSolverOptions).
Problem MakeCombescureProblem(const PolyMesh& reference, const GridShape& shape,
                              const CombescureLengths& lengths);
SolverOptions CombescureSolverOptions();
// Writes the problem's vertices into a copy of the reference.
PolyMesh CombescureResult(const PolyMesh& reference, const Problem& problem);

struct ParallelismMeasures {
  double max_angle = 0.0;  // max over edges of the angle between the edge lines (radians)
  int worst_edge = -1;
  double min_length_ratio = 0.0;  // min over edges of signed length ratio new / reference
};
// Edge i of `mesh` against edge i of `reference` (same connectivity).
ParallelismMeasures MeasureParallelism(const PolyMesh& reference, const PolyMesh& mesh);

}  // namespace gproj
