// The registry's problems as Python functions, generated from their specs: required mesh inputs
// as positional (V, F) arrays, optional inputs and options as keyword arguments named as in the
// schema (defaults, ranges and docs from it), `callback` for the iteration records; and
// gproj.schema(), the same document as `gproj schema`.
#include <pybind11/numpy.h>
#include <pybind11/stl.h>

#include <string>

#include "problems/run/registry.h"
#include "python/conversions.h"
#include "python/module.h"
#include "python/run_bridge.h"

namespace gproj::python {
namespace {

[[noreturn]] void TypeError(const std::string& message) {
  PyErr_SetString(PyExc_TypeError, message.c_str());
  throw py::error_already_set();
}

std::string TypeNameOf(const py::handle& value) {
  return py::str(py::type::handle_of(value).attr("__name__"));
}

// 0-based vertex ids: a sequence or integer array of ids, or a boolean mask over the vertices.
std::vector<int> VertexIdsFromPython(const std::string& name, const py::handle& value,
                                     int num_vertices) {
  const std::string expected = name +
                               ": expected a sequence of 0-based vertex ids or a boolean "
                               "mask of the vertices";
  std::vector<long long> ids;
  if (py::isinstance<py::array>(value)) {
    const auto array = py::reinterpret_borrow<py::array>(value);
    const char kind = array.dtype().kind();
    if (array.ndim() != 1)
      throw InputError(name + ": expected a 1-D array, not one of " + std::to_string(array.ndim()) +
                       " dimensions");
    if (kind == 'b') {
      if (array.shape(0) != num_vertices)
        throw InputError(name + ": the boolean mask has " + std::to_string(array.shape(0)) +
                         " entries; the mesh has " + std::to_string(num_vertices) + " vertices");
      const auto mask = array.cast<std::vector<bool>>();
      std::vector<int> out;
      for (int v = 0; v < num_vertices; ++v)
        if (mask[v]) out.push_back(v);
      return out;
    }
    if (kind != 'i' && kind != 'u')
      TypeError(expected + ", not an array of dtype " + std::string(py::str(array.dtype())));
    ids = array.cast<std::vector<long long>>();
  } else if (py::isinstance<py::str>(value) || !py::hasattr(value, "__iter__")) {
    TypeError(expected + ", not " + TypeNameOf(value));
  } else {
    for (const py::handle item : value) {
      if (py::isinstance<py::bool_>(item) || !py::isinstance<py::int_>(item))
        TypeError(expected + "; an entry is " + TypeNameOf(item));
      ids.push_back(item.cast<long long>());
    }
  }
  std::vector<int> out;
  for (long long id : ids) {
    if (id < 0 || id >= num_vertices)
      throw InputError(name + ": vertex " + std::to_string(id) + " is out of range (the mesh has " +
                       std::to_string(num_vertices) + " vertices)");
    out.push_back(static_cast<int>(id));
  }
  return out;
}

// A mesh keyword argument: a pair (V, F).
PolyMesh MeshFromPython(const InputSpec& input, const py::handle& value) {
  if (!py::isinstance<py::tuple>(value) && !py::isinstance<py::list>(value))
    TypeError(input.name + ": expected a pair (V, F), not " + TypeNameOf(value));
  const auto pair = py::reinterpret_borrow<py::sequence>(value);
  if (pair.size() != 2) TypeError(input.name + ": expected a pair (V, F)");
  return MeshFromArrays(pair[0], pair[1], input.kind == InputKind::kQuadMesh);
}

// A curve: an (n, 3) array of at least two points, none repeating the one before.
std::vector<Eigen::Vector3d> CurveFromPython(const std::string& name, const py::handle& value) {
  const std::vector<Eigen::Vector3d> points = PointsFromArray(value, name);
  if (points.size() < 2)
    throw InputError(name + ": a curve needs at least 2 points, got " +
                     std::to_string(points.size()));
  for (size_t i = 1; i < points.size(); ++i)
    if (points[i] == points[i - 1])
      throw InputError(name + ": point " + std::to_string(i) + " repeats the one before");
  return points;
}

py::object Call(const ProblemSpec& spec, const py::args& args, const py::kwargs& kwargs) {
  RunInputs inputs;
  size_t next = 0;
  int num_vertices = -1;
  for (const InputSpec& input : spec.inputs) {
    if (!input.required) continue;
    inputs.sources[input.name] = input.name;
    if (input.kind == InputKind::kCurve) {
      if (args.size() < next + 1)
        TypeError(spec.name + "() needs the (n, 3) array of its " + input.name);
      inputs.curves[input.name] = CurveFromPython(input.name, args[next]);
      next += 1;
      continue;
    }
    if (args.size() < next + 2)
      TypeError(spec.name + "() needs the arrays V and F of its " + input.name);
    inputs.meshes[input.name] =
        MeshFromArrays(args[next], args[next + 1], input.kind == InputKind::kQuadMesh);
    if (num_vertices < 0) num_vertices = static_cast<int>(inputs.meshes[input.name].n_vertices());
    next += 2;
  }
  if (args.size() > next)
    TypeError(spec.name + "() takes " + std::to_string(next) + " positional arguments but " +
              std::to_string(args.size()) + " were given");
  py::object callback = py::none();
  std::set<std::string> outputs;
  for (const OutputSpec& output : spec.outputs)
    if (output.required) outputs.insert(output.name);
  nlohmann::json options = nlohmann::json::object();
  for (const auto& [key, value] : kwargs) {
    const std::string name = py::str(key);
    if (name == "callback") {
      callback = py::reinterpret_borrow<py::object>(value);
    } else if (name == "outputs") {
      if (py::isinstance<py::str>(value) || !py::hasattr(value, "__iter__"))
        TypeError("outputs: expected a sequence of output names, not " + TypeNameOf(value));
      for (const py::handle item : value) {
        const std::string output = py::str(item);
        const auto known = std::find_if(spec.outputs.begin(), spec.outputs.end(),
                                        [&](const OutputSpec& o) { return o.name == output; });
        if (known == spec.outputs.end()) {
          std::string names;
          for (const OutputSpec& o : spec.outputs) names += (names.empty() ? "" : ", ") + o.name;
          throw InputError("outputs: " + spec.name + " has no output '" + output + "' (" + names +
                           ")");
        }
        outputs.insert(output);
      }
    } else if (const InputSpec* input = spec.FindInput(name)) {
      if (value.is_none()) continue;
      if (input->kind == InputKind::kVertexIds)
        inputs.vertex_ids[name] = VertexIdsFromPython(name, value, num_vertices);
      else if (input->kind == InputKind::kCurve)
        inputs.curves[name] = CurveFromPython(name, value);
      else
        inputs.meshes[name] = MeshFromPython(*input, value);
      inputs.sources[name] = name;
    } else {
      try {
        options[name] = PythonToJson(value);
      } catch (const InputError& e) {
        TypeError(name + ": " + e.what());
      }
    }
  }
  bool keeps = false;
  for (const OutputSpec& output : spec.outputs) keeps = keeps || output.same_connectivity;
  if (keeps && outputs.size() > 1)
    throw InputError("outputs: " + spec.name +
                     "() returns its result's vertices; its other outputs are made by the command "
                     "line (--picture, ...)");
  RunBridge bridge(callback);
  RunContext context;
  context.on_record = bridge.callback();
  context.outputs = outputs;
  const RunResult result = bridge.Call([&] { return RunProblem(spec, inputs, options, context); });
  const py::module_ warnings = py::module_::import("warnings");
  for (const RunMessage& message : result.messages)
    if (message.kind == RunMessage::Kind::kWarning)
      warnings.attr("warn")(spec.name + ": " + SpellOptions(message.text, false),
                            py::module_::import("builtins").attr("UserWarning"), 2);
  const py::object report = JsonToPython(RunResultJson(spec, result, options, nullptr, nullptr));
  for (const OutputSpec& output : spec.outputs)
    if (output.kind == OutputKind::kMesh && output.same_connectivity) {
      const auto mesh = result.meshes.find(output.name);
      return py::make_tuple(mesh == result.meshes.end() ? py::object(py::none())
                                                        : py::object(VerticesToArray(mesh->second)),
                            report);
    }
  if (result.report.failed) return py::make_tuple(py::none(), report);
  py::dict out;
  for (const auto& [name, mesh] : result.meshes) out[name.c_str()] = MeshToPython(mesh);
  for (const auto& [name, text] : result.texts) {
    const OutputSpec* output = nullptr;
    for (const OutputSpec& o : spec.outputs)
      if (o.name == name) output = &o;
    if (output && output->kind == OutputKind::kJson)
      out[name.c_str()] = JsonToPython(nlohmann::json::parse(text));
    else
      out[name.c_str()] = text;
  }
  for (const auto& [name, array] : result.arrays) {
    py::array_t<double> a({array.rows(), array.cols()});
    auto view = a.mutable_unchecked<2>();
    for (Eigen::Index i = 0; i < array.rows(); ++i)
      for (Eigen::Index j = 0; j < array.cols(); ++j) view(i, j) = array(i, j);
    out[name.c_str()] = a;
  }
  return py::make_tuple(out, report);
}

// "picture, face_values" (or "none").
std::string OptionalOutputs(const ProblemSpec& spec) {
  std::string names;
  for (const OutputSpec& o : spec.outputs)
    if (!o.required) names += (names.empty() ? "" : ", ") + o.name;
  return names.empty() ? "none" : names;
}

// "planarize(V, F, *, solver='gp', ...) -> (V_out, report)" and one entry per argument.
std::string DocOf(const ProblemSpec& spec) {
  std::string signature = spec.name + "(";
  std::string arguments;
  for (const InputSpec& input : spec.inputs) {
    if (input.required && input.kind == InputKind::kCurve) {
      signature += input.name + ", ";
      arguments +=
          "    " + input.name + ": (n, 3) float64 points, at least 2. " + input.doc + ".\n";
    } else if (input.required) {
      signature += "V, F, ";
      arguments += "    V, F: the " + input.name +
                   ": (n, 3) float64 vertex positions and (m, k) "
                   "integer faces (0-based; a list of faces for mixed sizes). " +
                   input.doc + ".\n";
    }
  }
  signature += "*";
  for (const InputSpec& input : spec.inputs) {
    if (input.required) continue;
    signature += ", " + input.name + "=None";
    arguments += "    " + input.name + ": " +
                 (input.kind == InputKind::kVertexIds
                      ? "None, a sequence of 0-based vertex ids or a boolean mask. "
                  : input.kind == InputKind::kCurve ? "None or an (n, 3) array of points. "
                                                    : "None or a mesh (V, F). ") +
                 input.doc + ".\n";
  }
  for (const OptionSpec& option : spec.options) {
    if (option.required) {
      signature += ", " + option.name;
      arguments += "    " + option.name + " (" + OptionTypeName(option.type) +
                   (option.unit.empty() ? "" : ", " + option.unit) +
                   (option.RangeText().empty() ? "" : ", " + option.RangeText()) +
                   ", required): " + option.doc + ".\n";
      continue;
    }
    const std::string shown =
        option.default_value.is_null()      ? "None"
        : option.default_value.is_boolean() ? (option.default_value.get<bool>() ? "True" : "False")
        : option.default_value.is_string()  ? "'" + option.default_value.get<std::string>() + "'"
                                            : OptionText(option.default_value);
    signature += ", " + option.name + "=" + shown;
    arguments += "    " + option.name + " (" + OptionTypeName(option.type) +
                 (option.unit.empty() ? "" : ", " + option.unit) +
                 (option.RangeText().empty() ? "" : ", " + option.RangeText()) +
                 "): " + option.doc + ".\n";
  }
  signature += ", outputs=(), callback=None)";
  bool keeps = false;
  for (const OutputSpec& output : spec.outputs) keeps = keeps || output.same_connectivity;
  signature += keeps ? " -> (V_out, report)" : " -> (result, report)";
  std::string returns =
      keeps ? "Returns the result vertices (None when the run failed) and the report dict"
            : "Returns a dict of the results (None when the run failed) and the report dict";
  if (!keeps) {
    returns += "; the results:\n";
    for (const OutputSpec& output : spec.outputs)
      if (output.required)
        returns += "    " + output.name + ": " + output.doc +
                   (output.kind == OutputKind::kMesh ? " as (V, F)" : " as text") + ".\n";
    for (const ArraySpec& array : spec.arrays)
      returns += "    " + array.name + ": float64 array, " + array.doc + ".\n";
    returns += "And the report";
  }
  return signature + "\n\n" + spec.summary + "\n\n" + arguments +
         "    outputs: names of optional outputs to make as well (" + OptionalOutputs(spec) +
         "); each comes back in the result dict under its name.\n"
         "    callback: None or callback(record: dict) called at the start and after every "
         "iteration with the keys of report[\"history\"] entries; returning False stops the run. "
         "Ctrl-C stops the run and raises KeyboardInterrupt.\n\n" +
         returns +
         " (the keys of the command line's --report; \"input\" and \"output\" are None). "
         "Raises ValueError for "
         "bad arrays or option values and TypeError for arguments of the wrong type, naming the "
         "argument; warns (UserWarning) when the result is far from the input.\n";
}

}  // namespace

void BindRegistry(py::module_& m) {
  py::options options;
  options.disable_function_signatures();  // the docstrings give the schema's signatures
  for (const ProblemSpec& spec : Registry::Builtin().problems()) {
    const ProblemSpec* p = &spec;
    m.def(
        spec.name.c_str(),
        [p](const py::args& args, const py::kwargs& kwargs) { return Call(*p, args, kwargs); },
        DocOf(spec).c_str());
  }
  m.def(
      "schema", [] { return JsonToPython(Registry::Builtin().SchemaJson()); },
      "schema() -> dict\n\nThe registry of problems (inputs, outputs, options with types, "
      "defaults, ranges, units and docs): the document `gproj schema` prints.");
  m.attr("__version__") = GprojVersion();
}

}  // namespace gproj::python
