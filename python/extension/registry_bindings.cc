// The run of the registry's problems from Python: _run, behind the functions the package
// generates from the schema (python/gproj/_problems.py), reads the positional inputs ((V, F) per
// mesh), the keyword inputs and the options, runs the problem and returns its outputs, arrays,
// report and warnings; _check_options checks an options object; schema() is the document
// `gproj schema` prints.
#include <pybind11/numpy.h>
#include <pybind11/stl.h>

#include <string>

#include "gproj/geometry/io/text_input.h"
#include "gproj/problems/mesh/vertex_control.h"
#include "gproj/problems/run/registry.h"
#include "python/extension/conversions.h"
#include "python/extension/module.h"
#include "python/extension/run_bridge.h"

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

// A mesh from its arrays, welded when asked (the map kept in inputs->weld_maps).
void ReadMesh(const InputSpec& input, const py::handle& vertices, const py::handle& faces,
              bool weld, RunInputs* inputs) {
  std::vector<int> map;
  inputs->meshes[input.name] = MeshFromArrays(
      vertices, faces, MeshRequirements{input.kind == InputKind::kQuadMesh, weld}, &map);
  if (weld) inputs->weld_maps[input.name] = std::move(map);
}

// A mesh keyword argument: a pair (V, F).
void MeshFromPython(const InputSpec& input, const py::handle& value, bool weld, RunInputs* inputs) {
  if (!py::isinstance<py::tuple>(value) && !py::isinstance<py::list>(value))
    TypeError(input.name + ": expected a pair (V, F), not " + TypeNameOf(value));
  const auto pair = py::reinterpret_borrow<py::sequence>(value);
  if (pair.size() != 2) TypeError(input.name + ": expected a pair (V, F)");
  ReadMesh(input, pair[0], pair[1], weld, inputs);
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

// A JSON input: a dict (or list) converted, or a str holding the JSON text.
std::string JsonFromPython(const std::string& name, const py::handle& value) {
  if (py::isinstance<py::str>(value)) return value.cast<std::string>();
  if (!py::isinstance<py::dict>(value))
    TypeError(name + ": expected a dict, its JSON text or a path, not " + TypeNameOf(value));
  return PythonToJson(value).dump();
}

// Whether a str is JSON text rather than a path: its first non-blank character opens an object
// or an array.
bool LooksLikeJson(const std::string& text) {
  const std::size_t first = text.find_first_not_of(" \t\r\n");
  return first != std::string::npos && (text[first] == '{' || text[first] == '[');
}

// The path a value names: an os.PathLike, or a str for the kinds no str can be otherwise (a
// curve, a B-spline, vertex ids) and for a JSON input a str that is not JSON text; empty for
// anything else.
std::string PathOf(const InputSpec& input, const py::handle& value) {
  const py::module_ os = py::module_::import("os");
  const bool path_like = py::isinstance(value, os.attr("PathLike"));
  if (!path_like && !py::isinstance<py::str>(value)) return "";
  if (input.kind == InputKind::kJson && !path_like && LooksLikeJson(value.cast<std::string>()))
    return "";
  if (input.kind != InputKind::kCurve && input.kind != InputKind::kBSpline &&
      input.kind != InputKind::kVertexIds && input.kind != InputKind::kJson)
    return "";
  const py::object path = os.attr("fspath")(value);
  if (!py::isinstance<py::str>(path))
    TypeError(input.name + ": expected a path as str or os.PathLike[str], not bytes");
  return path.cast<std::string>();
}

// One input from its Python value: (V, F) for a mesh passed as a keyword, an array for a curve,
// a dict for a B-spline, a str for a text, ids or a mask for vertex ids; a path (str or
// os.PathLike) for a curve, a B-spline or vertex ids, read as the command line reads it.
void ReadInput(const InputSpec& input, const py::handle& value, int num_vertices, bool weld,
               RunInputs* inputs) {
  const std::string path = PathOf(input, value);
  if (!path.empty()) {
    if (input.kind == InputKind::kCurve)
      inputs->curves[input.name] = ReadPoints(path, 2);
    else if (input.kind == InputKind::kBSpline)
      inputs->surfaces[input.name] = ReadBSplineJson(path);
    else if (input.kind == InputKind::kJson)
      inputs->texts[input.name] = ReadTextFile(path);
    else
      inputs->vertex_ids[input.name] = ReadVertexIds(path, num_vertices);
    inputs->sources[input.name] = path;
    inputs->files[input.name] = path;
    return;
  }
  if (input.kind == InputKind::kVertexIds)
    inputs->vertex_ids[input.name] = VertexIdsFromPython(input.name, value, num_vertices);
  else if (input.kind == InputKind::kCurve)
    inputs->curves[input.name] = CurveFromPython(input.name, value);
  else if (input.kind == InputKind::kBSpline)
    inputs->surfaces[input.name] = BSplineFromPython(input.name, value);
  else if (input.kind == InputKind::kText)
    inputs->texts[input.name] = TextFromPython(input.name, value);
  else if (input.kind == InputKind::kJson)
    inputs->texts[input.name] = JsonFromPython(input.name, value);
  else
    MeshFromPython(input, value, weld, inputs);
  inputs->sources[input.name] = input.name;
}

// The positional inputs from the positional arguments: (V, F) per mesh, one object per other
// kind; an optional positional input may be left out. Returns the vertex count of the first
// mesh (-1: none).
int ReadPositional(const ProblemSpec& spec, const py::tuple& args, bool weld, RunInputs* inputs) {
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
      ReadMesh(input, args[next], args[next + 1], weld, inputs);
      inputs->sources[input.name] = input.name;
      if (num_vertices < 0)
        num_vertices = static_cast<int>(inputs->meshes[input.name].n_vertices());
    } else {
      ReadInput(input, args[next], num_vertices, weld, inputs);
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
}

// The keyword inputs (a dict by input name; positional ones refused) and the options (a dict,
// as JSON, checked by the run protocol).
void ReadKeywords(const ProblemSpec& spec, const py::dict& keywords, const py::dict& options,
                  int num_vertices, bool weld, CallArguments* call) {
  for (const auto& [key, value] : keywords) {
    const std::string name = py::str(key);
    const InputSpec* input = spec.FindInput(name);
    if (!input) TypeError(spec.name + "() has no input '" + name + "'");
    if (value.is_none()) continue;
    if (input->IsPositional())
      TypeError(spec.name + "(): " + name + " is positional (" +
                (input->kind == InputKind::kMesh || input->kind == InputKind::kQuadMesh
                     ? "its arrays V, F"
                     : "the first argument") +
                ")");
    ReadInput(*input, value, num_vertices, weld, &call->inputs);
  }
  for (const auto& [key, value] : options) {
    const std::string name = py::str(key);
    try {
      call->options[name] = PythonToJson(value);
    } catch (const InputError& e) {
      TypeError(name + ": " + e.what());
    }
  }
}

// The outputs as a dict by name: meshes as (V, F), JSON texts as dicts, other texts as str; the
// problem's arrays as a second dict of float64 arrays. Both empty when the run failed.
std::pair<py::dict, py::dict> ResultToPython(const ProblemSpec& spec, const RunResult& result) {
  py::dict out, arrays;
  if (result.report.failed) return {out, arrays};
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
    arrays[name.c_str()] = a;
  }
  return {out, arrays};
}

const ProblemSpec& SpecNamed(const std::string& name) {
  const ProblemSpec* spec = Registry::Builtin().Find(name);
  if (!spec) throw InputError("problem: no problem named '" + name + "'");
  return *spec;
}

// What Result.resolve starts from: a run's problem, inputs, options and outputs asked, and its
// result mesh (the output spec.WarmResolveOutput() names), for the problems that have a warm
// re-solve.
struct WarmStart {
  std::string problem;
  RunInputs inputs;
  nlohmann::json options;
  std::set<std::string> outputs;
  PolyMesh result;
};

// Runs the call; returns (outputs, arrays, report, warnings, weld maps, warm start or None).
py::tuple RunCall(const ProblemSpec& spec, CallArguments call, bool soft_free_start) {
  RunBridge bridge(call.callback);
  RunContext context;
  context.on_record = bridge.callback();
  context.stop_requested = bridge.stop_poll();
  context.outputs = call.outputs;
  context.soft_free_start = soft_free_start;
  RunResult result =
      bridge.Call([&] { return RunProblem(spec, call.inputs, call.options, context); });
  result.report.termination = SpellOptions(result.report.termination, false);
  py::list messages;
  for (const RunMessage& message : result.messages)
    if (message.kind == RunMessage::Kind::kWarning)
      messages.append(SpellOptions(message.text, false));
  const auto [values, arrays] = ResultToPython(spec, result);
  py::dict weld_maps;
  for (const auto& [input, map] : call.inputs.weld_maps)
    weld_maps[input.c_str()] = py::array_t<int>(static_cast<py::ssize_t>(map.size()), map.data());
  const py::object report =
      JsonToPython(RunResultJson(spec, result, call.options, call.inputs, nullptr));
  py::object warm = py::none();
  const OutputSpec* output = spec.WarmResolveOutput();
  if (output && !result.report.failed && result.meshes.count(output->name))
    warm = py::capsule(
        new WarmStart{spec.name, std::move(call.inputs), std::move(call.options), call.outputs,
                      result.meshes.at(output->name)},
        "gproj.WarmStart", [](PyObject* capsule) {
          delete static_cast<WarmStart*>(PyCapsule_GetPointer(capsule, "gproj.WarmStart"));
        });
  return py::make_tuple(values, arrays, report, messages, weld_maps, warm);
}

// _run(problem, positional, options, keywords, outputs, callback, weld): the one entry of the
// package's functions (gproj/_problems.py); see RunCall.
py::tuple Run(const std::string& name, const py::tuple& positional, const py::dict& options,
              const py::dict& keywords, const py::object& outputs, const py::object& callback,
              bool weld) {
  const ProblemSpec& spec = SpecNamed(name);
  CallArguments call;
  const int num_vertices = ReadPositional(spec, positional, weld, &call.inputs);
  for (const OutputSpec& output : spec.outputs)
    if (output.required) call.outputs.insert(output.name);
  ReadOutputNames(spec, outputs, &call.outputs);
  ReadKeywords(spec, keywords, options, num_vertices, weld, &call);
  call.callback = callback;
  return RunCall(spec, std::move(call), false);
}

// _resolve(warm, moved, to, fixed, options, soft_terms, callback): Result.resolve, a warm
// re-solve from a run's result after an edit (ApplyWarmEdit); `options` override the run's
// (None restores a default).
py::tuple Resolve(const py::object& state, const std::vector<int>& moved,
                  const std::vector<std::vector<double>>& to, const std::vector<int>& fixed,
                  const py::dict& options, bool soft_terms, const py::object& callback) {
  void* pointer = PyCapsule_IsValid(state.ptr(), "gproj.WarmStart")
                      ? PyCapsule_GetPointer(state.ptr(), "gproj.WarmStart")
                      : nullptr;
  if (!pointer) throw py::type_error("warm: expected what _run gave back");
  const WarmStart& warm = *static_cast<const WarmStart*>(pointer);
  const ProblemSpec& spec = SpecNamed(warm.problem);
  CallArguments call;
  call.inputs = warm.inputs;
  call.outputs = warm.outputs;
  call.callback = callback;
  std::vector<Eigen::Vector3d> points;
  for (const auto& p : to) {
    if (p.size() != 3) throw InputError("moved: expected points (x, y, z)");
    points.emplace_back(p[0], p[1], p[2]);
  }
  ApplyWarmEdit(spec, warm.result, moved, points, fixed, &call.inputs);
  nlohmann::json given = warm.options;
  for (const auto& [key, value] : options) {
    const std::string option = py::str(key);
    try {
      if (value.is_none())
        given.erase(option);
      else
        given[option] = PythonToJson(value);
    } catch (const InputError& e) {
      TypeError(option + ": " + e.what());
    }
  }
  call.options = given;
  return RunCall(spec, std::move(call), !soft_terms);
}

}  // namespace

void BindRegistry(py::module_& m) {
  m.def("_run", &Run, py::arg("problem"), py::arg("positional"), py::arg("options"),
        py::arg("keywords"), py::arg("outputs"), py::arg("callback"), py::arg("weld"),
        "The run of a registry problem behind gproj's functions (gproj/_problems.py).");
  m.def("_resolve", &Resolve, py::arg("warm"), py::arg("moved"), py::arg("to"), py::arg("fixed"),
        py::arg("options"), py::arg("soft_terms"), py::arg("callback"),
        "A warm re-solve from a run's result after an edit (Result.resolve).");
  m.def(
      "_check_options",
      [](const std::string& name, const py::dict& options) {
        nlohmann::json given = nlohmann::json::object();
        for (const auto& [key, value] : options) {
          if (value.is_none()) continue;
          const std::string option = py::str(key);
          try {
            given[option] = PythonToJson(value);
          } catch (const InputError& e) {
            TypeError(option + ": " + e.what());
          }
        }
        CompleteOptions(SpecNamed(name).options, given);
      },
      py::arg("problem"), py::arg("options"),
      "Checks a problem's options (names, types, ranges) as a run would; raises naming the "
      "option.");
  m.def(
      "schema", [] { return py::dict(JsonToPython(Registry::Builtin().SchemaJson())); },
      "The registry of problems (inputs, outputs, options with types, "
      "defaults, ranges, units and docs): the document `gproj schema` prints.");
  m.attr("__version__") = GprojVersion();
}

}  // namespace gproj::python
