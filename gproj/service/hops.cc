#include "gproj/service/hops.h"

#include <cmath>
#include <limits>
#include <set>
#include <string>
#include <vector>

#include "gproj/problems/run/report_json.h"

namespace gproj::service {
namespace {

constexpr long long kAnyCount = std::numeric_limits<int>::max();  // Hops' "list" AtMost

[[noreturn]] void Refuse(const std::string& field, const std::string& rule) {
  throw RequestError(field + ": " + rule);
}

bool IsMesh(InputKind kind) { return kind == InputKind::kMesh || kind == InputKind::kQuadMesh; }

// Outputs a component gives: meshes and JSON documents (pictures and tables are left to the
// command line and the web app).
bool IsHopsOutput(const OutputSpec& output) {
  return output.kind == OutputKind::kMesh || output.kind == OutputKind::kJson;
}

const char* ResultType(const std::string& param_type) {
  if (param_type == "Number") return "System.Double";
  if (param_type == "Integer") return "System.Int32";
  if (param_type == "Boolean") return "System.Boolean";
  if (param_type == "Point") return "Rhino.Geometry.Point3d";
  return "System.String";
}

nlohmann::json Param(const std::string& name, const std::string& description,
                     const std::string& type, long long at_least, long long at_most) {
  return {{"Name", name},
          {"Nickname", name},
          {"Description", description},
          {"ParamType", type},
          {"ResultType", ResultType(type)},
          {"AtLeast", at_least},
          {"AtMost", at_most}};
}

nlohmann::json OptionParam(const OptionSpec& option) {
  std::string type = "Text";
  if (option.type == OptionType::kBool) type = "Boolean";
  if (option.type == OptionType::kInt) type = "Integer";
  if (option.type == OptionType::kNumber) type = "Number";
  std::string doc = option.doc;
  if (!option.unit.empty()) doc += " [" + option.unit + "]";
  if (!option.RangeText().empty()) doc += " (" + option.RangeText() + ")";
  if (!option.choices.empty()) {
    std::string choices;
    for (const std::string& c : option.choices) choices += (choices.empty() ? "" : "|") + c;
    doc += " (" + choices + ")";
  }
  if (type == "Text" && option.type != OptionType::kChoice)
    doc += " (written as on the command line, e.g. 1,2,3)";
  nlohmann::json param = Param(option.name, doc, type, option.required ? 1 : 0, 1);
  if (!option.default_value.is_null())
    param["Default"] = type == "Text" && !option.default_value.is_string()
                           ? nlohmann::json(OptionText(option.default_value))
                           : option.default_value;
  if (type == "Integer" || type == "Number") {
    if (std::isfinite(option.min) && !option.min_exclusive) param["Minimum"] = option.min;
    if (std::isfinite(option.max) && !option.max_exclusive) param["Maximum"] = option.max;
  }
  return param;
}

std::vector<std::string> MeasureOutputs(const ProblemSpec& spec) {
  std::vector<std::string> names;
  for (const std::string& measure : spec.log_measures) {
    bool taken = false;
    for (const OutputSpec& output : spec.outputs) taken = taken || output.name == measure;
    if (!taken && measure != "converged" && measure != "status" && measure != "iterations" &&
        measure != "report")
      names.push_back(measure);
  }
  return names;
}

// The items of each parameter of a solve body, by name: one branch per parameter.
std::map<std::string, nlohmann::json> ValuesByName(const nlohmann::json& body) {
  if (!body.is_object()) Refuse("solve", "expected a JSON object");
  if (!body.contains("values") || !body.at("values").is_array())
    Refuse("values", "expected a list of data trees ({\"ParamName\", \"InnerTree\"})");
  std::map<std::string, nlohmann::json> values;
  const nlohmann::json& trees = body.at("values");
  for (std::size_t i = 0; i < trees.size(); ++i) {
    const nlohmann::json& tree = trees[i];
    const std::string where = "values[" + std::to_string(i) + "]";
    if (!tree.is_object() || !tree.contains("ParamName") || !tree.at("ParamName").is_string())
      Refuse(where, "expected a data tree with a ParamName");
    const std::string name = tree.at("ParamName").get<std::string>();
    const nlohmann::json inner = tree.value("InnerTree", nlohmann::json::object());
    if (!inner.is_object()) Refuse(name, "InnerTree: expected an object of branches");
    if (inner.size() > 1)
      Refuse(name, "has " + std::to_string(inner.size()) +
                       " branches; gproj's components take one (flatten the tree)");
    nlohmann::json items = nlohmann::json::array();
    if (inner.size() == 1) {
      items = inner.begin().value();
      if (!items.is_array()) Refuse(name, "a branch must be a list of items");
    }
    if (values.count(name)) Refuse(name, "is given twice");
    values[name] = items;
  }
  return values;
}

// A data string as JSON, nested at most kMaxJsonDepth deep; a string that is not JSON as itself.
nlohmann::json ParseData(const std::string& text, const std::string& where) {
  try {
    return ParseRequestJson(text);
  } catch (const RequestError& e) {
    if (std::string(e.what()).find("nests deeper") != std::string::npos)
      Refuse(where, "the data nests deeper than " + std::to_string(kMaxJsonDepth) + " levels");
    return text;  // a bare string
  }
}

// An item's data as JSON ("1.5", "true", "\"text\"", "{\"X\":1,...}"), with the quotes Hops
// trims itself taken off values that are not strings.
nlohmann::json ItemData(const nlohmann::json& item, const std::string& where) {
  if (!item.is_object() || !item.contains("data"))
    Refuse(where, "expected an item {\"type\", \"data\"}");
  const nlohmann::json& data = item.at("data");
  if (!data.is_string()) return data;
  return ParseData(data.get<std::string>(), where);
}

double NumberItem(const nlohmann::json& item, const std::string& where) {
  nlohmann::json data = ItemData(item, where);
  if (data.is_string()) data = ParseData(data.get<std::string>(), where);
  if (!data.is_number() || !std::isfinite(data.get<double>()))
    Refuse(where, "expected a finite number");
  return data.get<double>();
}

long long IntegerItem(const nlohmann::json& item, const std::string& where) {
  const double x = NumberItem(item, where);
  if (x != std::floor(x) || std::abs(x) > 9e15) Refuse(where, "expected an integer");
  return static_cast<long long>(x);
}

bool BooleanItem(const nlohmann::json& item, const std::string& where) {
  const nlohmann::json data = ItemData(item, where);
  if (data.is_boolean()) return data.get<bool>();
  if (data.is_string()) {
    const std::string& s = data.get_ref<const std::string&>();
    if (s == "True" || s == "true") return true;
    if (s == "False" || s == "false") return false;
  }
  Refuse(where, "expected true or false");
}

std::string TextItem(const nlohmann::json& item, const std::string& where) {
  const nlohmann::json data = ItemData(item, where);
  return data.is_string() ? data.get<std::string>() : DumpJson(data);
}

nlohmann::json PointItem(const nlohmann::json& item, const std::string& where) {
  const nlohmann::json data = ItemData(item, where);
  if (!data.is_object()) Refuse(where, "expected a point {\"X\", \"Y\", \"Z\"}");
  nlohmann::json point = nlohmann::json::array();
  for (const char* axis : {"X", "Y", "Z"}) {
    std::string lower(1, static_cast<char>(axis[0] - 'A' + 'a'));
    const nlohmann::json* value = data.contains(axis)    ? &data.at(axis)
                                  : data.contains(lower) ? &data.at(lower)
                                                         : nullptr;
    if (!value || !value->is_number() || !std::isfinite(value->get<double>()))
      Refuse(where, std::string("expected a point with finite ") + axis);
    point.push_back(value->get<double>());
  }
  return point;
}

// The items of a parameter (empty: not connected).
const nlohmann::json& ItemsOf(const std::map<std::string, nlohmann::json>& values,
                              const std::string& name) {
  static const nlohmann::json kNone = nlohmann::json::array();
  const auto it = values.find(name);
  return it == values.end() ? kNone : it->second;
}

std::string ItemPlace(const std::string& name, std::size_t i) {
  return name + "[" + std::to_string(i) + "]";
}

nlohmann::json Tree(const std::string& name, nlohmann::json items) {
  return {{"ParamName", name}, {"InnerTree", {{"0", std::move(items)}}}};
}

nlohmann::json Item(const char* type, const nlohmann::json& value) {
  return {{"type", type}, {"data", DumpJson(value)}};
}

// A text is sent as it is, not JSON-quoted: the Hops component trims quotes off an item's data
// but does not undo JSON escapes, so a quoted report would arrive with \" in it.
nlohmann::json TextOut(const std::string& text) {
  return {{"type", "System.String"}, {"data", text}};
}

nlohmann::json PointsItems(const PolyMesh& mesh) {
  nlohmann::json items = nlohmann::json::array();
  for (const auto vh : mesh.vertices()) {
    const auto& p = mesh.point(vh);
    items.push_back(
        Item("Rhino.Geometry.Point3d",
             {{"X", JsonNumber(p[0])}, {"Y", JsonNumber(p[1])}, {"Z", JsonNumber(p[2])}}));
  }
  return items;
}

}  // namespace

bool HasHopsComponent(const ProblemSpec&) { return true; }

nlohmann::json HopsDescription(const ProblemSpec& spec) {
  nlohmann::json inputs = nlohmann::json::array(), outputs = nlohmann::json::array();
  for (const InputSpec& input : spec.inputs) {
    const long long at_least = input.required ? 1 : 0;
    switch (input.kind) {
      case InputKind::kMesh:
      case InputKind::kQuadMesh:
        inputs.push_back(Param(input.name + "_points", input.doc + ": the vertices", "Point",
                               at_least, kAnyCount));
        inputs.push_back(
            Param(input.name + "_faces",
                  input.doc + ": the faces as one list of 0-based vertex ids, " +
                      (input.kind == InputKind::kQuadMesh ? "four per quad"
                                                          : input.name + "_corners per face"),
                  "Integer", at_least, kAnyCount));
        if (input.kind == InputKind::kMesh) {
          nlohmann::json corners =
              Param(input.name + "_corners", "Vertices per face of " + input.name, "Integer", 0, 1);
          corners["Default"] = input.flat_face_corners;
          corners["Minimum"] = 3;
          inputs.push_back(corners);
        }
        break;
      case InputKind::kVertexIds:
        inputs.push_back(
            Param(input.name, input.doc + " (0-based vertex ids)", "Integer", at_least, kAnyCount));
        break;
      case InputKind::kCurve:
        inputs.push_back(Param(input.name, input.doc, "Point", at_least, kAnyCount));
        break;
      case InputKind::kBSpline:
        inputs.push_back(
            Param(input.name, input.doc + " (the B-spline's JSON)", "Text", at_least, 1));
        break;
      case InputKind::kText:
        inputs.push_back(Param(input.name, input.doc + " (the file's text)", "Text", at_least, 1));
        break;
      case InputKind::kJson:
        inputs.push_back(Param(input.name, input.doc + " (the JSON text)", "Text", at_least, 1));
        break;
    }
  }
  for (const OptionSpec& option : spec.options) inputs.push_back(OptionParam(option));
  for (const OutputSpec& output : spec.outputs) {
    if (!IsHopsOutput(output)) continue;
    if (output.kind == OutputKind::kJson) {
      outputs.push_back(Param(output.name, output.doc + " (JSON)", "Text", 1, 1));
      continue;
    }
    outputs.push_back(
        Param(output.name + "_points", output.doc + ": the vertices", "Point", 1, kAnyCount));
    if (!output.same_connectivity) {
      outputs.push_back(Param(output.name + "_faces",
                              output.doc + ": the faces as one list of vertex ids", "Integer", 1,
                              kAnyCount));
      outputs.push_back(Param(output.name + "_face_sizes",
                              output.doc + ": the vertices of each face", "Integer", 1, kAnyCount));
    }
  }
  outputs.push_back(Param("converged", "Whether the tolerance was met", "Boolean", 1, 1));
  outputs.push_back(Param("status",
                          "converged, not-converged, failed or cancelled, with how the run "
                          "ended",
                          "Text", 1, 1));
  outputs.push_back(Param("iterations", "Iterations of the run", "Integer", 1, 1));
  for (const std::string& measure : MeasureOutputs(spec))
    outputs.push_back(Param(measure, "The result's " + measure, "Number", 1, 1));
  outputs.push_back(Param("report", "The run's report (JSON)", "Text", 1, 1));
  return {{"Uri", "/hops/" + spec.name},
          {"Name", "gproj " + spec.name},
          {"Nickname", spec.name},
          {"Description", spec.summary},
          {"Category", "gproj"},
          {"Subcategory", "guided projection"},
          {"Inputs", inputs},
          {"Outputs", outputs}};
}

nlohmann::json HopsComponents(const Registry& registry) {
  nlohmann::json list = nlohmann::json::array();
  for (const ProblemSpec& spec : registry.problems())
    if (HasHopsComponent(spec)) list.push_back(HopsDescription(spec));
  return list;
}

const ProblemSpec* HopsProblem(const nlohmann::json& body, const Registry& registry) {
  if (!body.is_object() || !body.contains("pointer") || !body.at("pointer").is_string())
    return nullptr;
  std::string pointer = body.at("pointer").get<std::string>();
  while (!pointer.empty() && pointer.front() == '/') pointer.erase(0, 1);
  while (!pointer.empty() && pointer.back() == '/') pointer.pop_back();
  const std::string prefix = "hops/";
  if (pointer.compare(0, prefix.size(), prefix) != 0) return nullptr;
  const ProblemSpec* spec = registry.Find(pointer.substr(prefix.size()));
  return spec && HasHopsComponent(*spec) ? spec : nullptr;
}

nlohmann::json HopsRunRequest(const nlohmann::json& body, const ProblemSpec& spec) {
  const std::map<std::string, nlohmann::json> values = ValuesByName(body);
  // A name the component does not have: a definition made for another version of it.
  std::set<std::string> known;
  const nlohmann::json description = HopsDescription(spec);
  for (const nlohmann::json& input : description.at("Inputs"))
    known.insert(input.at("Name").get<std::string>());
  for (const auto& [name, items] : values)
    if (!known.count(name))
      Refuse(name, "gproj " + spec.name + " has no such input (GET /hops/" + spec.name +
                       " describes them)");
  nlohmann::json inputs = nlohmann::json::object(), options = nlohmann::json::object();
  for (const InputSpec& input : spec.inputs) {
    if (IsMesh(input.kind)) {
      const std::string points_name = input.name + "_points", faces_name = input.name + "_faces";
      const nlohmann::json& points = ItemsOf(values, points_name);
      const nlohmann::json& ids = ItemsOf(values, faces_name);
      if (points.empty() && ids.empty()) continue;
      if (points.empty()) Refuse(points_name, "is empty, but " + faces_name + " is given");
      if (ids.empty()) Refuse(faces_name, "is empty, but " + points_name + " is given");
      long long corners = 4;
      if (input.kind == InputKind::kMesh) {
        const nlohmann::json& given = ItemsOf(values, input.name + "_corners");
        corners = given.empty() ? input.flat_face_corners
                                : IntegerItem(given[0], input.name + "_corners");
        if (corners < 3) Refuse(input.name + "_corners", "must be at least 3");
      }
      if (ids.size() % corners != 0)
        Refuse(faces_name, std::to_string(ids.size()) + " ids are not a whole number of faces of " +
                               std::to_string(corners));
      nlohmann::json vertices = nlohmann::json::array(), faces = nlohmann::json::array();
      for (std::size_t i = 0; i < points.size(); ++i)
        vertices.push_back(PointItem(points[i], ItemPlace(points_name, i)));
      for (std::size_t f = 0; f < ids.size() / corners; ++f) {
        nlohmann::json face = nlohmann::json::array();
        for (long long k = 0; k < corners; ++k)
          face.push_back(IntegerItem(ids[f * corners + k], ItemPlace(faces_name, f * corners + k)));
        faces.push_back(std::move(face));
      }
      inputs[input.name] = {{"vertices", std::move(vertices)}, {"faces", std::move(faces)}};
      continue;
    }
    const nlohmann::json& items = ItemsOf(values, input.name);
    if (items.empty()) continue;
    nlohmann::json value;
    if (input.kind == InputKind::kVertexIds) {
      value = nlohmann::json::array();
      for (std::size_t i = 0; i < items.size(); ++i)
        value.push_back(IntegerItem(items[i], ItemPlace(input.name, i)));
    } else if (input.kind == InputKind::kCurve) {
      value = nlohmann::json::array();
      for (std::size_t i = 0; i < items.size(); ++i)
        value.push_back(PointItem(items[i], ItemPlace(input.name, i)));
    } else {
      const std::string text = TextItem(items[0], input.name);
      if (input.kind == InputKind::kBSpline) {
        value = ParseData(text, input.name);
        if (!value.is_object()) Refuse(input.name, "expected the B-spline's JSON object");
      } else {
        value = text;
      }
    }
    inputs[input.name] = std::move(value);
  }
  for (const OptionSpec& option : spec.options) {
    const nlohmann::json& items = ItemsOf(values, option.name);
    if (items.empty()) continue;
    if (items.size() > 1)
      Refuse(option.name, "takes one item, got " + std::to_string(items.size()));
    switch (option.type) {
      case OptionType::kBool:
        options[option.name] = BooleanItem(items[0], option.name);
        break;
      case OptionType::kInt:
        options[option.name] = IntegerItem(items[0], option.name);
        break;
      case OptionType::kNumber:
        options[option.name] = NumberItem(items[0], option.name);
        break;
      case OptionType::kChoice:
        options[option.name] = TextItem(items[0], option.name);
        break;
      default: {
        const std::string text = TextItem(items[0], option.name);
        if (text.empty()) continue;  // an empty panel: the default
        options[option.name] = ParseOptionText(option, text);
      }
    }
  }
  nlohmann::json outputs = nlohmann::json::array();
  for (const OutputSpec& output : spec.outputs)
    if (!output.required && IsHopsOutput(output)) outputs.push_back(output.name);
  return {{"problem", spec.name}, {"inputs", inputs}, {"options", options}, {"outputs", outputs}};
}

nlohmann::json HopsAnswer(const ProblemSpec& spec, const RunResult* result,
                          const nlohmann::json& report, const std::string& status,
                          const std::vector<std::string>& errors,
                          const std::vector<std::string>& warnings) {
  nlohmann::json values = nlohmann::json::array();
  const bool usable = result && !result->report.failed;
  for (const OutputSpec& output : spec.outputs) {
    if (!IsHopsOutput(output)) continue;
    if (output.kind == OutputKind::kJson) {
      nlohmann::json items = nlohmann::json::array();
      if (usable && result->texts.count(output.name))
        items.push_back(TextOut(result->texts.at(output.name)));
      values.push_back(Tree(output.name, items));
      continue;
    }
    const PolyMesh* mesh =
        usable && result->meshes.count(output.name) ? &result->meshes.at(output.name) : nullptr;
    values.push_back(
        Tree(output.name + "_points", mesh ? PointsItems(*mesh) : nlohmann::json::array()));
    if (output.same_connectivity) continue;
    nlohmann::json ids = nlohmann::json::array(), sizes = nlohmann::json::array();
    if (mesh)
      for (const auto fh : mesh->faces()) {
        int size = 0;
        for (const auto vh : mesh->fv_range(fh)) {
          ids.push_back(Item("System.Int32", vh.idx()));
          ++size;
        }
        sizes.push_back(Item("System.Int32", size));
      }
    values.push_back(Tree(output.name + "_faces", ids));
    values.push_back(Tree(output.name + "_face_sizes", sizes));
  }
  const bool has_report = report.is_object();
  values.push_back(Tree("converged", has_report ? nlohmann::json::array({Item(
                                                      "System.Boolean", status == "converged")})
                                                : nlohmann::json::array()));
  std::string status_text = status;
  if (has_report && report.contains("termination"))
    status_text += ": " + report.at("termination").get<std::string>();
  values.push_back(Tree("status", nlohmann::json::array({TextOut(status_text)})));
  values.push_back(
      Tree("iterations",
           has_report ? nlohmann::json::array({Item("System.Int32", report.value("iterations", 0))})
                      : nlohmann::json::array()));
  for (const std::string& measure : MeasureOutputs(spec)) {
    nlohmann::json items = nlohmann::json::array();
    if (has_report && report.contains("final") && report.at("final").contains(measure) &&
        report.at("final").at(measure).is_number())
      items.push_back(Item("System.Double", report.at("final").at(measure).get<double>()));
    values.push_back(Tree(measure, items));
  }
  values.push_back(Tree("report", has_report ? nlohmann::json::array({TextOut(DumpJson(report))})
                                             : nlohmann::json::array()));
  return {{"values", values}, {"errors", errors}, {"warnings", warnings}};
}

}  // namespace gproj::service
