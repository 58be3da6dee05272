#include "python/extension/python_term.h"

#include <pybind11/numpy.h>

#include <cmath>
#include <limits>

#include "python/extension/conversions.h"

namespace gproj::python {

void ErrorSlot::RethrowIfAny() {
  if (!error) return;
  std::unique_ptr<py::error_already_set> raised = std::move(error);
  throw std::move(*raised);
}

PythonTerm::PythonTerm(std::string name, int rows, py::function function, FamilyRole role,
                       double weight, std::shared_ptr<ErrorSlot> errors)
    : ConstraintFamily(std::move(name), rows, role, weight),
      function_(std::move(function)),
      errors_(std::move(errors)) {}

PythonTerm::~PythonTerm() {
  // The family may be destroyed where the GIL is not held (a problem freed by C++).
  py::gil_scoped_acquire gil;
  function_ = py::function();
}

void PythonTerm::AddPythonElement(const std::vector<int>& items, int local_dim) {
  AddElement(items);
  local_dims_.push_back(local_dim);
}

void PythonTerm::EvaluateElement(int e, const double* x_local, double* phi, double* jac) const {
  py::gil_scoped_acquire gil;
  if (errors_->empty()) {
    try {
      if (PyErr_CheckSignals() != 0) throw py::error_already_set();
      Call(e, x_local, phi, jac);
      return;
    } catch (py::error_already_set& error) {
      errors_->error = std::make_unique<py::error_already_set>(std::move(error));
    } catch (const std::exception& error) {
      PyErr_SetString(PyExc_ValueError, error.what());
      errors_->error = std::make_unique<py::error_already_set>();
    }
  }
  const int d = local_dims_[e];
  for (int r = 0; r < rows_per_element(); ++r) {
    phi[r] = std::numeric_limits<double>::quiet_NaN();
    for (int l = 0; l < d; ++l) jac[r * d + l] = 0.0;
  }
}

void PythonTerm::Call(int e, const double* x_local, double* phi, double* jac) const {
  const int d = local_dims_[e];
  const int rows = rows_per_element();
  py::array_t<double> x(d);
  std::copy(x_local, x_local + d, x.mutable_data());
  const py::object result = function_(x, e);
  const std::string where = "term '" + name() + "', element " + std::to_string(e) + ": ";
  if (!py::isinstance<py::tuple>(result) || py::len(result) != 2)
    throw std::invalid_argument(where + "the function must return (values, jacobian)");
  const auto values = py::array_t<double, py::array::c_style | py::array::forcecast>::ensure(
      result.cast<py::tuple>()[0]);
  const auto jacobian = py::array_t<double, py::array::c_style | py::array::forcecast>::ensure(
      result.cast<py::tuple>()[1]);
  if (!values || values.ndim() > 1 || values.size() != rows)
    throw std::invalid_argument(where + "values must have shape (" + std::to_string(rows) +
                                ",), not " + (values ? ShapeText(values) : "a non-array"));
  // (rows, d) exactly, (d,) for one row: a transposed jacobian is refused.
  const bool exact =
      jacobian && jacobian.ndim() == 2 && jacobian.shape(0) == rows && jacobian.shape(1) == d;
  const bool one_row = jacobian && rows == 1 && jacobian.ndim() == 1 && jacobian.shape(0) == d;
  if (!exact && !one_row)
    throw std::invalid_argument(where + "the jacobian must have shape (" + std::to_string(rows) +
                                ", " + std::to_string(d) +
                                ") (rows x the element's scalars), not " +
                                (jacobian ? ShapeText(jacobian) : "a non-array"));
  std::copy(values.data(), values.data() + rows, phi);
  std::copy(jacobian.data(), jacobian.data() + rows * d, jac);
}

}  // namespace gproj::python
