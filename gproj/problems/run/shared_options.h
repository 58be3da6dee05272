#pragma once
// Option groups that several problems share, so that each has one name, doc, range and rule
// everywhere: the solver method and guided projection's options (the mesh problems' panel bounds
// and vertex control: problems/mesh/mesh_options.h). Each takes the schema and a function from
// the problem's settings to the struct it fills; the defaults stay those of the problem's own
// Options.

#include <string>
#include <utility>
#include <vector>

#include "gproj/problems/run/guided_problem.h"
#include "gproj/problems/run/option_schema.h"
#include "gproj/solver/guided_projection.h"

namespace gproj {

// A choice of solver stored as a SolverKind: `choices` pairs each value's text with its kind
// (SolverKindName, or a word of the problem's own such as "propagation" for kDirect).
template <typename S>
typename OptionSchema<S>::Builder AddSolverChoice(
    OptionSchema<S>* schema, const std::string& name, const std::string& doc,
    std::function<SolverKind&(S&)> field, std::vector<std::pair<std::string, SolverKind>> choices) {
  S defaults{};
  std::string default_text;
  std::vector<std::string> texts;
  for (const auto& [text, kind] : choices) {
    texts.push_back(text);
    if (kind == field(defaults)) default_text = text;
  }
  return schema
      ->Custom(name, OptionType::kChoice, doc, default_text,
               [field, choices](const nlohmann::json& value, S* s) {
                 for (const auto& choice : choices)
                   if (choice.first == value.get<std::string>()) field(*s) = choice.second;
               })
      .Choices(texts);
}

// "solver": gp (guided projection) or ceres (Levenberg–Marquardt on the same rows).
template <typename S>
void AddMethodOption(OptionSchema<S>* schema, std::function<SolverKind&(S&)> field) {
  AddSolverChoice<S>(
      schema, "solver",
      "gp: guided projection; ceres: Levenberg-Marquardt on the same rows (cross-check)", field,
      {{"gp", SolverKind::kGuidedProjection}, {"ceres", SolverKind::kCeres}});
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
                               "polylines; at vertices of polygon meshes that no polyline "
                               "passes, twice the offset from the neighbours' centroid)",
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
  schema
      ->Custom("step_control", OptionType::kChoice,
               "How a monotone step that does not lower the energy is shortened: dogleg (a "
               "trust region on the iteration's factor: a rejected trial costs an evaluation) or "
               "damping (epsilon grows and the step is refactorised)",
               StepControlName(solver(defaults).step_control),
               [solver](const nlohmann::json& value, S* s) {
                 ParseStepControl(value.get<std::string>(), &solver(*s).step_control);
               })
      .Choices({"dogleg", "damping"})
      .Group("solver");
}

}  // namespace gproj
