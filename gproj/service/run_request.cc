#include "gproj/service/run_request.h"

#include <cmath>
#include <string>
#include <vector>

#include "gproj/problems/run/report_json.h"

namespace gproj::service {
namespace {

[[noreturn]] void Refuse(const std::string& field, const std::string& rule) {
  throw RequestError(field + ": " + rule);
}

const char* TypeName(const nlohmann::json& value) {
  switch (value.type()) {
    case nlohmann::json::value_t::null:
      return "null";
    case nlohmann::json::value_t::boolean:
      return "a boolean";
    case nlohmann::json::value_t::string:
      return "a string";
    case nlohmann::json::value_t::array:
      return "an array";
    case nlohmann::json::value_t::object:
      return "an object";
    default:
      return "a number";
  }
}

void CheckCount(const std::string& field, std::size_t count, long long limit, const char* what) {
  if (static_cast<long long>(count) > limit)
    Refuse(field, "has " + std::to_string(count) + " " + what + "; the service takes at most " +
                      std::to_string(limit));
}

double Coordinate(const nlohmann::json& value, const std::string& field) {
  if (!value.is_number()) Refuse(field, std::string("expected a number, not ") + TypeName(value));
  const double x = value.get<double>();
  if (!std::isfinite(x)) Refuse(field, "is not finite");
  return x;
}

Eigen::Vector3d Point(const nlohmann::json& value, const std::string& field) {
  if (!value.is_array() || value.size() != 3)
    Refuse(field, std::string("expected a point [x, y, z], not ") +
                      (value.is_array() ? "an array of " + std::to_string(value.size())
                                        : std::string(TypeName(value))));
  return {Coordinate(value[0], field + "[0]"), Coordinate(value[1], field + "[1]"),
          Coordinate(value[2], field + "[2]")};
}

long long Integer(const nlohmann::json& value, const std::string& field) {
  if (value.is_number_unsigned() && value.get<unsigned long long>() > (1ull << 53))
    Refuse(field,
           "the integer " + std::to_string(value.get<unsigned long long>()) + " is out of range");
  if (value.is_number_integer()) return value.get<long long>();
  if (value.is_number_float()) {
    const double x = value.get<double>();
    if (std::isfinite(x) && x == std::floor(x) && std::abs(x) < 9e15)
      return static_cast<long long>(x);
  }
  Refuse(field, std::string("expected an integer, not ") + TypeName(value));
}

const nlohmann::json& Array(const nlohmann::json& value, const std::string& field) {
  if (!value.is_array()) Refuse(field, std::string("expected an array, not ") + TypeName(value));
  return value;
}

// A mesh: {"vertices", "faces"} or a file's contents {"obj" | "off" | "ply": "..."}.
PolygonSoup SoupFromJson(const nlohmann::json& value, const std::string& field,
                         const RequestLimits& limits) {
  if (!value.is_object())
    Refuse(field, std::string("expected a mesh: {\"vertices\": [...], \"faces\": [...]} or "
                              "{\"obj\": \"...\"}, not ") +
                      TypeName(value));
  for (const char* format : {"obj", "off", "ply"}) {
    if (!value.contains(format)) continue;
    if (value.size() != 1)
      Refuse(field, std::string("a mesh given as \"") + format + "\" contents takes no other key");
    const nlohmann::json& contents = value.at(format);
    if (!contents.is_string())
      Refuse(field + "." + format,
             std::string("expected the file's contents as a string, not ") + TypeName(contents));
    PolygonSoup soup = ParsePolygonSoup(field, format, contents.get_ref<const std::string&>());
    CheckCount(field, soup.vertices.size(), limits.max_vertices, "vertices");
    CheckCount(field, soup.faces.size(), limits.max_faces, "faces");
    return soup;
  }
  for (auto it = value.begin(); it != value.end(); ++it)
    if (it.key() != "vertices" && it.key() != "faces")
      Refuse(field, "unknown key \"" + it.key() +
                        "\" (a mesh has \"vertices\" and \"faces\", or one of \"obj\", \"off\", "
                        "\"ply\")");
  if (!value.contains("vertices")) Refuse(field, "has no \"vertices\"");
  if (!value.contains("faces")) Refuse(field, "has no \"faces\"");
  const nlohmann::json& vertices = Array(value.at("vertices"), field + ".vertices");
  const nlohmann::json& faces = Array(value.at("faces"), field + ".faces");
  CheckCount(field + ".vertices", vertices.size(), limits.max_vertices, "vertices");
  CheckCount(field + ".faces", faces.size(), limits.max_faces, "faces");
  PolygonSoup soup;
  soup.vertices.reserve(vertices.size());
  for (std::size_t v = 0; v < vertices.size(); ++v)
    soup.vertices.push_back(Point(vertices[v], field + ".vertices[" + std::to_string(v) + "]"));
  soup.faces.reserve(faces.size());
  const long long n = static_cast<long long>(soup.vertices.size());
  for (std::size_t f = 0; f < faces.size(); ++f) {
    const std::string where = field + ".faces[" + std::to_string(f) + "]";
    const nlohmann::json& face = Array(faces[f], where);
    if (face.size() < 3)
      Refuse(where, "a face needs at least 3 vertices, got " + std::to_string(face.size()));
    if (static_cast<long long>(face.size()) > n)
      Refuse(where, "has " + std::to_string(face.size()) + " vertices; the mesh has only " +
                        std::to_string(n));
    std::vector<int>& ids = soup.faces.emplace_back();
    for (std::size_t k = 0; k < face.size(); ++k) {
      const long long id = Integer(face[k], where + "[" + std::to_string(k) + "]");
      if (id < 0 || id >= n)
        Refuse(where, "vertex " + std::to_string(id) + " is out of range (the mesh has " +
                          std::to_string(n) + " vertices)");
      ids.push_back(static_cast<int>(id));
    }
  }
  return soup;
}

std::vector<int> VertexIdsFromJson(const nlohmann::json& value, const std::string& field,
                                   int num_vertices, const RequestLimits& limits) {
  const nlohmann::json& ids = Array(value, field);
  CheckCount(field, ids.size(), limits.max_points, "ids");
  std::vector<int> out;
  out.reserve(ids.size());
  for (std::size_t i = 0; i < ids.size(); ++i) {
    const std::string where = field + "[" + std::to_string(i) + "]";
    const long long id = Integer(ids[i], where);
    if (num_vertices < 0) Refuse(field, "vertex ids need a mesh input first");
    if (id < 0 || id >= num_vertices)
      Refuse(where, "vertex " + std::to_string(id) + " is out of range (the mesh has " +
                        std::to_string(num_vertices) + " vertices)");
    out.push_back(static_cast<int>(id));
  }
  return out;
}

std::vector<Eigen::Vector3d> CurveFromJson(const nlohmann::json& value, const std::string& field,
                                           const RequestLimits& limits) {
  const nlohmann::json& points = Array(value, field);
  CheckCount(field, points.size(), limits.max_points, "points");
  if (points.size() < 2)
    Refuse(field, "a curve needs at least 2 points, got " + std::to_string(points.size()));
  std::vector<Eigen::Vector3d> out;
  out.reserve(points.size());
  for (std::size_t i = 0; i < points.size(); ++i) {
    out.push_back(Point(points[i], field + "[" + std::to_string(i) + "]"));
    if (i > 0 && out[i] == out[i - 1])
      Refuse(field + "[" + std::to_string(i) + "]", "repeats the point before");
  }
  return out;
}

std::string ProblemNames(const Registry& registry) {
  std::string names;
  for (const ProblemSpec& spec : registry.problems())
    names += (names.empty() ? "" : ", ") + spec.name;
  return names;
}

}  // namespace

nlohmann::json ParseRequestJson(const std::string& text) {
  const auto depth_check = [](int depth, nlohmann::json::parse_event_t, nlohmann::json&) {
    if (depth > kMaxJsonDepth)
      throw RequestError("request: the JSON nests deeper than " + std::to_string(kMaxJsonDepth) +
                         " levels");
    return true;
  };
  const std::size_t nul = text.find('\0');
  if (nul != std::string::npos)
    throw RequestError("request: the body is not JSON (a NUL byte at byte " + std::to_string(nul) +
                       ")");
  try {
    return nlohmann::json::parse(text, depth_check);
  } catch (const nlohmann::json::parse_error& e) {
    std::string where = e.what();
    const std::size_t at = where.find("parse error");
    if (at != std::string::npos) where = where.substr(at);
    throw RequestError("request: the body is not JSON (" + where + ")");
  } catch (const nlohmann::json::exception& e) {
    // out_of_range 406: a number beyond double's range (1e400), which JSON allows but no field
    // of a request can take.
    std::string what = e.what();
    const std::size_t at = what.find("] ");
    if (at != std::string::npos) what = what.substr(at + 2);
    throw RequestError("request: the body is not usable JSON (" + what + ")");
  }
}

std::string DumpJson(const nlohmann::json& value) {
  return value.dump(-1, ' ', false, nlohmann::json::error_handler_t::replace);
}

RunRequest ParseRunRequest(const nlohmann::json& body, const Registry& registry,
                           const RequestLimits& limits) {
  if (!body.is_object())
    Refuse("request", std::string("expected a JSON object, not ") + TypeName(body));
  for (auto it = body.begin(); it != body.end(); ++it)
    if (it.key() != "problem" && it.key() != "inputs" && it.key() != "options" &&
        it.key() != "outputs" && it.key() != "weld")
      Refuse(it.key(),
             "unknown key (a run request has problem, inputs, options, outputs and weld)");
  if (!body.contains("problem") || !body.at("problem").is_string())
    Refuse("problem", "expected the name of a problem (" + ProblemNames(registry) + ")");
  RunRequest request;
  const std::string& name = body.at("problem").get_ref<const std::string&>();
  request.spec = registry.Find(name);
  if (!request.spec)
    Refuse("problem", "no problem named \"" + name + "\" (" + ProblemNames(registry) + ")");
  const ProblemSpec& spec = *request.spec;
  if (body.contains("weld")) {
    if (!body.at("weld").is_boolean()) Refuse("weld", "expected true or false");
    request.weld = body.at("weld").get<bool>();
  }

  const nlohmann::json inputs = body.value("inputs", nlohmann::json::object());
  if (!inputs.is_object())
    Refuse("inputs",
           std::string("expected an object (input name -> value), not ") + TypeName(inputs));
  for (auto it = inputs.begin(); it != inputs.end(); ++it)
    if (!spec.FindInput(it.key())) {
      std::string names;
      for (const InputSpec& input : spec.inputs) names += (names.empty() ? "" : ", ") + input.name;
      Refuse("inputs." + it.key(), spec.name + " has no such input (" +
                                       (names.empty() ? std::string("it takes none") : names) +
                                       ")");
    }
  int num_vertices = -1;
  // Meshes first: vertex ids number the first mesh's vertices.
  for (const bool meshes : {true, false}) {
    for (const InputSpec& input : spec.inputs) {
      const bool mesh = input.kind == InputKind::kMesh || input.kind == InputKind::kQuadMesh;
      if (mesh != meshes) continue;
      const std::string field = "inputs." + input.name;
      if (!inputs.contains(input.name) || inputs.at(input.name).is_null()) {
        if (input.required) Refuse(field, "is required (" + input.doc + ")");
        continue;
      }
      const nlohmann::json& value = inputs.at(input.name);
      request.inputs.sources[input.name] = field;
      switch (input.kind) {
        case InputKind::kMesh:
        case InputKind::kQuadMesh: {
          const PolygonSoup soup = SoupFromJson(value, field, limits);
          std::vector<int> map;
          request.inputs.meshes[input.name] =
              BuildMesh(soup, field,
                        MeshRequirements{input.kind == InputKind::kQuadMesh, request.weld}, &map);
          if (request.weld) request.inputs.weld_maps[input.name] = std::move(map);
          if (num_vertices < 0)
            num_vertices = static_cast<int>(request.inputs.meshes[input.name].n_vertices());
          break;
        }
        case InputKind::kVertexIds:
          request.inputs.vertex_ids[input.name] =
              VertexIdsFromJson(value, field, num_vertices, limits);
          break;
        case InputKind::kCurve:
          request.inputs.curves[input.name] = CurveFromJson(value, field, limits);
          break;
        case InputKind::kBSpline:
          if (!value.is_object())
            Refuse(field,
                   std::string("expected the B-spline's JSON object, not ") + TypeName(value));
          request.inputs.surfaces[input.name] = ParseBSplineJson(DumpJson(value), field);
          break;
        case InputKind::kText:
          if (!value.is_string())
            Refuse(field, std::string("expected the text as a string, not ") + TypeName(value));
          request.inputs.texts[input.name] = value.get<std::string>();
          break;
        case InputKind::kJson:
          if (!value.is_object() && !value.is_string())
            Refuse(field,
                   std::string("expected a JSON object (or its text), not ") + TypeName(value));
          request.inputs.texts[input.name] =
              value.is_string() ? value.get<std::string>() : DumpJson(value);
          break;
      }
    }
  }

  if (body.contains("options")) {
    const nlohmann::json& options = body.at("options");
    if (!options.is_object())
      Refuse("options",
             std::string("expected an object (option name -> value), not ") + TypeName(options));
    for (auto it = options.begin(); it != options.end(); ++it)
      if (!it.value().is_null()) request.options[it.key()] = it.value();
  }
  request.options = CompleteOptions(spec.options, request.options);  // OptionError names it

  for (const OutputSpec& output : spec.outputs)
    if (output.required) request.outputs.insert(output.name);
  if (body.contains("outputs")) {
    const nlohmann::json& outputs = Array(body.at("outputs"), "outputs");
    for (std::size_t i = 0; i < outputs.size(); ++i) {
      const std::string where = "outputs[" + std::to_string(i) + "]";
      if (!outputs[i].is_string())
        Refuse(where, std::string("expected an output name, not ") + TypeName(outputs[i]));
      const std::string& output = outputs[i].get_ref<const std::string&>();
      bool known = false;
      std::string names;
      for (const OutputSpec& o : spec.outputs) {
        known = known || o.name == output;
        names += (names.empty() ? "" : ", ") + o.name;
      }
      if (!known) Refuse(where, spec.name + " has no output \"" + output + "\" (" + names + ")");
      request.outputs.insert(output);
    }
  }
  return request;
}

nlohmann::json MeshJson(const PolyMesh& mesh) {
  nlohmann::json vertices = nlohmann::json::array(), faces = nlohmann::json::array();
  for (const auto vh : mesh.vertices()) {
    const auto& p = mesh.point(vh);
    vertices.push_back({JsonNumber(p[0]), JsonNumber(p[1]), JsonNumber(p[2])});
  }
  for (const auto fh : mesh.faces()) {
    nlohmann::json face = nlohmann::json::array();
    for (const auto vh : mesh.fv_range(fh)) face.push_back(vh.idx());
    faces.push_back(std::move(face));
  }
  return {{"vertices", std::move(vertices)}, {"faces", std::move(faces)}};
}

nlohmann::json ReadMeshJson(const nlohmann::json& value, const std::string& field,
                            const RequestLimits& limits) {
  const PolygonSoup soup = SoupFromJson(value, field, limits);
  nlohmann::json vertices = nlohmann::json::array(), faces = nlohmann::json::array();
  for (const Eigen::Vector3d& p : soup.vertices) vertices.push_back({p.x(), p.y(), p.z()});
  for (const std::vector<int>& face : soup.faces) faces.push_back(face);
  return {{"vertices", std::move(vertices)}, {"faces", std::move(faces)}};
}

nlohmann::json ResultJson(const ProblemSpec& spec, const RunResult& result) {
  nlohmann::json out = nlohmann::json::object();
  if (result.report.failed) return out;
  for (const auto& [name, mesh] : result.meshes) out[name] = MeshJson(mesh);
  for (const auto& [name, text] : result.texts) {
    const OutputSpec* output = nullptr;
    for (const OutputSpec& o : spec.outputs)
      if (o.name == name) output = &o;
    out[name] = output && output->kind == OutputKind::kJson
                    ? nlohmann::json::parse(text, nullptr, /*allow_exceptions=*/false)
                    : nlohmann::json(text);
  }
  if (!result.arrays.empty()) {
    nlohmann::json arrays = nlohmann::json::object();
    for (const auto& [name, array] : result.arrays) {
      nlohmann::json rows = nlohmann::json::array();
      for (Eigen::Index i = 0; i < array.rows(); ++i) {
        nlohmann::json row = nlohmann::json::array();
        for (Eigen::Index j = 0; j < array.cols(); ++j) row.push_back(JsonNumber(array(i, j)));
        rows.push_back(std::move(row));
      }
      arrays[name] = std::move(rows);
    }
    out["arrays"] = std::move(arrays);
  }
  return out;
}

}  // namespace gproj::service
