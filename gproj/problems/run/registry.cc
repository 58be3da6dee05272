#include "gproj/problems/run/registry.h"

#include <algorithm>
#include <cctype>
#include <set>
#include <stdexcept>

#include "gproj/problems/run/report_json.h"

#ifndef GPROJ_VERSION
#error "GPROJ_VERSION is set by CMake (the project's version)"
#endif

namespace gproj {
namespace {

bool IsIdentifier(const std::string& name) {
  if (name.empty() || !std::islower(static_cast<unsigned char>(name[0]))) return false;
  return std::all_of(name.begin(), name.end(), [](unsigned char c) {
    return std::islower(c) || std::isdigit(c) || c == '_';
  });
}

}  // namespace

const char* InputKindName(InputKind kind) {
  switch (kind) {
    case InputKind::kQuadMesh:
      return "quad_mesh";
    case InputKind::kMesh:
      return "mesh";
    case InputKind::kVertexIds:
      return "vertex_ids";
    case InputKind::kCurve:
      return "curve";
    case InputKind::kBSpline:
      return "bspline";
    case InputKind::kText:
      return "text";
    case InputKind::kJson:
      return "json";
  }
  return "?";
}

const char* OutputKindName(OutputKind kind) {
  switch (kind) {
    case OutputKind::kMesh:
      return "mesh";
    case OutputKind::kSvg:
      return "svg";
    case OutputKind::kCsv:
      return "csv";
    case OutputKind::kPly:
      return "ply";
    case OutputKind::kJson:
      return "json";
    case OutputKind::kSegments:
      return "segments";
  }
  return "?";
}

const char* OutputExtension(OutputKind kind) {
  switch (kind) {
    case OutputKind::kSvg:
      return ".svg";
    case OutputKind::kPly:
      return ".ply";
    case OutputKind::kJson:
      return ".json";
    case OutputKind::kSegments:
      return ".obj";
    case OutputKind::kMesh:
    case OutputKind::kCsv:
      return "";
  }
  return "";
}

const PolyMesh& RunInputs::Mesh(const std::string& name) const {
  const auto it = meshes.find(name);
  if (it == meshes.end()) throw InputError("the input " + name + " is required");
  return it->second;
}

const PolyMesh* RunInputs::OptionalMesh(const std::string& name) const {
  const auto it = meshes.find(name);
  return it == meshes.end() ? nullptr : &it->second;
}

std::vector<int> RunInputs::VertexIds(const std::string& name) const {
  const auto it = vertex_ids.find(name);
  return it == vertex_ids.end() ? std::vector<int>() : it->second;
}

const std::vector<Eigen::Vector3d>& RunInputs::Curve(const std::string& name) const {
  const auto it = curves.find(name);
  if (it == curves.end()) throw InputError("the input " + name + " is required");
  return it->second;
}

const BSplineSurface& RunInputs::Surface(const std::string& name) const {
  const auto it = surfaces.find(name);
  if (it == surfaces.end()) throw InputError("the input " + name + " is required");
  return it->second;
}

const std::string* RunInputs::Text(const std::string& name) const {
  const auto it = texts.find(name);
  return it == texts.end() ? nullptr : &it->second;
}

bool RunInputs::Has(const std::string& name) const {
  return meshes.count(name) || vertex_ids.count(name) || curves.count(name) ||
         surfaces.count(name) || texts.count(name);
}

std::string RunInputs::Source(const std::string& name) const {
  const auto it = sources.find(name);
  return it == sources.end() ? name : it->second;
}

void RunContext::Headline(const std::string& text) const {
  if (on_message) on_message({RunMessage::Kind::kHeadline, text});
}

void RunContext::Info(const std::string& text) const {
  if (on_message) on_message({RunMessage::Kind::kInfo, text});
}

const OptionSpec* ProblemSpec::FindOption(const std::string& option) const {
  for (const OptionSpec& spec : options)
    if (spec.name == option) return &spec;
  return nullptr;
}

const InputSpec* ProblemSpec::FindInput(const std::string& input) const {
  for (const InputSpec& spec : inputs)
    if (spec.name == input) return &spec;
  return nullptr;
}

const OutputSpec* ProblemSpec::WarmResolveOutput() const {
  const InputSpec* fixed = FindInput("fixed");
  if (!FindInput("mesh") || !fixed || fixed->kind != InputKind::kVertexIds) return nullptr;
  for (const OutputSpec& o : outputs)
    if (o.kind == OutputKind::kMesh && o.same_connectivity) return &o;
  return nullptr;
}

void Registry::Add(ProblemSpec spec) {
  const auto bad = [&spec](const std::string& why) {
    throw std::invalid_argument("registry: problem '" + spec.name + "': " + why);
  };
  if (!IsIdentifier(spec.name)) bad("the name is not an identifier");
  if (Find(spec.name)) bad("registered twice");
  if (!spec.run) bad("no run");
  std::set<std::string> names;
  const auto unique = [&](const std::string& name) {
    if (!IsIdentifier(name)) bad("'" + name + "' is not an identifier");
    if (!names.insert(name).second) bad("two inputs, outputs or options are named '" + name + "'");
  };
  bool optional_positional = false;
  for (const InputSpec& input : spec.inputs) {
    unique(input.name);
    if (input.positional && (input.required || optional_positional))
      bad("'" + input.name + "': only one optional input may be positional");
    if (input.required && optional_positional)
      bad("'" + input.name + "': a required input after the optional positional one");
    if (input.positional && input.kind == InputKind::kVertexIds)
      bad("'" + input.name + "': vertex ids cannot be positional");
    optional_positional = optional_positional || input.positional;
  }
  if (spec.generator) {
    int meshes = 0;
    for (const OutputSpec& output : spec.outputs) meshes += output.kind == OutputKind::kMesh;
    if (!spec.inputs.empty() || meshes != 1 || !spec.outputs.front().required)
      bad("a generator has no inputs and one mesh output, the first and required");
  }
  for (const ArraySpec& array : spec.arrays) unique(array.name);
  for (const OutputSpec& output : spec.outputs) unique(output.name);
  for (const OptionSpec& option : spec.options) {
    unique(option.name);
    if (!option.negation.empty()) unique(option.negation);
    try {
      if (!option.default_value.is_null()) CheckOptionValue(option, option.default_value);
    } catch (const OptionError& e) {
      bad(std::string("the default of ") + e.what());
    }
  }
  problems_.push_back(std::move(spec));
}

const ProblemSpec* Registry::Find(const std::string& name) const {
  for (const ProblemSpec& spec : problems_)
    if (spec.name == name) return &spec;
  return nullptr;
}

nlohmann::json Registry::SchemaJson() const {
  nlohmann::json problems = nlohmann::json::array();
  for (const ProblemSpec& spec : problems_) {
    nlohmann::json inputs = nlohmann::json::array(), outputs = nlohmann::json::array(),
                   options = nlohmann::json::array();
    for (const InputSpec& i : spec.inputs)
      inputs.push_back({{"name", i.name},
                        {"kind", InputKindName(i.kind)},
                        {"doc", i.doc},
                        {"required", i.required},
                        {"positional", i.IsPositional()}});
    for (const OutputSpec& o : spec.outputs)
      outputs.push_back({{"name", o.name},
                         {"kind", OutputKindName(o.kind)},
                         {"extension", OutputExtension(o.kind)},
                         {"doc", o.doc},
                         {"required", o.required}});
    for (const OptionSpec& o : spec.options) options.push_back(OptionSpecJson(o));
    nlohmann::json arrays = nlohmann::json::array();
    for (const ArraySpec& a : spec.arrays) arrays.push_back({{"name", a.name}, {"doc", a.doc}});
    problems.push_back({{"name", spec.name},
                        {"summary", spec.summary},
                        {"inputs", inputs},
                        {"outputs", outputs},
                        {"options", options},
                        {"arrays", arrays},
                        {"log_measures", spec.log_measures},
                        {"generator", spec.generator},
                        {"warm_resolve", spec.WarmResolveOutput() != nullptr}});
  }
  return {{"version", GprojVersion()}, {"problems", problems}};
}

void ApplyWarmEdit(const ProblemSpec& spec, PolyMesh result, const std::vector<int>& moved,
                   const std::vector<Eigen::Vector3d>& to, const std::vector<int>& fixed,
                   RunInputs* inputs) {
  if (!spec.WarmResolveOutput())
    throw InputError(spec.name +
                     " has no warm re-solve (it needs a mesh input, fixed vertices and a result "
                     "mesh of the input's connectivity)");
  if (moved.size() != to.size())
    throw InputError("moved: " + std::to_string(moved.size()) + " vertices but " +
                     std::to_string(to.size()) + " positions");
  const int n = static_cast<int>(result.n_vertices());
  const auto check = [n](int v, const std::string& what) {
    if (v < 0 || v >= n)
      throw InputError(what + ": vertex " + std::to_string(v) + " is out of range (the mesh has " +
                       std::to_string(n) + " vertices)");
  };
  std::set<int> held;
  for (int v : inputs->VertexIds("fixed")) held.insert(v);
  std::set<int> moved_once;
  for (size_t i = 0; i < moved.size(); ++i) {
    check(moved[i], "moved");
    if (!moved_once.insert(moved[i]).second)
      throw InputError("moved: vertex " + std::to_string(moved[i]) + " is moved twice");
    if (!to[i].allFinite())
      throw InputError("moved: the position of vertex " + std::to_string(moved[i]) +
                       " is not finite");
    result.set_point(result.vertex_handle(moved[i]), {to[i].x(), to[i].y(), to[i].z()});
    held.insert(moved[i]);
  }
  for (int v : fixed) {
    check(v, "fixed");
    held.insert(v);
  }
  inputs->meshes["mesh"] = std::move(result);
  inputs->vertex_ids["fixed"].assign(held.begin(), held.end());
  inputs->sources["fixed"] = "fixed";
  inputs->weld_maps.clear();
  inputs->files.clear();
}

RunResult RunProblem(const ProblemSpec& spec, const RunInputs& inputs,
                     const nlohmann::json& options, const RunContext& context) {
  const nlohmann::json complete = CompleteOptions(spec.options, options);
  for (const InputSpec& input : spec.inputs) {
    if (input.required && !inputs.Has(input.name))
      throw InputError("the input " + input.name + " is required");
  }
  RunResult result = spec.run(inputs, complete, context);
  FailOnNonFiniteMeasures(&result.report);
  ConcludeStatus(&result.report);
  return result;
}

nlohmann::json RunResultJson(const ProblemSpec& spec, const RunResult& result,
                             const nlohmann::json& options, const RunInputs& inputs,
                             const nlohmann::json& output) {
  nlohmann::json extra = result.facts;
  extra["options"] = CompleteOptions(spec.options, options);
  extra["input"] = nullptr;
  bool first = true;
  for (const InputSpec& input : spec.inputs) {
    if (!inputs.Has(input.name)) continue;
    const auto file = inputs.files.find(input.name);
    extra[first ? "input" : input.name] =
        file == inputs.files.end() ? nlohmann::json(nullptr) : nlohmann::json(file->second);
    first = false;
  }
  extra["output"] = output;
  // The final measure the problem's tolerance bounds, and the bound, so that every front end
  // shows that one against it.
  if (!result.tolerance_measure.empty()) {
    extra["tolerance_measure"] = result.tolerance_measure;
    extra["tolerance"] = result.tolerance;
  }
  for (const auto& [name, map] : inputs.weld_maps) {
    const int welded = map.empty() ? 0 : *std::max_element(map.begin(), map.end()) + 1;
    extra["welded"][name] = {{"input_vertices", map.size()}, {"vertices", welded}};
  }
  nlohmann::json report = ReportJson(spec.name, result.report, extra);
  for (size_t i = 0; i < result.history_facts.size() && i < report["history"].size(); ++i)
    report["history"][i].update(result.history_facts[i]);
  return report;
}

namespace {

std::string FlagOf(const std::string& name) {
  std::string flag = "--" + name;
  std::replace(flag.begin(), flag.end(), '_', '-');
  return flag;
}

std::string DefaultText(const OptionSpec& option) {
  if (option.required) return "required";
  if (option.default_value.is_null()) return "none";
  if (option.default_value.is_boolean()) return option.default_value.get<bool>() ? "on" : "off";
  return "`" + OptionText(option.default_value) + "`";
}

// A table cell: no line breaks, '|' escaped.
std::string Cell(std::string text) {
  std::string out;
  for (char c : text) out += c == '|' ? std::string("\\|") : std::string(1, c);
  return out;
}

}  // namespace

std::string SpellOptions(const std::string& text, bool command_line) {
  std::string out;
  size_t at = 0;
  while (true) {
    const size_t open = text.find('`', at);
    const size_t close = open == std::string::npos ? open : text.find('`', open + 1);
    if (close == std::string::npos) break;
    const std::string name = text.substr(open + 1, close - open - 1);
    out += text.substr(at, open - at);
    out += IsIdentifier(name) ? (command_line ? FlagOf(name) : name) : "`" + name + "`";
    at = close + 1;
  }
  return out + text.substr(at);
}

std::string ReferenceMarkdown(const ProblemSpec& spec) {
  std::string md = "# `gproj " + spec.name + "` / `gproj." + spec.name + "()`\n\n";
  md +=
      "<!-- Generated from the registry by `gproj schema --markdown docs/reference`; do not "
      "edit. -->\n\n";
  md += spec.summary + "\n\n## Inputs\n\n";
  md += "| name | kind | command line | Python | |\n|---|---|---|---|---|\n";
  for (const InputSpec& input : spec.inputs) {
    const bool mesh = input.kind == InputKind::kMesh || input.kind == InputKind::kQuadMesh;
    const std::string python =
        mesh ? (input.IsPositional() ? "`V, F` arrays" : "`" + input.name + "=(V, F)`")
             : (input.IsPositional() ? "positional " : "`" + input.name + "=` ") +
                   std::string(input.kind == InputKind::kCurve     ? "(n, 3) array or path"
                               : input.kind == InputKind::kBSpline ? "dict or path"
                               : input.kind == InputKind::kText    ? "str (text) or path"
                               : input.kind == InputKind::kJson    ? "dict, JSON text or path"
                                                                   : "ids, mask or path");
    md += "| `" + input.name + "` | " + InputKindName(input.kind) + " | " +
          (input.IsPositional() ? "positional path" : "`" + FlagOf(input.name) + " FILE`") + " | " +
          python + " | " + Cell(input.doc) + " |\n";
  }
  md += "\n## Outputs\n\n| name | kind | command line | |\n|---|---|---|---|\n";
  for (const OutputSpec& output : spec.outputs)
    md += "| `" + output.name + "` | " + OutputKindName(output.kind) + " | `" +
          (output.name == "output" ? std::string("-o, --output") : FlagOf(output.name)) + " FILE`" +
          (output.required ? " (required)" : "") + " | " + Cell(output.doc) + " |\n";
  md +=
      "| `report` | json | `--report FILE` | converged, iterations, seconds, history, the "
      "initial and final measures, the options |\n";
  md +=
      "\n## Options\n\n| Python keyword | command line | type | default | range | unit | "
      "|\n|---|---|---|---|---|---|---|\n";
  for (const OptionSpec& option : spec.options) {
    std::string type = OptionTypeName(option.type);
    if (!option.choices.empty()) {
      type += ":";
      for (const std::string& c : option.choices) type += " `" + c + "`";
    }
    if (option.type == OptionType::kNumbers && option.count > 0)
      type += " (" + std::to_string(option.count) + ": " + option.placeholder + ")";
    md += "| `" + option.name + "` | `" + FlagOf(option.name) + "`" +
          (option.negation.empty() ? "" : ", `" + FlagOf(option.negation) + "`") + " | " + type +
          " | " + DefaultText(option) + " | " + Cell(option.RangeText()) + " | " + option.unit +
          " | " + Cell(option.doc) + " |\n";
  }
  if (spec.log_measures.empty()) {
    md += "\nNo live log: the run builds its result without iterating.";
  } else {
    md += "\nLive log columns: ";
    for (size_t i = 0; i < spec.log_measures.size(); ++i)
      md += (i ? ", `" : "`") + spec.log_measures[i] + "`";
    md += ".";
  }
  md +=
      "\n\nExit codes (command line): 0 converged (the tolerance is met), 1 bad input or "
      "option (nothing written), 3 tolerance not reached (result written), 4 numerical failure "
      "(nothing written).\n";
  return md;
}

const char* GprojVersion() { return GPROJ_VERSION; }

}  // namespace gproj
