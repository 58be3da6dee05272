#pragma once
// The Marionette mesh problem (002 §2.4, §4.1) on the shared run protocol: a plan of any
// connectivity lifted on the lines of its projection from guide values, by guided projection on
// the rows of MakeMarionetteMeshProblem or by Ceres on the same rows. The direct lift
// (LiftMarionetteMesh's propagation) is set with SetParameters and reported by
// GuidedProblem::RunDirect (gproj/problems/marionette/marionette_run.h).

#include <Eigen/Core>
#include <string>
#include <vector>

#include "gproj/problems/marionette/marionette_mesh.h"
#include "gproj/problems/run/guided_problem.h"

namespace gproj::marionette {

// Guided projection's defaults for lifts on non-vertical lines (bilinear rows): 50 iterations,
// ε = 1e-3, rows solved to 1e-12.
SolverOptions MarionetteMeshSolverDefaults();

struct MarionetteMeshOptions {
  // Guided projection for non-vertical projections; vertical lifts are linear and take
  // MarionetteSolverOptions() (one iteration) instead.
  SolverOptions solver = MarionetteMeshSolverDefaults();
  // Max relative det (MaxLiftPlanarity) and max guide error (|t_v − value| / (1 + |value|)) to
  // reach.
  double tolerance = 1e-9;

  bool IsValid(std::string* why) const;
};

// Measures (the report's keys): max_relative_det, max_guide_error, and max_planarity,
// mean_planarity (diagonal distance / mean edge) of the lifted mesh; the tolerance bounds the
// first two. x starts at the plan's parameters with the prescribed values put in.
// Guided projection stops by the solver's own rules (rows to solver.residual_tolerance, the
// step, the iteration limit), not at the tolerance, so that the rows are solved to round-off:
// StopsAtTolerance() is false and the tolerance judges the final measures.
class MarionetteMeshProblem : public GuidedProblem {
 public:
  // `prescribed` from ResolveMarionetteGuides. Throws InputError (naming the face) for a
  // degenerate vertical plan quad.
  MarionetteMeshProblem(const MarionetteLines& lines, std::vector<MarionetteTarget> prescribed,
                        const MarionetteMeshOptions& options);

  Problem& problem() override { return problem_; }
  SolverOptions solver_options() const override;
  CeresOptions ceres_options(int max_iterations) const override;
  NamedValues MeasureAt(const Eigen::VectorXd& x) const override;
  bool MeetsTolerance(const NamedValues& m) const override;
  bool StopsAtTolerance() const override { return false; }

  // The line parameters t (#V) of the current x, and setting them (the normals stay).
  Eigen::VectorXd Parameters() const { return MarionetteMeshParameters(problem_); }
  void SetParameters(const Eigen::VectorXd& t);
  // The lifted mesh at the current parameters.
  PolyMesh Result() const { return MarionetteLiftedMesh(lines_, Parameters()); }

 private:
  MarionetteLines lines_;
  std::vector<MarionetteTarget> prescribed_;
  MarionetteMeshOptions options_;
  Problem problem_;
};

}  // namespace gproj::marionette
