// The registry's problems as Python functions, generated from their specs: required mesh inputs
// as positional (V, F) arrays, optional inputs and options as keyword arguments named as in the
// schema (defaults, ranges and docs from it), `callback` for the iteration records; and
// gproj.schema(), the same document as `gproj schema`.
#include <pybind11/numpy.h>
#include <pybind11/stl.h>

#include <string>

#include "gproj/problems/run/registry.h"
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

// A B-spline surface: a dict with the keys of its JSON (docs/formats.md); arrays are accepted.
BSplineSurface BSplineFromPython(const std::string& name, const py::handle& value) {
  if (!py::isinstance<py::dict>(value))
    TypeError(name +
              ": expected a dict (the B-spline's JSON: degree, knots_u, knots_v, "
              "control_points), not " +
              TypeNameOf(value));
  return ParseBSplineJson(PythonToJson(value).dump(), name);
}

// The arguments of a call, converted.
struct CallArguments {
  RunInputs inputs;
  nlohmann::json options = nlohmann::json::object();
  py::object callback = py::none();
  std::set<std::string> outputs;  // the required ones and those asked for
};

// A text input: a str (the text of the file the command line reads).
std::string TextFromPython(const std::string& name, const py::handle& value) {
  if (!py::isinstance<py::str>(value))
    TypeError(name + ": expected a str (the file's text), not " + TypeNameOf(value));
  return value.cast<std::string>();
}

// One input from its Python value: (V, F) for a mesh passed as a keyword, an array for a curve,
// a dict for a B-spline, a str for a text, ids or a mask for vertex ids.
void ReadInput(const InputSpec& input, const py::handle& value, int num_vertices,
               RunInputs* inputs) {
  if (input.kind == InputKind::kVertexIds)
    inputs->vertex_ids[input.name] = VertexIdsFromPython(input.name, value, num_vertices);
  else if (input.kind == InputKind::kCurve)
    inputs->curves[input.name] = CurveFromPython(input.name, value);
  else if (input.kind == InputKind::kBSpline)
    inputs->surfaces[input.name] = BSplineFromPython(input.name, value);
  else if (input.kind == InputKind::kText)
    inputs->texts[input.name] = TextFromPython(input.name, value);
  else
    inputs->meshes[input.name] = MeshFromPython(input, value);
  inputs->sources[input.name] = input.name;
}

// The positional inputs from the positional arguments: (V, F) per mesh, one object per other
// kind; an optional positional input may be left out. Returns the vertex count of the first
// mesh (-1: none).
int ReadPositional(const ProblemSpec& spec, const py::args& args, RunInputs* inputs) {
  size_t next = 0;
  int num_vertices = -1;
  for (const InputSpec& input : spec.inputs) {
    if (!input.IsPositional()) continue;
    const bool mesh = input.kind == InputKind::kMesh || input.kind == InputKind::kQuadMesh;
    const size_t count = mesh ? 2 : 1;
    if (args.size() < next + count) {
      if (!input.required && args.size() == next) break;
      TypeError(spec.name + "() needs " +
                (mesh ? "the arrays V and F of its " + input.name : "its " + input.name));
    }
    if (mesh) {
      inputs->meshes[input.name] =
          MeshFromArrays(args[next], args[next + 1], input.kind == InputKind::kQuadMesh);
      inputs->sources[input.name] = input.name;
      if (num_vertices < 0)
        num_vertices = static_cast<int>(inputs->meshes[input.name].n_vertices());
    } else {
      ReadInput(input, args[next], num_vertices, inputs);
    }
    next += count;
  }
  if (args.size() > next)
    TypeError(spec.name + "() takes " + std::to_string(next) + " positional arguments but " +
              std::to_string(args.size()) + " were given");
  return num_vertices;
}

// outputs=[...]: names of the spec's outputs.
void ReadOutputNames(const ProblemSpec& spec, const py::handle& value,
                     std::set<std::string>* outputs) {
  if (py::isinstance<py::str>(value) || !py::hasattr(value, "__iter__"))
    TypeError("outputs: expected a sequence of output names, not " + TypeNameOf(value));
  for (const py::handle item : value) {
    const std::string output = py::str(item);
    const auto known = std::find_if(spec.outputs.begin(), spec.outputs.end(),
                                    [&](const OutputSpec& o) { return o.name == output; });
    if (known == spec.outputs.end()) {
      std::string names;
      for (const OutputSpec& o : spec.outputs) names += (names.empty() ? "" : ", ") + o.name;
      throw InputError("outputs: " + spec.name + " has no output '" + output + "' (" + names + ")");
    }
    outputs->insert(output);
  }
  bool keeps = false;
  for (const OutputSpec& o : spec.outputs) keeps = keeps || o.same_connectivity;
  if (keeps && outputs->size() > 1)
    throw InputError("outputs: " + spec.name +
                     "() returns its result's vertices; its other outputs are made by the command "
                     "line (--picture, ...)");
}

// The keyword arguments: callback, outputs, optional inputs and the options (as JSON, checked
// by the run protocol).
void ReadKeywords(const ProblemSpec& spec, const py::kwargs& kwargs, int num_vertices,
                  CallArguments* call) {
  for (const auto& [key, value] : kwargs) {
    const std::string name = py::str(key);
    if (name == "callback") {
      call->callback = py::reinterpret_borrow<py::object>(value);
    } else if (name == "outputs") {
      ReadOutputNames(spec, value, &call->outputs);
    } else if (const InputSpec* input = spec.FindInput(name)) {
      if (value.is_none()) continue;
      if (input->IsPositional())
        TypeError(spec.name + "(): " + name + " is positional (" +
                  (input->kind == InputKind::kMesh || input->kind == InputKind::kQuadMesh
                       ? "its arrays V, F"
                       : "the first argument") +
                  ")");
      ReadInput(*input, value, num_vertices, &call->inputs);
    } else {
      try {
        call->options[name] = PythonToJson(value);
      } catch (const InputError& e) {
        TypeError(name + ": " + e.what());
      }
    }
  }
}

// (V, F) alone for a generator; (V_out, report) for a result that keeps the connectivity of the
// mesh input given, else (result, report) with
// the meshes as (V, F), JSON texts as dicts, other texts as str and the arrays as numpy arrays.
py::object ResultToPython(const ProblemSpec& spec, const RunInputs& inputs, const RunResult& result,
                          const py::object& report) {
  if (spec.generator) return MeshToPython(result.meshes.at(spec.outputs.front().name));
  for (const OutputSpec& output : spec.outputs)
    if (output.kind == OutputKind::kMesh && output.same_connectivity && !inputs.meshes.empty()) {
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

py::object Call(const ProblemSpec& spec, const py::args& args, const py::kwargs& kwargs) {
  CallArguments call;
  const int num_vertices = ReadPositional(spec, args, &call.inputs);
  for (const OutputSpec& output : spec.outputs)
    if (output.required) call.outputs.insert(output.name);
  ReadKeywords(spec, kwargs, num_vertices, &call);
  RunBridge bridge(call.callback);
  RunContext context;
  context.on_record = bridge.callback();
  context.outputs = call.outputs;
  RunResult result =
      bridge.Call([&] { return RunProblem(spec, call.inputs, call.options, context); });
  result.report.termination = SpellOptions(result.report.termination, false);
  const py::module_ warnings = py::module_::import("warnings");
  for (const RunMessage& message : result.messages)
    if (message.kind == RunMessage::Kind::kWarning)
      warnings.attr("warn")(spec.name + ": " + SpellOptions(message.text, false),
                            py::module_::import("builtins").attr("UserWarning"), 2);
  return ResultToPython(
      spec, call.inputs, result,
      JsonToPython(RunResultJson(spec, result, call.options, call.inputs, false, nullptr)));
}

// "picture, face_values" (or "none").
std::string OptionalOutputs(const ProblemSpec& spec) {
  std::string names;
  for (const OutputSpec& o : spec.outputs)
    if (!o.required) names += (names.empty() ? "" : ", ") + o.name;
  return names.empty() ? "none" : names;
}

// A keyword input's entry: what it takes.
std::string KeywordInputKind(InputKind kind) {
  switch (kind) {
    case InputKind::kVertexIds:
      return "None, a sequence of 0-based vertex ids or a boolean mask. ";
    case InputKind::kCurve:
      return "None or an (n, 3) array of points. ";
    case InputKind::kText:
      return "None or a str, the text of the file the command line reads. ";
    case InputKind::kBSpline:
      return "None or a dict, the B-spline's JSON. ";
    default:
      return "None or a mesh (V, F). ";
  }
}

// The positional part of the signature ("V, F, ") and the inputs' entries.
void DescribeInputs(const ProblemSpec& spec, std::string* signature, std::string* arguments) {
  for (const InputSpec& input : spec.inputs) {
    if (!input.IsPositional()) continue;
    const std::string optional = input.required ? "" : "=None";
    const std::string left_out = input.required ? "" : " (optional)";
    if (input.kind == InputKind::kCurve) {
      *signature += input.name + optional + ", ";
      *arguments += "    " + input.name + left_out + ": (n, 3) float64 points, at least 2. " +
                    input.doc + ".\n";
    } else if (input.kind == InputKind::kBSpline) {
      *signature += input.name + optional + ", ";
      *arguments += "    " + input.name + left_out +
                    ": a dict, the B-spline's JSON (degree, knots_u, knots_v, control_points; "
                    "numpy arrays accepted). " +
                    input.doc + ".\n";
    } else if (input.kind == InputKind::kText) {
      *signature += input.name + optional + ", ";
      *arguments +=
          "    " + input.name + left_out + ": a str, the file's text. " + input.doc + ".\n";
    } else {
      *signature += "V" + optional + ", F" + optional + ", ";
      *arguments += "    V, F: the " + input.name + left_out +
                    ": (n, 3) float64 vertex positions and (m, k) integer faces (0-based; a list "
                    "of faces for mixed sizes). " +
                    input.doc + ".\n";
    }
  }
  *signature += "*";
  for (const InputSpec& input : spec.inputs) {
    if (input.IsPositional()) continue;
    *signature += ", " + input.name + "=None";
    *arguments += "    " + input.name + ": " + KeywordInputKind(input.kind) + input.doc + ".\n";
  }
}

// A default as a Python literal: None, True, 'text', 1e-09, [0, 0, 1].
std::string PythonLiteral(const nlohmann::json& d) {
  if (d.is_null()) return "None";
  if (d.is_boolean()) return d.get<bool>() ? "True" : "False";
  if (d.is_string()) return "'" + d.get<std::string>() + "'";
  if (d.is_array()) {
    std::string items;
    for (const nlohmann::json& item : d) items += (items.empty() ? "" : ", ") + PythonLiteral(item);
    return "[" + items + "]";
  }
  return OptionText(d);
}

// The options' part of the signature (", tolerance=1e-09") and their entries.
void DescribeOptions(const ProblemSpec& spec, std::string* signature, std::string* arguments) {
  for (const OptionSpec& option : spec.options) {
    *signature +=
        ", " + option.name + (option.required ? "" : "=" + PythonLiteral(option.default_value));
    *arguments += "    " + option.name + " (" + OptionTypeName(option.type) +
                  (option.unit.empty() ? "" : ", " + option.unit) +
                  (option.RangeText().empty() ? "" : ", " + option.RangeText()) +
                  (option.required ? ", required" : "") + "): " + option.doc + ".\n";
  }
}

// What a call returns, for the docstring.
std::string DescribeReturns(const ProblemSpec& spec, bool keeps) {
  if (keeps)
    return "Returns the result vertices (None when the run failed; a dict {\"output\": (V, F)} "
           "when no input mesh was given) and the report dict";
  std::string returns =
      "Returns a dict of the results (None when the run failed) and the report dict; the "
      "results:\n";
  for (const OutputSpec& output : spec.outputs)
    if (output.required)
      returns += "    " + output.name + ": " + output.doc +
                 (output.kind == OutputKind::kMesh   ? " as (V, F)"
                  : output.kind == OutputKind::kJson ? " as a dict"
                                                     : " as text") +
                 ".\n";
  for (const ArraySpec& array : spec.arrays)
    returns += "    " + array.name + ": float64 array, " + array.doc + ".\n";
  return returns + "And the report";
}

// "planarize(V, F, *, solver='gp', ...) -> (V_out, report)" and one entry per argument.
std::string DocOf(const ProblemSpec& spec) {
  std::string signature = spec.name + "(", arguments;
  DescribeInputs(spec, &signature, &arguments);
  DescribeOptions(spec, &signature, &arguments);
  if (spec.generator)
    return signature + ") -> (V, F)\n\n" + spec.summary + "\n\n" + arguments +
           "\nReturns V: (n, 3) float64 and F: (m, 4) int32. Raises ValueError for option values "
           "out of range and TypeError for arguments of the wrong type, naming the argument.\n";
  bool keeps = false;
  for (const OutputSpec& output : spec.outputs) keeps = keeps || output.same_connectivity;
  signature += std::string(", outputs=(), callback=None)") +
               (keeps ? " -> (V_out, report)" : " -> (result, report)");
  return signature + "\n\n" + spec.summary + "\n\n" + arguments +
         "    outputs: names of optional outputs to make as well (" + OptionalOutputs(spec) +
         "); each comes back in the result dict under its name.\n"
         "    callback: None or callback(record: dict) called at the start and after every "
         "iteration with the keys of report[\"history\"] entries; returning False stops the run. "
         "Ctrl-C stops the run and raises KeyboardInterrupt.\n\n" +
         DescribeReturns(spec, keeps) +
         " (the keys of the command line's --report; \"input\" and \"output\" are None). "
         "Raises ValueError for bad arrays or option values and TypeError for arguments of the "
         "wrong type, naming the argument; warns (UserWarning) when the result is far from the "
         "input.\n";
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
