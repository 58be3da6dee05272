#include "gproj/problems/marionette/marionette_mesh_problem.h"

#include <algorithm>
#include <cmath>

#include "gproj/problems/mesh/planarity_measures.h"

namespace gproj::marionette {

SolverOptions MarionetteMeshSolverDefaults() {
  return MarionetteMeshSolverOptions(MarionetteProjection::kCylindrical);
}

bool MarionetteMeshOptions::IsValid(std::string* why) const {
  if (!(tolerance > 0.0) || !std::isfinite(tolerance) || solver.max_iterations < 1) {
    *why = "the tolerance must be > 0 and max_iterations ≥ 1";
    return false;
  }
  return solver.IsValid(why);
}

MarionetteMeshProblem::MarionetteMeshProblem(const MarionetteLines& lines,
                                             std::vector<MarionetteTarget> prescribed,
                                             const MarionetteMeshOptions& options)
    : lines_(lines),
      prescribed_(std::move(prescribed)),
      options_(options),
      problem_(MakeMarionetteMeshProblem(lines_, prescribed_)) {}

SolverOptions MarionetteMeshProblem::solver_options() const {
  return lines_.projection == MarionetteProjection::kVertical ? MarionetteSolverOptions()
                                                              : options_.solver;
}

CeresOptions MarionetteMeshProblem::ceres_options(int max_iterations) const {
  return CeresOptionsFor(options_.solver, max_iterations);
}

NamedValues MarionetteMeshProblem::MeasureAt(const Eigen::VectorXd& x) const {
  const int block = problem_.layout().FindBlock("parameters");
  const Eigen::VectorXd t = x.segment(problem_.layout().block(block).offset, lines_.num_vertices());
  double guide_error = 0.0;
  for (const MarionetteTarget& g : prescribed_)
    guide_error =
        std::max(guide_error, std::abs(t[g.vertex] - g.height) / (1 + std::abs(g.height)));
  const PolyMesh lifted = MarionetteLiftedMesh(lines_, t);
  const PlanarityMeasures m = MeasurePlanarity(lifted, lifted);
  return {{"max_relative_det", MaxLiftPlanarity(lines_, t)},
          {"max_guide_error", guide_error},
          {"max_planarity", m.max_planarity},
          {"mean_planarity", m.mean_planarity}};
}

bool MarionetteMeshProblem::MeetsTolerance(const NamedValues& m) const {
  return ValueOf(m, "max_relative_det") <= options_.tolerance &&
         ValueOf(m, "max_guide_error") <= options_.tolerance;
}

void MarionetteMeshProblem::SetParameters(const Eigen::VectorXd& t) {
  const int block = problem_.layout().FindBlock("parameters");
  problem_.x().segment(problem_.layout().block(block).offset, t.size()) = t;
}

}  // namespace gproj::marionette
