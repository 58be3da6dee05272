#pragma once
// Option groups that several problems share, so that each has one name, doc, range and rule
// everywhere: the solver method, guided projection's options, the panel bounds and the vertex
// control of the mesh problems. Each takes the schema and a function from the problem's settings
// to the struct it fills; the defaults stay those of the problem's own Options.

#include <string>

#include "problems/panel_bounds.h"
#include "problems/run/option_schema.h"
#include "problems/vertex_control.h"
#include "solver/guided_projection.h"

namespace gproj {

// "solver": gp (guided projection) or ceres (Levenberg–Marquardt on the same rows).
template <typename S>
void AddMethodOption(OptionSchema<S>* schema, std::function<std::string&(S&)> field) {
  schema
      ->template Field<std::string>(
          "solver", OptionType::kChoice,
          "gp: guided projection; ceres: Levenberg-Marquardt on the same rows (cross-check)", field)
      .Choices({"gp", "ceres"});
}

// max_iterations, fairness, soft_decay, soft_floor, soft_residual, epsilon, epsilon_min,
// linear_solver, threads, monotone (the solver's options a user tunes).
template <typename S>
void AddSolverOptions(OptionSchema<S>* schema, std::function<SolverOptions&(S&)> solver) {
  const auto field = [solver](auto member) {
    return [ solver, member ](S & s) -> auto& { return solver(s).*member; };
  };
  schema
      ->template Field<int>("max_iterations", OptionType::kInt, "Iterations at most",
                            field(&SolverOptions::max_iterations))
      .Range(0, 100000)
      .Group("solver");
  schema
      ->template Field<double>("fairness", OptionType::kNumber,
                               "omega_f: weight of the fairness (second differences along "
                               "polylines)",
                               field(&SolverOptions::fairness_weight))
      .NonNegative()
      .Group("solver");
  schema
      ->template Field<double>("soft_decay", OptionType::kNumber,
                               "Closeness and fairness weights are multiplied by this each "
                               "iteration ...",
                               field(&SolverOptions::soft_weight_decay))
      .Range(1e-12, 1.0)
      .Group("solver");
  schema
      ->template Field<double>("soft_floor", OptionType::kNumber,
                               "... down to this fraction of their initial value",
                               field(&SolverOptions::soft_weight_floor))
      .Range(0.0, 1.0)
      .Group("solver");
  schema
      ->template Field<double>("soft_residual", OptionType::kNumber,
                               "... and, when > 0, also by this times the max constraint residual "
                               "of the iteration (the soft weights vanish as the constraints "
                               "converge)",
                               field(&SolverOptions::soft_weight_residual_factor))
      .NonNegative()
      .Group("solver");
  schema
      ->template Field<double>("epsilon", OptionType::kNumber,
                               "epsilon: weight of the proximal term eps^2 |x - x^k|^2",
                               field(&SolverOptions::epsilon))
      .Positive()
      .Group("solver");
  schema
      ->template Field<double>("epsilon_min", OptionType::kNumber,
                               "When > 0, epsilon follows the constraint residual down to this "
                               "(quadratic convergence near the solution)",
                               field(&SolverOptions::epsilon_min))
      .NonNegative()
      .Group("solver");
  S defaults{};
  schema
      ->Custom("linear_solver", OptionType::kChoice,
               "Sparse Cholesky backend for gp: cholmod (supernodal) or eigen",
               LinearSolverTypeName(solver(defaults).linear_solver),
               [solver](const nlohmann::json& value, S* s) {
                 ParseLinearSolverType(value.get<std::string>(), &solver(*s).linear_solver);
               })
      .Choices({"cholmod", "eigen"})
      .Group("solver");
  schema
      ->template Field<int>("threads", OptionType::kInt, "Threads for BLAS / Ceres (0: default)",
                            field(&SolverOptions::num_threads))
      .Range(0, 256)
      .Group("solver");
  schema
      ->template Field<bool>("monotone", OptionType::kBool,
                             "Monotone steps: keep a step only if it lowers the energy, else damp "
                             "it (plain steps: take every Gauss-Newton step)",
                             field(&SolverOptions::monotone))
      .Negation("plain_steps")
      .Group("solver");
}

// min_angle, edge_length, allow_folds.
template <typename S>
void AddPanelBoundsOptions(OptionSchema<S>* schema, std::function<PanelBoundsOptions&(S&)> panels) {
  schema
      ->template Field<double>(
          "min_angle", OptionType::kNumber,
          "Every quad corner angle stays within [min_angle, 180 - min_angle] (a corner already "
          "outside in the input is kept from getting worse); 0 only keeps quads convex",
          [panels](S& s) -> double& { return panels(s).min_angle_deg; })
      .Range(0.0, 59.9)
      .Unit("deg")
      .Group("panels");
  schema
      ->Custom("edge_length", OptionType::kNumbers,
               "Every edge length stays within these (an edge outside in the input is kept from "
               "getting worse); without it no edge shrinks below 10% of its input length",
               nullptr,
               [panels](const nlohmann::json& value, S* s) {
                 panels(*s).min_edge_length = value[0].get<double>();
                 panels(*s).max_edge_length = value[1].get<double>();
               })
      .NonNegative()
      .Count(2, "MIN,MAX")
      .Unit("input units")
      .Group("panels");
  schema
      ->Custom("allow_folds", OptionType::kBool,
               "No corner-angle or default edge bounds: quads may turn non-convex or fold", false,
               [panels](const nlohmann::json& value, S* s) {
                 if (value.get<bool>()) panels(*s).AllowFolds();
               })
      .Group("panels");
}

// fix_boundary, glide_boundary (held vertices are the problem's "fixed" input).
template <typename S>
void AddVertexControlOptions(OptionSchema<S>* schema,
                             std::function<VertexControlOptions&(S&)> vertices) {
  schema
      ->template Field<bool>("fix_boundary", OptionType::kBool,
                             "Every boundary vertex stays where it is",
                             [vertices](S& s) -> bool& { return vertices(s).fix_boundary; })
      .Group("vertices");
  schema
      ->template Field<bool>("glide_boundary", OptionType::kBool,
                             "Boundary vertices slide along the input's boundary (they stay on "
                             "it to rounding)",
                             [vertices](S& s) -> bool& { return vertices(s).glide_boundary; })
      .Group("vertices");
}

}  // namespace gproj
