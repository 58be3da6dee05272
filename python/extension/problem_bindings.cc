// gproj.Problem: the generic API (gproj/solver/problem.h) from Python — variable blocks, the
// built-in planarity, closeness and fairness terms, terms written in Python, and a solve by
// guided projection or by Ceres returning the summary as a dict.
#include <pybind11/numpy.h>
#include <pybind11/stl.h>

#include <cmath>
#include <memory>
#include <string>
#include <vector>

#include "gproj/common/input_error.h"
#include "gproj/constraints/closeness.h"
#include "gproj/constraints/polyline_fairness.h"
#include "gproj/constraints/quad_planarity.h"
#include "gproj/problems/run/guided_problem.h"
#include "gproj/solver/ceres_adapter.h"
#include "gproj/solver/guided_projection.h"
#include "python/extension/conversions.h"
#include "python/extension/module.h"
#include "python/extension/problem_solve.h"
#include "python/extension/python_term.h"
#include "python/extension/run_bridge.h"
#include "python/extension/solver_args.h"

namespace gproj::python {
namespace {

using IndexArray = py::array_t<long long, py::array::c_style | py::array::forcecast>;

// A Problem and the error slot its Python terms share.
struct PyProblem {
  Problem problem;
  std::shared_ptr<ErrorSlot> errors = std::make_shared<ErrorSlot>();

  const VariableBlock& Block(int b) const {
    if (b < 0 || b >= problem.layout().num_blocks())
      throw InputError("no block " + std::to_string(b) + " (the problem has " +
                       std::to_string(problem.layout().num_blocks()) + ")");
    return problem.layout().block(b);
  }
  void CheckName(const std::string& name) {
    if (name.empty() || problem.FindFamily(name) != nullptr)
      throw InputError("term name '" + name + "' is empty or already used");
  }
};

FamilyRole RoleOf(const std::string& role) {
  if (role == "constraint") return FamilyRole::kConstraint;
  if (role == "soft") return FamilyRole::kSoft;
  if (role == "fairness") return FamilyRole::kFairness;
  throw InputError("role must be constraint, soft or fairness, not '" + role + "'");
}

// An (m, k) index array, each index in [0, limit); `what` names it in messages.
std::vector<std::vector<int>> IndexRows(const py::object& value, int k, int limit,
                                        const std::string& what) {
  const py::array raw = py::array::ensure(value);
  if (!raw || (raw.dtype().kind() != 'i' && raw.dtype().kind() != 'u'))
    throw InputError(what + " must be an integer array");
  const IndexArray array(raw);
  if (array.ndim() != 2 || (k > 0 && array.shape(1) != k))
    throw InputError(what + " must have shape (m, " + (k > 0 ? std::to_string(k) : "k") + ")");
  const auto view = array.unchecked<2>();
  std::vector<std::vector<int>> rows(view.shape(0), std::vector<int>(view.shape(1)));
  for (py::ssize_t i = 0; i < view.shape(0); ++i)
    for (py::ssize_t j = 0; j < view.shape(1); ++j) {
      if (view(i, j) < 0 || view(i, j) >= limit)
        throw InputError(what + ": row " + std::to_string(i) + " has index " +
                         std::to_string(view(i, j)) + ", outside [0, " + std::to_string(limit) +
                         ")");
      rows[i][j] = static_cast<int>(view(i, j));
    }
  return rows;
}

// The items of `block` chosen by `value`, as indices into the block: None (all of them), a
// boolean mask of the block's length, or a 1-D integer array of indices; `what` names it.
std::vector<int> ChosenItems(const VariableBlock& block, const py::object& value,
                             const std::string& what) {
  std::vector<int> chosen;
  if (value.is_none()) {
    for (int i = 0; i < block.num_items; ++i) chosen.push_back(i);
    return chosen;
  }
  const py::array raw = py::array::ensure(value);
  if (!raw || raw.ndim() != 1 ||
      (raw.dtype().kind() != 'b' && raw.dtype().kind() != 'i' && raw.dtype().kind() != 'u'))
    throw py::type_error(
        what + ": expected None, a boolean mask of shape (" + std::to_string(block.num_items) +
        ",) or a 1-D integer array of item indices into block '" + block.name + "'");
  if (raw.dtype().kind() == 'b') {
    if (raw.shape(0) != block.num_items)
      throw InputError(what + ": a boolean mask of shape " + ShapeText(raw) + ", expected (" +
                       std::to_string(block.num_items) + ",) for block '" + block.name + "'");
    const auto mask = py::array_t<bool, py::array::c_style | py::array::forcecast>::ensure(raw);
    for (int i = 0; i < block.num_items; ++i)
      if (mask.data()[i]) chosen.push_back(i);
    return chosen;
  }
  const IndexArray array(raw);
  for (py::ssize_t i = 0; i < array.size(); ++i) {
    const long long index = array.data()[i];
    if (index < 0 || index >= block.num_items)
      throw InputError(what + ": index " + std::to_string(index) + " (position " +
                       std::to_string(i) + ") is outside block '" + block.name + "' of " +
                       std::to_string(block.num_items) + " items");
    chosen.push_back(static_cast<int>(index));
  }
  return chosen;
}

int AddBlock(PyProblem& p, const std::string& name, int items, int dim, bool eliminable) {
  if (items < 0 || dim < 1) throw InputError("a block needs items >= 0 and dim >= 1");
  if (name.empty() || p.problem.layout().FindBlock(name) >= 0)
    throw InputError("block name '" + name + "' is empty or already used");
  const int b = p.problem.layout().AddBlock(name, items, dim, eliminable);
  p.problem.ResizeToLayout();
  return b;
}

py::array_t<double> BlockValues(const PyProblem& p, int b) {
  const VariableBlock& block = p.Block(b);
  py::array_t<double> out({block.num_items, block.item_dim});
  std::copy_n(p.problem.x().data() + block.offset, block.size(), out.mutable_data());
  return out;
}

// `value` as (count, dim) float64 values for `count` items of the block (default: all of
// them): that exact shape ((count,) too when dim is 1), finite; a transposed or flattened
// array is refused naming `what`.
py::array_t<double, py::array::c_style> BlockArray(const VariableBlock& block,
                                                   const py::object& value, const std::string& what,
                                                   int count = -1) {
  if (count < 0) count = block.num_items;
  const std::string needs =
      "(" + std::to_string(count) + ", " + std::to_string(block.item_dim) + ") for " +
      (count == block.num_items ? "block '" + block.name + "'"
                                : "the chosen items of block '" + block.name + "'");
  const py::array raw = py::array::ensure(value);
  const char kind = raw ? raw.dtype().kind() : '?';
  if (!raw || (kind != 'f' && kind != 'i' && kind != 'u'))
    throw py::type_error(what + ": expected a float array of shape " + needs);
  const bool exact = raw.ndim() == 2 && raw.shape(0) == count && raw.shape(1) == block.item_dim;
  const bool column = block.item_dim == 1 && raw.ndim() == 1 && raw.shape(0) == count;
  if (!exact && !column)
    throw InputError(what + ": shape " + ShapeText(raw) + ", expected " + needs);
  const auto array = py::array_t<double, py::array::c_style | py::array::forcecast>::ensure(raw);
  for (py::ssize_t i = 0; i < array.size(); ++i)
    if (!std::isfinite(array.data()[i]))
      throw InputError(what + ": item " + std::to_string(i / block.item_dim) +
                       " has a non-finite value");
  return array;
}

void SetBlockValues(PyProblem& p, int b, const py::object& values) {
  const VariableBlock& block = p.Block(b);
  const auto array = BlockArray(block, values, "values");
  std::copy_n(array.data(), block.size(), p.problem.x().data() + block.offset);
}

py::array_t<int> Items(const PyProblem& p, int b) {
  const VariableBlock& block = p.Block(b);
  py::array_t<int> out(block.num_items);
  for (int i = 0; i < block.num_items; ++i) out.mutable_data()[i] = block.first_item + i;
  return out;
}

// Planarity of the quads `faces` of `vertex_block` with a new eliminable normal block
// (initialised from the diagonals at x); returns the normal block.
int AddPlanarity(PyProblem& p, int vertex_block, const py::object& faces, double weight,
                 const std::string& name) {
  const VariableBlock& vertices = p.Block(vertex_block);
  if (vertices.item_dim != 3) throw InputError("planarity needs a block of 3D points");
  p.CheckName(name);
  const auto quads = IndexRows(faces, 4, vertices.num_items, "faces");
  const int normals =
      AddBlock(p, name + "_normals", static_cast<int>(quads.size()), 3, /*eliminable=*/true);
  auto* planarity = p.problem.AddFamily<QuadPlanarity>(weight, name);
  const VariableLayout& layout = p.problem.layout();
  Eigen::VectorXd& x = p.problem.x();
  for (int f = 0; f < static_cast<int>(quads.size()); ++f) {
    int v[4];
    Eigen::Vector3d corner[4];
    for (int j = 0; j < 4; ++j) {
      v[j] = layout.Item(vertex_block, quads[f][j]);
      corner[j] = x.segment<3>(layout.ItemOffset(v[j]));
    }
    x.segment<3>(layout.Index(normals, f, 0)) =
        QuadPlanarity::InitialNormal(corner[0], corner[1], corner[2], corner[3]);
    planarity->AddQuad(layout.Item(normals, f), v[0], v[1], v[2], v[3]);
  }
  return normals;
}

// Closeness of the chosen items of the block (default: all) to targets (default: their values
// now).
void AddCloseness(PyProblem& p, int b, double weight, const std::string& name,
                  const std::string& role, const py::object& targets, const py::object& items) {
  const VariableBlock& block = p.Block(b);
  p.CheckName(name);
  const std::vector<int> chosen = ChosenItems(block, items, "items");
  const int count = static_cast<int>(chosen.size());
  std::vector<double> values(static_cast<size_t>(count) * block.item_dim);
  if (targets.is_none()) {
    for (int i = 0; i < count; ++i)
      std::copy_n(p.problem.x().data() + block.offset + chosen[i] * block.item_dim, block.item_dim,
                  values.data() + i * block.item_dim);
  } else {
    const auto given = BlockArray(block, targets, "targets", count);
    std::copy_n(given.data(), values.size(), values.data());
  }
  auto* closeness = p.problem.AddFamily<Closeness>(block.item_dim, weight, name, RoleOf(role));
  for (int i = 0; i < count; ++i)
    closeness->AddTarget(block.first_item + chosen[i], values.data() + i * block.item_dim);
}

// Holds the chosen items of the block (default: all) at their values (or releases them).
void Hold(PyProblem& p, int b, const py::object& items, bool held) {
  const VariableBlock& block = p.Block(b);
  if (block.eliminable)
    throw InputError("block '" + block.name +
                     "' is eliminable (per-element auxiliaries): its items cannot be held");
  for (int i : ChosenItems(block, items, "items"))
    p.problem.SetConstant(block.first_item + i, held);
}

py::array_t<bool> Held(const PyProblem& p, int b) {
  const VariableBlock& block = p.Block(b);
  py::array_t<bool> out(block.num_items);
  for (int i = 0; i < block.num_items; ++i)
    out.mutable_data()[i] = p.problem.IsConstant(block.first_item + i);
  return out;
}

void AddFairness(PyProblem& p, int b, const py::object& stencils, double weight,
                 const std::string& name) {
  const VariableBlock& block = p.Block(b);
  p.CheckName(name);
  const auto rows = IndexRows(stencils, 0, block.num_items, "stencils");
  const int order = rows.empty() ? 2 : static_cast<int>(rows[0].size()) - 1;
  if (order != 2 && order != 3)
    throw InputError("stencils must be (k, 3) (second differences) or (k, 4) (third)");
  auto* fairness = p.problem.AddFamily<PolylineFairness>(order, block.item_dim, weight, name);
  for (std::vector<int> row : rows) {
    for (int& i : row) i += block.first_item;
    fairness->AddElement(row);
  }
}

PythonTermSettings TermSettings(FamilyRole role, double weight, const std::string& jac,
                                bool check_jac, bool inequality) {
  PythonTermSettings settings;
  settings.role = role;
  settings.weight = weight;
  settings.derivatives = DerivativesFromName(jac);
  settings.check = check_jac;
  settings.inequality = inequality;
  return settings;
}

void CheckCallable(const py::object& function, const char* returns) {
  if (!PyCallable_Check(function.ptr()))
    throw py::type_error(std::string("function: expected a callable function(x, element) -> ") +
                         returns + ", not " +
                         std::string(py::str(py::type::handle_of(function).attr("__name__"))));
}

void AddPythonTerm(PyProblem& p, const std::string& name, const py::object& function, int rows,
                   const py::object& items, const std::string& role, double weight,
                   const std::string& jac, bool check_jac) {
  p.CheckName(name);
  if (rows < 1) throw InputError("a term has at least one row");
  CheckCallable(function, "values or (values, jacobian)");
  const VariableLayout& layout = p.problem.layout();
  const auto elements = IndexRows(items, 0, layout.num_items(), "items");
  auto* term = p.problem.AddFamily<PythonTerm>(
      name, rows, py::reinterpret_borrow<py::function>(function),
      TermSettings(RoleOf(role), weight, jac, check_jac, false), p.errors);
  for (const std::vector<int>& element : elements) {
    int local_dim = 0;
    for (int item : element) local_dim += layout.ItemDim(item);
    term->AddPythonElement(element, local_dim);
  }
}

// g(element's items) >= 0 per row, with a new eliminable block '<name>_slack' (one item of
// `rows` slacks per element); returns its id.
int AddPythonInequality(PyProblem& p, const std::string& name, const py::object& function, int rows,
                        const py::object& items, double weight, const std::string& jac,
                        bool check_jac) {
  p.CheckName(name);
  if (rows < 1) throw InputError("an inequality has at least one row");
  CheckCallable(function, "g or (g, jacobian)");
  const auto elements = IndexRows(items, 0, p.problem.layout().num_items(), "items");
  const int slacks = AddBlock(p, name + "_slack", static_cast<int>(elements.size()), rows,
                              /*eliminable=*/true);
  const VariableLayout& layout = p.problem.layout();
  auto* term = p.problem.AddFamily<PythonTerm>(
      name, rows, py::reinterpret_borrow<py::function>(function),
      TermSettings(FamilyRole::kConstraint, weight, jac, check_jac, true), p.errors);
  for (size_t e = 0; e < elements.size(); ++e) {
    std::vector<int> element = elements[e];
    int function_dim = 0;
    for (int item : element) function_dim += layout.ItemDim(item);
    element.push_back(layout.Item(slacks, static_cast<int>(e)));
    term->AddPythonElement(element, function_dim);
  }
  return slacks;
}

py::dict Solve(PyProblem& p, const std::string& solver, const py::object& callback,
               int max_iterations, double fairness, double epsilon, double soft_decay,
               double soft_floor, double soft_residual, double epsilon_min,
               double residual_tolerance, double step_tolerance, const std::string& linear_solver,
               int threads, double soft_scale, bool monotone, const std::string& step_control,
               bool shifted_constraints, double initial_soft_scale) {
  GenericSolveArgs args;
  SolverArgs{max_iterations, fairness,    epsilon,       soft_decay, soft_floor,
             soft_residual,  epsilon_min, linear_solver, threads}
      .ApplyTo(&args.gp);
  args.gp.residual_tolerance = residual_tolerance;
  args.gp.step_tolerance = step_tolerance;
  args.gp.monotone = monotone;
  if (!ParseStepControl(step_control, &args.gp.step_control))
    throw InputError("step_control must be 'dogleg' or 'damping', not '" + step_control + "'");
  args.gp.shifted_constraints = shifted_constraints;
  args.gp.initial_soft_scale = initial_soft_scale;
  std::string why;
  if (!args.gp.IsValid(&why)) throw InputError("invalid option: " + why);
  args.ceres.max_iterations = max_iterations;
  args.ceres.fairness_weight = fairness;
  args.ceres.soft_scale = soft_scale;
  args.ceres.num_threads = threads > 0 ? threads : 1;
  return SolveProblem(&p.problem, p.errors.get(), solver, callback, args);
}

// Problem.solve's guided projection defaults: the soft and fairness weights fade by half per
// iteration and with the constraint residual, and ε follows the residual down, so that a
// problem of constraints and closeness converges to the constraints (a fixed closeness weight
// would hold it at a balance above the tolerance).
SolverOptions ProblemSolveDefaults() {
  SolverOptions s;
  s.soft_weight_decay = 0.5;
  s.soft_weight_residual_factor = 1.0;
  s.epsilon_min = 1e-6;
  return s;
}

const char* const kProblemDoc = R"(A problem of your own: unknowns in named blocks, terms
(families of rows), solved by guided projection or Ceres from the same definitions.

    p = gproj.Problem()
    V = p.add_block("vertices", n, 3)          # block id; x grows by n * 3 zeros
    p.set_values(V, vertices)                   # (n, 3)
    p.add_planarity(V, quads)                   # quads: (m, 4) indices into the block
    p.add_closeness(V, weight=0.1)              # soft: stay near the current values
    p.hold(V, corners)                          # indices or a mask: these do not move
    def on_sphere(x, e):                        # a term written in Python; its jacobian
        return np.array([x @ x - 1.0])          # by complex step (or return (values, jac))
    p.add_term("on_sphere", on_sphere, 1, p.items(V)[:, None])
    p.add_inequality("above", lambda x, e: x[2:] - 0.1, 1, p.items(V)[:, None])  # z >= 0.1
    summary = p.solve()                         # or p.solve("ceres")
    p.values(V)                                 # (n, 3) result
)";

const char* const kAddTermDoc =
    R"(A term written in Python (for prototyping; every element calls back into Python).

    name: identifier of the term, unique in the problem (a key of the per-term residuals).
    function: function(x, element) -> values or (values, jacobian), where x: (d,) is the
        element's local vector (its items' scalars concatenated in order) and element: int its
        index; values: (rows,) and jacobian: (rows, d) (row-major) at x.
    rows: rows per element.
    items: (m, k) integer array of global item ids (see items()), one row per element.
    role: "constraint" (must vanish), "soft" (regulariser, fades with soft_decay) or
        "fairness" (weight omega_f^2 * weight, fades likewise).
    weight: the rows' weight.
    jac: "given" (the function returns (values, jacobian)), "cs" (it returns the values;
        the jacobian comes from complex-step differentiation: x is then complex128, so write
        the function with numpy operations that keep complex numbers, e.g. build arrays with
        dtype=x.dtype) or "auto" (decided by the function's first result: a 2-tuple is
        (values, jacobian)).
    check_jac: compare a given jacobian with complex-step (or, for a function that refuses
        complex input, central-difference) derivatives before the first solve; a mismatch
        raises ValueError naming the element and entry.

Before the first solve every element is probed once: its rows' sparsity comes from the
jacobian at the start and at a perturbed point (only the scalars a row depends on are stepped
and enter the solver's pattern), and complex-step derivatives are compared with central
differences, so that a function that drops imaginary parts is refused, not trusted.
An exception in the function stops the solve and is raised by solve().
)";

const char* const kAddInequalityDoc =
    R"(Inequalities g(x) >= 0 written in Python, one per row of every element.

    name, function, rows, items, weight, jac, check_jac: as for add_term; function(x, element)
        gives g (and its jacobian) at the element's local vector x (its items, not the slacks).

Each row becomes g - s^2 = 0 with a slack s, set to sqrt(max(g, 0)) at the start and at every
trial point, so that a bound pulls only where it is violated (Tang et al. 2014). Returns the id
of the new eliminable block '<name>_slack' ((m, rows) slacks). Ceres sees the same rows with
the slacks as free unknowns.
)";

const char* const kSolveDoc = R"(Solves in place (x holds the result afterwards).

    solver: "gp" (guided projection) or "ceres" (Levenberg-Marquardt on the same rows,
        weights fixed: soft and fairness rows times soft_scale).
    callback: None or callback(record: dict) with the keys of a report's history entries;
        returning False stops the solve. Ctrl-C stops it and raises KeyboardInterrupt.
    max_iterations, fairness (omega_f), epsilon, soft_decay, soft_floor, soft_residual,
        epsilon_min, linear_solver, threads: the solver options planarize and the other
        problems take, with the solver's own defaults (SolverOptions; each problem sets its
        own, e.g. fairness 1 for planarize, 0.5 for anet).
    residual_tolerance: gp converges when every constraint row has |phi| <= this.
    step_tolerance: gp converges when the step's max norm <= this.
    soft_scale: ceres only, factor on the soft and fairness weights.
    monotone: gp keeps a step only if it lowers the energy (else the step is shortened, see
        step_control).
    step_control: how gp shortens a monotone step that does not lower the energy: 'dogleg'
        (a trust region on the iteration's factorisation: a rejected trial costs an
        evaluation) or 'damping' (epsilon grows and the step is refactorised).
    shifted_constraints: gp moves the constraint rows' targets against their residuals after
        each step (Bregman iteration): the constraints then hold exactly with fixed soft
        weights.
    initial_soft_scale: gp's soft-weight factor at iteration 0 (small to continue from a
        converged state).
Problem.solve's schedule: soft and fairness weights times max(soft_decay^k, soft_floor), and
falling with the constraint residual (soft_residual), epsilon following it down to
epsilon_min, so that constraints plus closeness converge to the constraints; soft_decay=1
keeps fixed weights (a balance of the weighted objective).

Returns the summary as a dict: "solver", "termination", "message", "converged", "usable",
"iterations" (records), "objective" (1/2 sum w phi^2 + 1/2 omega_f^2 |P x|^2 at the result, fixed
weights) and the solver's own fields ("full_report", counts, times).
)";

}  // namespace

void BindGenericProblem(py::module_& m) {
  const SolverOptions d = ProblemSolveDefaults();
  py::class_<PyProblem>(m, "Problem", kProblemDoc)
      .def(py::init<>())
      .def("add_block", &AddBlock, py::arg("name"), py::arg("items"), py::arg("dim"),
           py::arg("eliminable") = false,
           "Returns the block id. Appends `items` "
           "items of `dim` scalars to x (zeros). eliminable: per-element auxiliaries, no row "
           "touches two of them (the solver may eliminate them first).")
      .def("values", &BlockValues, py::arg("block"),
           "A copy of the block's values, (items, dim) float64.")
      .def("set_values", &SetBlockValues, py::arg("block"), py::arg("values"),
           "Sets the block's values: (items, dim).")
      .def("items", &Items, py::arg("block"),
           "The block's global item ids, (items,) int32, for add_term's items.")
      .def_property(
          "x",
          [](const PyProblem& p) {
            return py::array_t<double>(p.problem.x().size(), p.problem.x().data());
          },
          [](PyProblem& p, const py::array_t<double, py::array::forcecast>& x) {
            if (x.size() != p.problem.x().size())
              throw InputError("x needs " + std::to_string(p.problem.x().size()) + " values");
            std::copy_n(x.data(), x.size(), p.problem.x().data());
          },
          "All unknowns, (n,) float64 (a copy; assign to set).")
      .def_property_readonly(
          "terms",
          [](const PyProblem& p) {
            std::vector<std::string> names;
            for (int i = 0; i < p.problem.num_families(); ++i)
              names.push_back(p.problem.family(i).name());
            return names;
          },
          "Names of the terms, in order.")
      .def("add_planarity", &AddPlanarity, py::arg("block"), py::arg("faces"),
           py::arg("weight") = 1.0, py::arg("name") = "planarity",
           "Quad planarity (004 §3.2): faces (m, 4) indices into `block` (3D points); adds the "
           "eliminable block '<name>_normals' of unit normals, initialised from the diagonals, and "
           "returns its id.")
      .def("add_closeness", &AddCloseness, py::arg("block"), py::arg("weight") = 1.0,
           py::arg("name") = "closeness", py::arg("role") = "soft", py::arg("targets") = py::none(),
           py::arg("items") = py::none(),
           "The chosen items of the block near their targets. items: None (all), a boolean mask "
           "(items,) or indices into the block; targets: (chosen, dim), default their values "
           "now. role 'soft' fades with the soft schedule; 'constraint' pulls them onto the "
           "targets exactly.")
      .def("hold", &Hold, py::arg("block"), py::arg("items") = py::none(), py::arg("held") = true,
           "Holds the chosen items of the block at their values (items: None for all, a "
           "boolean mask or indices into the block): the solve leaves them untouched bit for bit "
           "(Ceres: constant parameter blocks). held=False releases them. Items of eliminable "
           "blocks cannot be held.")
      .def("held", &Held, py::arg("block"), "Which items of the block are held, (items,) bool.")
      .def("add_fairness", &AddFairness, py::arg("block"), py::arg("stencils"),
           py::arg("weight") = 1.0, py::arg("name") = "fairness",
           "Polyline fairness: stencils (k, 3) item indices (second differences a - 2b + c) or (k, "
           "4) (third).")
      .def("add_term", &AddPythonTerm, py::arg("name"), py::arg("function"), py::arg("rows"),
           py::arg("items"), py::arg("role") = "constraint", py::arg("weight") = 1.0, py::kw_only(),
           py::arg("jac") = "auto", py::arg("check_jac") = true, kAddTermDoc)
      .def("add_inequality", &AddPythonInequality, py::arg("name"), py::arg("function"),
           py::arg("rows"), py::arg("items"), py::arg("weight") = 1.0, py::kw_only(),
           py::arg("jac") = "auto", py::arg("check_jac") = true, kAddInequalityDoc)
      .def("solve", &Solve, kSolveDoc, py::arg("solver") = "gp", py::kw_only(),
           py::arg("callback") = py::none(), py::arg("max_iterations") = d.max_iterations,
           py::arg("fairness") = d.fairness_weight, py::arg("epsilon") = d.epsilon,
           py::arg("soft_decay") = d.soft_weight_decay, py::arg("soft_floor") = d.soft_weight_floor,
           py::arg("soft_residual") = d.soft_weight_residual_factor,
           py::arg("epsilon_min") = d.epsilon_min,
           py::arg("residual_tolerance") = d.residual_tolerance,
           py::arg("step_tolerance") = d.step_tolerance,
           py::arg("linear_solver") = std::string(LinearSolverTypeName(d.linear_solver)),
           py::arg("threads") = d.num_threads, py::arg("soft_scale") = CeresOptions().soft_scale,
           py::arg("monotone") = d.monotone,
           py::arg("step_control") = std::string(StepControlName(d.step_control)),
           py::arg("shifted_constraints") = d.shifted_constraints,
           py::arg("initial_soft_scale") = d.initial_soft_scale);
}

}  // namespace gproj::python
