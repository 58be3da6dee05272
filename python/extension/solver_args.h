#pragma once
// Guided projection's options as keyword arguments, shared by every problem function: the
// command line's --max-iterations, --fairness, --epsilon, --soft-decay, --soft-floor,
// --soft-residual, --epsilon-min, --linear-solver and --threads, with the problem's own defaults in
// the signature.

#include <pybind11/pybind11.h>

#include <string>
#include <tuple>

#include "gproj/solver/guided_projection.h"

namespace gproj::python {

namespace py = pybind11;

struct SolverArgs {
  int max_iterations = 0;
  double fairness = 0.0, epsilon = 0.0, soft_decay = 0.0, soft_floor = 0.0;
  double soft_residual = 0.0, epsilon_min = 0.0;
  std::string linear_solver;
  int threads = 0;
  // Sets the options; InputError for a value the command line would refuse.
  void ApplyTo(SolverOptions* options) const;
};

// The keyword arguments with `defaults`' values, in SolverArgs' order.
inline auto SolverArgList(const SolverOptions& defaults) {
  return std::make_tuple(
      py::arg("max_iterations") = defaults.max_iterations,
      py::arg("fairness") = defaults.fairness_weight, py::arg("epsilon") = defaults.epsilon,
      py::arg("soft_decay") = defaults.soft_weight_decay,
      py::arg("soft_floor") = defaults.soft_weight_floor,
      py::arg("soft_residual") = defaults.soft_weight_residual_factor,
      py::arg("epsilon_min") = defaults.epsilon_min,
      py::arg("linear_solver") = std::string(LinearSolverTypeName(defaults.linear_solver)),
      py::arg("threads") = defaults.num_threads);
}

// Their description, for docstrings.
extern const char* const kSolverArgsDoc;

// Defines `name` on `module` with the function, its docstring and `args` (a tuple of py::arg).
template <typename Function, typename Args>
void DefineFunction(py::module_& module, const char* name, Function function, const char* doc,
                    const Args& args) {
  std::apply([&](const auto&... arg) { module.def(name, function, doc, arg...); }, args);
}

}  // namespace gproj::python
