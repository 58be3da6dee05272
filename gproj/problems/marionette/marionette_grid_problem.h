#pragma once
// The grid Marionette problem (002 §2–3) on the shared run protocol: the heights of a grid plan
// lifted from two guide curves, or fitted to target heights (002 eq. 14), by guided projection
// on the rows of MakeMarionetteProblem (linear: one iteration solves them) or by Ceres on the
// same rows. The direct solutions (propagation, the normal equations of the fit) are set with
// SetHeights and reported by GuidedProblem::RunDirect.

#include <Eigen/Core>
#include <string>

#include "gproj/geometry/io/mesh_io.h"
#include "gproj/problems/marionette/marionette.h"
#include "gproj/problems/run/guided_problem.h"

namespace gproj::marionette {

struct MarionetteOptions {
  // Guided projection: the rows are linear, so one iteration with a tiny ε solves a lift. A fit
  // is exact in that solve only up to the weight ratio of its target rows (1e-8): it takes two
  // more with shifted constraint targets (Bregman iteration, SolverOptions::shifted_constraints),
  // which make it the constrained least-squares solution of 002 eq. 14, planar to rounding.
  SolverOptions solver = MarionetteSolverOptions();
  // Max planarity (diagonal distance / mean edge) and, for a lift, max guide error
  // (|z_v − h_v| / (1 + |h_v|)) to reach.
  double tolerance = 1e-9;

  bool IsValid(std::string* why) const;
};

// Measures (the report's keys): max_planarity, mean_planarity, and max_guide_error for a lift or
// rms_distance_to_target for a fit (over the vertices with a target), with hard constraints
// also max_constraint_error (prescribed heights and max height in height units, the volume
// relative to max(1, |V|)). A lift meets the tolerance when planarity and guide error
// are within it. A fit is one least-squares solve that does not stop at the tolerance (x = 0 is
// planar): StopsAtTolerance() is false and the tolerance judges the final planarity.
// x (#V heights) starts at 0.
class MarionetteGridProblem : public GuidedProblem {
 public:
  // `mesh`: a grid plan (MakeMarionettePlan; `path` names it in messages). A lift takes `row`
  // (M + 1 heights of vertices (0, j)) and `column` (N + 1 of (i, 0)) and throws InputError as
  // LiftMarionette when they do not fit; a fit takes `target` (#V heights) and empty curves.
  MarionetteGridProblem(const PolyMesh& mesh, const std::string& path, const Eigen::VectorXd& row,
                        const Eigen::VectorXd& column, const Eigen::VectorXd& target,
                        const MarionetteOptions& options);

  Problem& problem() override { return problem_; }
  SolverOptions solver_options() const override { return options_.solver; }
  CeresOptions ceres_options(int max_iterations) const override;
  NamedValues MeasureAt(const Eigen::VectorXd& x) const override;
  bool MeetsTolerance(const NamedValues& m) const override;
  bool StopsAtTolerance() const override { return !fit(); }

  bool fit() const { return target_.size() > 0; }
  // A partial target (weight 0 where no height is given) and hard constraints for the direct
  // fit (FitMarionette's KKT system); guided projection and Ceres take the full target only.
  void SetFitConstraints(const Eigen::VectorXd& weights, const MarionetteConstraints& c);
  bool constrained() const { return weights_.size() > 0; }
  const MarionettePlan& plan() const { return plan_; }
  // The direct solution: LiftMarionette's propagation, or the fit by 002 eq. 14 (#V heights).
  Eigen::VectorXd DirectHeights() const;
  void SetHeights(const Eigen::VectorXd& z) { problem_.x() = z; }
  // The plan with its vertices at the current heights.
  PolyMesh Result() const;

 private:
  PolyMesh mesh_;
  MarionettePlan plan_;
  Eigen::VectorXd row_, column_, target_;
  Eigen::VectorXd weights_;  // empty: the full target, no constraints
  MarionetteConstraints constraints_;
  MarionetteOptions options_;
  Problem problem_;
};

}  // namespace gproj::marionette
