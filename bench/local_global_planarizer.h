#pragma once
// A prefactored local–global planariser, the method of ShapeOp (Bouaziz et al., "Shape-Up:
// Shaping Discrete Geometry with Projections", SGP 2012; Deuss et al., "ShapeOp — a robust and
// extensible geometric modelling paradigm", 2015), as the baseline of BM_PlanarizeLocalGlobal:
// ShapeOp itself is not packaged for Debian. It minimises
//   w_c Σ_v ‖v − v⁰‖² + Σ_f ‖(I − ¼ 11ᵀ) V_f − P_f‖²,
// P_f the quad's mean-centred vertices projected onto their best-fit plane (local step, per
// quad). The global matrix w_c I + Σ_f S_fᵀ (I − ¼ 11ᵀ) S_f is the same for x, y, z and for every
// iteration: CHOLMOD factors it once, and each iteration is one projection per quad and three
// back-substitutions. With w_c > 0 the fixed point is not exactly planar; a smaller w_c reaches
// a smaller planarity, more slowly.

#include <Eigen/Core>
#include <Eigen/SparseCore>
#include <array>
#include <memory>
#include <utility>
#include <vector>

#include "gproj/geometry/io/mesh_io.h"

namespace gproj {

class LocalGlobalPlanarizer {
 public:
  // `mesh` must be a pure quad mesh.
  LocalGlobalPlanarizer(const PolyMesh& mesh, double closeness_weight);
  ~LocalGlobalPlanarizer();

  // One local step (every quad's plane projection) and one global solve.
  void Iterate();
  // Max over quads of the distance between the diagonals / the mean edge length (the measure
  // of PQPlanarization).
  double MaxPlanarity() const;
  const Eigen::MatrixX3d& vertices() const { return v_; }

 private:
  struct Factor;
  std::vector<std::array<int, 4>> quads_;
  std::vector<std::pair<int, int>> edges_;
  Eigen::MatrixX3d v0_, v_, rhs_;
  Eigen::VectorXd column_, solved_;  // one coordinate of the right-hand side and of the solve
  double closeness_weight_;
  std::unique_ptr<Factor> factor_;
};

}  // namespace gproj
