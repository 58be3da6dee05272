#include "gproj/problems/marionette/marionette_grid_problem.h"

#include <algorithm>
#include <cmath>
#include <vector>

#include "gproj/common/input_error.h"
#include "gproj/problems/mesh/planarity_measures.h"

namespace gproj::marionette {
namespace {

// The plan with its vertices at heights z.
PolyMesh WithHeights(const PolyMesh& plan, const Eigen::VectorXd& z) {
  PolyMesh out = plan;
  for (auto v : out.vertices()) {
    auto p = out.point(v);
    p[2] = z[v.idx()];
    out.set_point(v, p);
  }
  return out;
}

}  // namespace

bool MarionetteOptions::IsValid(std::string* why) const {
  if (!(tolerance > 0.0) || !std::isfinite(tolerance)) {
    *why = "the tolerance must be finite and > 0";
    return false;
  }
  return solver.IsValid(why);
}

MarionetteGridProblem::MarionetteGridProblem(const PolyMesh& mesh, const std::string& path,
                                             const Eigen::VectorXd& row,
                                             const Eigen::VectorXd& column,
                                             const Eigen::VectorXd& target,
                                             const MarionetteOptions& options)
    : mesh_(mesh),
      plan_(MakeMarionettePlan(mesh, path)),
      row_(row),
      column_(column),
      target_(target),
      options_(options) {
  std::vector<MarionetteTarget> hard, soft;
  if (fit()) {
    if (target.size() != plan_.num_vertices())
      throw InputError("the target needs " + std::to_string(plan_.num_vertices()) +
                       " heights, got " + std::to_string(target.size()));
    for (int v = 0; v < plan_.num_vertices(); ++v) soft.push_back({v, target[v]});
  } else {
    LiftMarionette(plan_, row, column);  // throws for curves that do not fit
    for (int j = 0; j <= plan_.cols; ++j) hard.push_back({plan_.Vertex(0, j), row[j]});
    for (int i = 1; i <= plan_.rows; ++i) hard.push_back({plan_.Vertex(i, 0), column[i]});
  }
  problem_ = MakeMarionetteProblem(plan_, hard, soft, 1.0, 1e-8);
  if (fit()) {
    options_.solver.shifted_constraints = true;
    options_.solver.max_iterations = std::max(options_.solver.max_iterations, 3);
  }
}

CeresOptions MarionetteGridProblem::ceres_options(int max_iterations) const {
  return CeresOptionsFor(options_.solver, max_iterations);
}

NamedValues MarionetteGridProblem::MeasureAt(const Eigen::VectorXd& z) const {
  const PolyMesh lifted = WithHeights(mesh_, z);
  const PlanarityMeasures m = MeasurePlanarity(lifted, lifted);
  NamedValues values = {{"max_planarity", m.max_planarity}, {"mean_planarity", m.mean_planarity}};
  if (fit()) {
    if (!constrained()) {
      values.push_back(
          {"rms_distance_to_target", std::sqrt((z - target_).squaredNorm() / z.size())});
      return values;
    }
    const Eigen::ArrayXd d = (z - target_).array() * weights_.array();
    values.push_back(
        {"rms_distance_to_target", std::sqrt(d.square().sum() / std::max(1.0, weights_.sum()))});
    double error = 0.0;
    for (const auto& [v, h] : constraints_.heights) error = std::max(error, std::abs(z[v] - h));
    if (constraints_.with_volume)
      error = std::max(error, std::abs(MarionetteVolumeRow(plan_).dot(z) - constraints_.volume) /
                                  std::max(1.0, std::abs(constraints_.volume)));
    if (constraints_.with_max_height)
      error = std::max(error, z.maxCoeff() - constraints_.max_height);
    values.push_back({"max_constraint_error", error});
    return values;
  }
  double error = 0.0;
  for (int j = 0; j <= plan_.cols; ++j)
    error = std::max(error, std::abs(z[plan_.Vertex(0, j)] - row_[j]) / (1 + std::abs(row_[j])));
  for (int i = 0; i <= plan_.rows; ++i)
    error =
        std::max(error, std::abs(z[plan_.Vertex(i, 0)] - column_[i]) / (1 + std::abs(column_[i])));
  values.push_back({"max_guide_error", error});
  return values;
}

bool MarionetteGridProblem::MeetsTolerance(const NamedValues& m) const {
  if (constrained() && ValueOf(m, "max_constraint_error") >
                           options_.tolerance * (1.0 + target_.cwiseAbs().maxCoeff()))
    return false;
  return ValueOf(m, "max_planarity") <= options_.tolerance &&
         (fit() || ValueOf(m, "max_guide_error") <= options_.tolerance);
}

void MarionetteGridProblem::SetFitConstraints(const Eigen::VectorXd& weights,
                                              const MarionetteConstraints& c) {
  if (!fit() || weights.size() != plan_.num_vertices())
    throw InputError("hard constraints and weights need a fit with one weight per vertex");
  weights_ = weights;
  constraints_ = c;
}

Eigen::VectorXd MarionetteGridProblem::DirectHeights() const {
  if (constrained()) return FitMarionette(plan_, target_, weights_, constraints_);
  return fit() ? FitMarionette(plan_, target_) : LiftMarionette(plan_, row_, column_);
}

PolyMesh MarionetteGridProblem::Result() const { return WithHeights(mesh_, problem_.x()); }

}  // namespace gproj::marionette
