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
//
// With an Anderson depth m > 0 the iteration is accelerated as in Peng et al., "Anderson
// Acceleration for Geometry Optimization and Physics Simulation" (SIGGRAPH 2018): the
// local–global map G (a local step at x, then the global solve) is a fixed-point map, and the
// next point is the combination of the last m + 1 images G(x_i) whose residuals G(x_i) − x_i
// combine to the least norm. The accelerated point is kept when its energy (the objective
// above, each quad's projection taken at the point) is below the last accepted one; otherwise
// the plain image G(x), whose energy never rises, is taken and the history is cleared.

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
  LocalGlobalPlanarizer(const PolyMesh& mesh, double closeness_weight, int anderson_depth = 0);
  ~LocalGlobalPlanarizer();

  // One local step (every quad's plane projection) and one global solve; with Anderson
  // acceleration, the accelerated point or, when its energy is not lower, the plain one.
  void Iterate();
  // The objective at the current vertices; Anderson steps taken and rejected so far.
  double Energy() const { return energy_; }
  int accepted() const { return accepted_; }
  int rejected() const { return rejected_; }
  // Max over quads of the distance between the diagonals / the mean edge length (the measure
  // of PQPlanarization).
  double MaxPlanarity() const;
  const Eigen::MatrixX3d& vertices() const { return v_; }

 private:
  struct Factor;
  // Each quad's plane projection at x into rhs_ (with the closeness part); the energy at x.
  double LocalStep(const Eigen::MatrixX3d& x);
  // The global solve of rhs_ into *x.
  void GlobalStep(Eigen::MatrixX3d* x);
  void IterateAnderson();

  std::vector<std::array<int, 4>> quads_;
  std::vector<std::pair<int, int>> edges_;
  Eigen::MatrixX3d v0_, v_, rhs_;
  Eigen::VectorXd column_, solved_;  // one coordinate of the right-hand side and of the solve
  double closeness_weight_;
  std::unique_ptr<Factor> factor_;
  double energy_ = 0.0;  // at v_, with rhs_ holding v_'s local step
  // Anderson: depth, the last image and residual, and the differences of the last m of each
  // (columns, flattened vertices).
  int depth_ = 0, accepted_ = 0, rejected_ = 0, history_ = 0, next_column_ = 0;
  bool has_last_ = false;               // last_image_ and last_residual_ hold a step
  Eigen::MatrixX3d image_, candidate_;  // G(v_) and the accelerated point
  Eigen::VectorXd residual_, last_image_, last_residual_;
  Eigen::MatrixXd image_changes_, residual_changes_;
};

}  // namespace gproj
