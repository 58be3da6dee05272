#pragma once
// A term written in Python (for prototyping): a constraint family whose elements are evaluated
// by a Python function of an element's local vector. The function gives the rows' values and
// their Jacobian, or the values alone: then the Jacobian comes from complex-step
// differentiation (Squire & Trapp 1998: J e_j = Im f(x + i h e_j) / h with h = 1e-30, exact to
// rounding for analytic numpy code), one call per scalar the rows depend on. Before the first
// solve, Prepare() probes every element once: the Jacobian at the start and at a perturbed
// point gives the rows' sparsity (the solver's pattern, and the columns the complex step
// computes), a given Jacobian is compared with complex-step (or, for a function that refuses
// complex input, central-difference) derivatives, and complex-step derivatives with central
// differences, so that a function that drops imaginary parts is found before it misleads the
// solve.
//
// An inequality term (g(x) >= 0 per row) has one more item per element, its slacks (the last
// item; gproj/solver/inequality.h): its rows are g - s^2 and Project() sets s = sqrt(max(g, 0)).
//
// Guided projection and the Ceres cross-check both call the function (the GIL is taken per
// element). An exception in the function (or a result of the wrong shape) during a solve is
// kept in the shared ErrorSlot, the element's rows become NaN (so the solver stops) and the
// caller raises it again once the solve has returned.

#include <pybind11/pybind11.h>

#include <Eigen/Core>
#include <memory>
#include <string>
#include <vector>

#include "gproj/solver/constraint_family.h"
#include "gproj/solver/problem.h"

namespace gproj::python {

namespace py = pybind11;

// The first error raised while solving, for the caller to raise again.
struct ErrorSlot {
  std::unique_ptr<py::error_already_set> error;
  bool empty() const { return !error; }
  // Raises the stored error (and clears the slot); needs the GIL.
  void RethrowIfAny();
};

// How a term's Jacobian is obtained: kGiven, the function returns (values, jacobian); kComplexStep,
// it returns the values; kAuto, decided by the function's first result (a (values, jacobian)
// tuple, or values).
enum class Derivatives { kAuto, kGiven, kComplexStep };
// "auto", "given", "cs"; throws InputError for another name.
Derivatives DerivativesFromName(const std::string& name);

struct PythonTermSettings {
  FamilyRole role = FamilyRole::kConstraint;
  double weight = 1.0;
  Derivatives derivatives = Derivatives::kAuto;
  bool check = true;        // compare a given Jacobian with computed derivatives (Prepare)
  bool inequality = false;  // rows g >= 0, with a slack item per element
};

class PythonTerm : public ConstraintFamily {
 public:
  // function(x_local: (d,) float64 or complex128, element: int) -> values: (rows,) or
  // (values, jacobian: (rows, d)); d counts the element's items without the slacks.
  PythonTerm(std::string name, int rows, py::function function, const PythonTermSettings& settings,
             std::shared_ptr<ErrorSlot> errors);
  ~PythonTerm() override;

  // Appends an element touching `items` (for an inequality, its slack item last) whose
  // function sees the first `function_dim` scalars of its local vector.
  void AddPythonElement(const std::vector<int>& items, int function_dim);

  // The probe described above, with the GIL held, at the problem's x; raises ValueError
  // naming the term, element, row and column where derivatives disagree. Runs once.
  void PrepareDerivatives(const Problem& problem);

  void EvaluateElement(int e, const double* x_local, double* phi, double* jac) const override;
  void RowPattern(int e, const double* x_local, int local_dim, bool* touches) const override;
  void Project(const VariableLayout& layout, Eigen::VectorXd* x) const override;
  bool ShiftsTargets() const override { return !settings_.inequality; }

  bool inequality() const { return settings_.inequality; }

 private:
  // The function's values (rows) and Jacobian (rows × d, row-major) at x (d = function_dim(e)),
  // by the term's derivatives; `columns` (null: all) limits the complex step to the scalars
  // the rows depend on. Throws on a bad result (the caller handles the GIL and errors).
  void Values(int e, const double* x, double* values, double* jac,
              const std::vector<char>* columns) const;
  // Values only (the slacks' projection).
  void ValuesOnly(int e, const double* x, double* values) const;
  void ComplexStep(int e, const double* x, double* values, double* jac,
                   const std::vector<char>* columns) const;
  void CentralDifferences(int e, const double* x, double* jac) const;
  // Complex-step derivatives at x into jac when the function takes complex input and they agree
  // with central differences (warnings silenced); false otherwise.
  bool ComplexStepWorks(int e, const double* x, double* jac) const;
  py::object CallFunction(const py::object& x, int e) const;
  std::string Where(int e) const;

  py::function function_;
  PythonTermSettings settings_;
  mutable Derivatives mode_;
  std::vector<int> function_dims_;
  std::vector<std::vector<char>> pattern_;  // per element, rows × d (probed), empty: not yet
  std::vector<std::vector<char>> columns_;  // per element, d: any row depends on the scalar
  bool prepared_ = false;
  std::shared_ptr<ErrorSlot> errors_;
};

}  // namespace gproj::python
