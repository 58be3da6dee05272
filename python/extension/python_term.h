#pragma once
// A term written in Python (for prototyping): a constraint family whose elements are evaluated
// by a Python function giving the values and the Jacobian of an element's rows at its local
// vector. Guided projection and the Ceres cross-check both call it (the GIL is taken per
// element). An exception in the function (or a result of the wrong shape) is kept in the
// shared ErrorSlot, the element's rows become NaN (so the solver stops) and the caller raises
// it again once the solve has returned.

#include <pybind11/pybind11.h>

#include <memory>
#include <string>
#include <vector>

#include "gproj/solver/constraint_family.h"

namespace gproj::python {

namespace py = pybind11;

// The first error raised while solving, for the caller to raise again.
struct ErrorSlot {
  std::unique_ptr<py::error_already_set> error;
  bool empty() const { return !error; }
  // Raises the stored error (and clears the slot); needs the GIL.
  void RethrowIfAny();
};

class PythonTerm : public ConstraintFamily {
 public:
  // function(x_local: (d,) float64, element: int) -> (values: (rows,), jacobian: (rows, d)).
  PythonTerm(std::string name, int rows, py::function function, FamilyRole role, double weight,
             std::shared_ptr<ErrorSlot> errors);
  ~PythonTerm() override;

  // Appends an element touching `items` whose local vector has `local_dim` scalars.
  void AddPythonElement(const std::vector<int>& items, int local_dim);
  void EvaluateElement(int e, const double* x_local, double* phi, double* jac) const override;

 private:
  void Call(int e, const double* x_local, double* phi, double* jac) const;

  py::function function_;
  std::vector<int> local_dims_;
  std::shared_ptr<ErrorSlot> errors_;
};

}  // namespace gproj::python
