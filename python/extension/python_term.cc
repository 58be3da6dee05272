#include "python/extension/python_term.h"

#include <pybind11/complex.h>
#include <pybind11/numpy.h>

#include <algorithm>
#include <cmath>
#include <complex>
#include <cstdio>
#include <limits>
#include <stdexcept>

#include "gproj/common/input_error.h"
#include "python/extension/conversions.h"

namespace gproj::python {
namespace {

using RealArray = py::array_t<double, py::array::c_style | py::array::forcecast>;
using ComplexArray = py::array_t<std::complex<double>, py::array::c_style | py::array::forcecast>;

constexpr double kComplexStep = 1e-30;
// Elements whose derivatives are compared (all up to this many, else an even spread).
constexpr int kCheckedElements = 200;

double MaxAbs(const std::vector<double>& values) {
  double worst = 0.0;
  for (double v : values) worst = std::max(worst, std::abs(v));
  return worst;
}

// The first (row, column) where `a` and `b` (rows × d) differ by more than tolerance × their
// scale; false when they agree.
bool FirstMismatch(const std::vector<double>& a, const std::vector<double>& b, int d,
                   double tolerance, int* row, int* column) {
  const double scale = std::max(MaxAbs(a), MaxAbs(b));
  for (size_t i = 0; i < a.size(); ++i)
    if (!(std::abs(a[i] - b[i]) <= tolerance * scale + 1e-12)) {
      *row = static_cast<int>(i) / d;
      *column = static_cast<int>(i) % d;
      return true;
    }
  return false;
}

std::string Number(double value) {
  char text[32];
  std::snprintf(text, sizeof(text), "%.6g", value);
  return text;
}

}  // namespace

void ErrorSlot::RethrowIfAny() {
  if (!error) return;
  std::unique_ptr<py::error_already_set> raised = std::move(error);
  throw std::move(*raised);
}

Derivatives DerivativesFromName(const std::string& name) {
  if (name == "auto") return Derivatives::kAuto;
  if (name == "given") return Derivatives::kGiven;
  if (name == "cs") return Derivatives::kComplexStep;
  throw InputError(
      "jac must be 'auto', 'given' (the function returns (values, jacobian)) or "
      "'cs' (complex-step derivatives of the values), not '" +
      name + "'");
}

PythonTerm::PythonTerm(std::string name, int rows, py::function function,
                       const PythonTermSettings& settings, std::shared_ptr<ErrorSlot> errors)
    : ConstraintFamily(std::move(name), rows, settings.role, settings.weight),
      function_(std::move(function)),
      settings_(settings),
      mode_(settings.derivatives),
      errors_(std::move(errors)) {}

PythonTerm::~PythonTerm() {
  // The family may be destroyed where the GIL is not held (a problem freed by C++).
  py::gil_scoped_acquire gil;
  function_ = py::function();
}

void PythonTerm::AddPythonElement(const std::vector<int>& items, int function_dim) {
  AddElement(items);
  function_dims_.push_back(function_dim);
}

std::string PythonTerm::Where(int e) const {
  return "term '" + name() + "', element " + std::to_string(e) + ": ";
}

py::object PythonTerm::CallFunction(const py::object& x, int e) const {
  py::object result = function_(x, e);
  if (mode_ == Derivatives::kAuto)
    mode_ = py::isinstance<py::tuple>(result) && py::len(result) == 2 ? Derivatives::kGiven
                                                                      : Derivatives::kComplexStep;
  return result;
}

void PythonTerm::ValuesOnly(int e, const double* x, double* values) const {
  const int d = function_dims_[e];
  RealArray xa(d);
  std::copy(x, x + d, xa.mutable_data());
  py::object result = CallFunction(xa, e);
  if (mode_ == Derivatives::kGiven) {
    if (!py::isinstance<py::tuple>(result) || py::len(result) != 2)
      throw std::invalid_argument(Where(e) + "the function must return (values, jacobian)");
    result = result.cast<py::tuple>()[0];
  }
  const RealArray array = RealArray::ensure(result);
  if (!array || array.ndim() > 1 || array.size() != rows_per_element())
    throw std::invalid_argument(Where(e) + "values must have shape (" +
                                std::to_string(rows_per_element()) + ",), not " +
                                (array ? ShapeText(array) : "a non-array"));
  std::copy(array.data(), array.data() + rows_per_element(), values);
}

void PythonTerm::ComplexStep(int e, const double* x, double* values, double* jac,
                             const std::vector<char>* columns) const {
  const int d = function_dims_[e], rows = rows_per_element();
  std::fill(jac, jac + rows * d, 0.0);
  bool have_values = false;
  ComplexArray xc(d);
  for (int j = 0; j < d; ++j) {
    if (columns && !(*columns)[j]) continue;
    std::complex<double>* z = xc.mutable_data();
    for (int l = 0; l < d; ++l) z[l] = x[l];
    z[j] += std::complex<double>(0.0, kComplexStep);
    py::object result = CallFunction(xc, e);
    if (py::isinstance<py::tuple>(result) && py::len(result) == 2) {
      if (mode_ != Derivatives::kGiven)
        throw std::invalid_argument(
            Where(e) + "with jac='cs' the function returns the values alone, not a tuple");
      result = result.cast<py::tuple>()[0];
    }
    const ComplexArray v = ComplexArray::ensure(result);
    if (!v || v.ndim() > 1 || v.size() != rows)
      throw std::invalid_argument(Where(e) + "values must have shape (" + std::to_string(rows) +
                                  ",), not " + (v ? ShapeText(v) : "a non-array"));
    for (int r = 0; r < rows; ++r) {
      jac[r * d + j] = v.data()[r].imag() / kComplexStep;
      if (!have_values) values[r] = v.data()[r].real();
    }
    have_values = true;
  }
  if (!have_values) ValuesOnly(e, x, values);
}

void PythonTerm::CentralDifferences(int e, const double* x, double* jac) const {
  const int d = function_dims_[e], rows = rows_per_element();
  double scale = 1e-8;
  for (int l = 0; l < d; ++l) scale = std::max(scale, std::abs(x[l]));
  std::vector<double> xp(x, x + d), plus(rows), minus(rows);
  for (int j = 0; j < d; ++j) {
    const double h = 1e-6 * scale;
    xp[j] = x[j] + h;
    ValuesOnly(e, xp.data(), plus.data());
    xp[j] = x[j] - h;
    ValuesOnly(e, xp.data(), minus.data());
    xp[j] = x[j];
    for (int r = 0; r < rows; ++r) jac[r * d + j] = (plus[r] - minus[r]) / (2.0 * h);
  }
}

void PythonTerm::Values(int e, const double* x, double* values, double* jac,
                        const std::vector<char>* columns) const {
  const int d = function_dims_[e], rows = rows_per_element();
  if (mode_ == Derivatives::kComplexStep) return ComplexStep(e, x, values, jac, columns);
  RealArray xa(d);
  std::copy(x, x + d, xa.mutable_data());
  const py::object result = CallFunction(xa, e);
  if (mode_ == Derivatives::kComplexStep) return ComplexStep(e, x, values, jac, columns);
  const char* hint = settings_.derivatives != Derivatives::kAuto
                         ? ""
                         : " (a function that returns a tuple gives (values, jacobian); return "
                           "the values as one array, or pass jac='cs', for computed "
                           "derivatives)";
  if (!py::isinstance<py::tuple>(result) || py::len(result) != 2)
    throw std::invalid_argument(Where(e) + "the function must return (values, jacobian)");
  const auto vals = RealArray::ensure(result.cast<py::tuple>()[0]);
  const auto jacobian = RealArray::ensure(result.cast<py::tuple>()[1]);
  if (!vals || vals.ndim() > 1 || vals.size() != rows)
    throw std::invalid_argument(Where(e) + "values must have shape (" + std::to_string(rows) +
                                ",), not " + (vals ? ShapeText(vals) : "a non-array") + hint);
  // (rows, d) exactly, (d,) for one row: a transposed jacobian is refused.
  const bool exact =
      jacobian && jacobian.ndim() == 2 && jacobian.shape(0) == rows && jacobian.shape(1) == d;
  const bool one_row = jacobian && rows == 1 && jacobian.ndim() == 1 && jacobian.shape(0) == d;
  if (!exact && !one_row)
    throw std::invalid_argument(Where(e) + "the jacobian must have shape (" + std::to_string(rows) +
                                ", " + std::to_string(d) +
                                ") (rows x the element's scalars), not " +
                                (jacobian ? ShapeText(jacobian) : "a non-array") + hint);
  std::copy(vals.data(), vals.data() + rows, values);
  std::copy(jacobian.data(), jacobian.data() + rows * d, jac);
}

bool PythonTerm::ComplexStepWorks(int e, const double* x, double* jac) const {
  const int d = function_dims_[e], rows = rows_per_element();
  std::vector<double> values(rows), differences(static_cast<size_t>(rows) * d);
  py::object warnings = py::module_::import("warnings");
  py::object quiet = warnings.attr("catch_warnings")();
  quiet.attr("__enter__")();
  bool works = true;
  try {
    warnings.attr("simplefilter")("ignore");
    ComplexStep(e, x, values.data(), jac, nullptr);
  } catch (py::error_already_set&) {
    works = false;
  } catch (const std::invalid_argument&) {
    works = false;
  }
  quiet.attr("__exit__")(py::none(), py::none(), py::none());
  if (!works) return false;
  // A function that keeps only real parts gives zeros: then differences decide.
  CentralDifferences(e, x, differences.data());
  int row = 0, column = 0;
  const std::vector<double> computed(jac, jac + rows * d);
  return !FirstMismatch(computed, differences, d, 1e-5, &row, &column);
}

void PythonTerm::PrepareDerivatives(const Problem& problem) {
  if (prepared_) return;
  const VariableLayout& layout = problem.layout();
  const int n = num_elements(), rows = rows_per_element();
  const int stride = std::max(1, n / kCheckedElements);
  pattern_.assign(n, {});
  columns_.assign(n, {});
  std::vector<double> x, xp, values(rows);
  for (int e = 0; e < n; ++e) {
    const int d = function_dims_[e];
    x.clear();
    for (int k = 0; k < element_num_items(e) && static_cast<int>(x.size()) < d; ++k) {
      const double* begin = problem.x().data() + layout.ItemOffset(element_items(e)[k]);
      x.insert(x.end(), begin, begin + layout.ItemDim(element_items(e)[k]));
    }
    double scale = 1.0;
    for (double v : x) scale = std::max(scale, std::abs(v));
    xp = x;
    for (int l = 0; l < d; ++l) xp[l] += 1e-3 * scale * (0.5 + 0.37 * ((l * 7 + e * 3) % 5) / 4.0);
    std::vector<double> j0(rows * d), j1(rows * d), reference(rows * d);
    try {
      Values(e, x.data(), values.data(), j0.data(), nullptr);
    } catch (py::error_already_set& error) {
      if (mode_ != Derivatives::kComplexStep || !error.matches(PyExc_TypeError)) throw;
      py::raise_from(error, PyExc_TypeError,
                     (Where(e) + "the function fails on a complex x: computed derivatives "
                                 "(jac='cs') call it with x + ih e_j, so write it with numpy "
                                 "operations that accept complex numbers, or return (values, "
                                 "jacobian)")
                         .c_str());
      throw py::error_already_set();
    }
    Values(e, xp.data(), values.data(), j1.data(), nullptr);
    const bool checked = e % stride == 0;
    int row = 0, column = 0;
    if (mode_ == Derivatives::kComplexStep && checked) {
      CentralDifferences(e, x.data(), reference.data());
      if (FirstMismatch(j0, reference, d, 1e-5, &row, &column))
        throw py::value_error(
            Where(e) + "complex-step derivative " + Number(j0[row * d + column]) + " of row " +
            std::to_string(row) + " by scalar " + std::to_string(column) +
            " disagrees with central differences (" + Number(reference[row * d + column]) +
            "): the function drops imaginary parts (float(), math.*, abs(), an array made "
            "without dtype=x.dtype); write it with numpy operations that keep complex numbers, "
            "or return (values, jacobian)");
    } else if (mode_ == Derivatives::kGiven && settings_.check && checked) {
      const char* method = "complex-step";
      double tolerance = 1e-8;
      if (!ComplexStepWorks(e, x.data(), reference.data())) {
        method = "central-difference";
        tolerance = 1e-5;
        CentralDifferences(e, x.data(), reference.data());
      }
      if (FirstMismatch(j0, reference, d, tolerance, &row, &column))
        throw py::value_error(Where(e) + "the given jacobian's entry (" + std::to_string(row) +
                              ", " + std::to_string(column) + ") is " +
                              Number(j0[row * d + column]) + ", the " + method + " derivative is " +
                              Number(reference[row * d + column]) +
                              ": fix the jacobian, pass jac='cs' to have it computed, or "
                              "check_jac=False");
    }
    pattern_[e].assign(rows * d, 0);
    columns_[e].assign(d, 0);
    for (int i = 0; i < rows * d; ++i)
      if (j0[i] != 0.0 || j1[i] != 0.0) pattern_[e][i] = 1, columns_[e][i % d] = 1;
  }
  prepared_ = true;
}

void PythonTerm::EvaluateElement(int e, const double* x_local, double* phi, double* jac) const {
  py::gil_scoped_acquire gil;
  const int d = function_dims_[e], rows = rows_per_element();
  const int local_dim = d + (settings_.inequality ? rows : 0);
  if (errors_->empty()) {
    try {
      if (PyErr_CheckSignals() != 0) throw py::error_already_set();
      thread_local std::vector<double> j;
      j.resize(static_cast<size_t>(rows) * d);
      Values(e, x_local, phi, j.data(), columns_.empty() ? nullptr : &columns_[e]);
      for (int r = 0; r < rows; ++r) {
        std::copy(j.begin() + r * d, j.begin() + (r + 1) * d, jac + r * local_dim);
        if (!settings_.inequality) continue;
        const double s = x_local[d + r];
        phi[r] -= s * s;
        for (int k = 0; k < rows; ++k) jac[r * local_dim + d + k] = k == r ? -2.0 * s : 0.0;
      }
      return;
    } catch (py::error_already_set& error) {
      errors_->error = std::make_unique<py::error_already_set>(std::move(error));
    } catch (const std::exception& error) {
      PyErr_SetString(PyExc_ValueError, error.what());
      errors_->error = std::make_unique<py::error_already_set>();
    }
  }
  for (int r = 0; r < rows; ++r) {
    phi[r] = std::numeric_limits<double>::quiet_NaN();
    for (int l = 0; l < local_dim; ++l) jac[r * local_dim + l] = 0.0;
  }
}

void PythonTerm::RowPattern(int e, const double* x_local, int local_dim, bool* touches) const {
  const int d = function_dims_[e];
  for (int r = 0; r < rows_per_element(); ++r)
    for (int l = 0; l < local_dim; ++l)
      touches[r * local_dim + l] = l < d ? pattern_.empty() || pattern_[e][r * d + l] : l - d == r;
}

void PythonTerm::Project(const VariableLayout& layout, Eigen::VectorXd* x) const {
  if (!settings_.inequality) return;
  py::gil_scoped_acquire gil;
  const int rows = rows_per_element();
  std::vector<double> local, g(rows);
  for (int e = 0; e < num_elements() && errors_->empty(); ++e) {
    const int slack = element_items(e)[element_num_items(e) - 1];
    local.clear();
    for (int k = 0; k + 1 < element_num_items(e); ++k) {
      const double* begin = x->data() + layout.ItemOffset(element_items(e)[k]);
      local.insert(local.end(), begin, begin + layout.ItemDim(element_items(e)[k]));
    }
    try {
      ValuesOnly(e, local.data(), g.data());
    } catch (py::error_already_set& error) {
      errors_->error = std::make_unique<py::error_already_set>(std::move(error));
      return;
    } catch (const std::exception& error) {
      PyErr_SetString(PyExc_ValueError, error.what());
      errors_->error = std::make_unique<py::error_already_set>();
      return;
    }
    for (int r = 0; r < rows; ++r)
      (*x)[layout.ItemOffset(slack) + r] =
          std::isfinite(g[r]) && g[r] > 0.0 ? std::sqrt(g[r]) : 0.0;
  }
}

}  // namespace gproj::python
