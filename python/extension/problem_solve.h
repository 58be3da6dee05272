#pragma once
// Problem.solve: guided projection or Ceres on a Problem, from Python.

#include <pybind11/pybind11.h>

#include <string>

#include "gproj/solver/ceres_adapter.h"
#include "gproj/solver/guided_projection.h"
#include "gproj/solver/problem.h"
#include "python/extension/python_term.h"

namespace gproj::python {

namespace py = pybind11;

struct GenericSolveArgs {
  SolverOptions gp;
  CeresOptions ceres;
};

// Solves `problem` in place with the GIL released (Python terms take it per element); every
// record goes to `callback` (a dict, as a report's history entry; False stops). Raises, once
// the solver has returned, what a Python term or the callback raised, or KeyboardInterrupt.
// Returns the summary as a dict.
py::dict SolveProblem(Problem* problem, ErrorSlot* errors, const std::string& solver,
                      const py::object& callback, const GenericSolveArgs& args);

}  // namespace gproj::python
