#include "gproj/service/web_app.h"

#include <limits.h>
#include <stdlib.h>
#include <unistd.h>

#include <cmath>
#include <fstream>
#include <sstream>

#include "gproj/common/input_error.h"
#include "gproj/geometry/surface/bspline_surface.h"

namespace gproj::service {
namespace {

bool ReadWhole(const std::string& path, std::string* content) {
  std::ifstream in(path, std::ios::binary);
  if (!in) return false;
  std::ostringstream text;
  text << in.rdbuf();
  *content = text.str();
  return static_cast<bool>(in) || in.eof();
}

std::string TypeOf(const std::string& path) {
  auto ends = [&path](const std::string& tail) {
    return path.size() >= tail.size() &&
           path.compare(path.size() - tail.size(), tail.size(), tail) == 0;
  };
  if (ends(".html")) return "text/html; charset=utf-8";
  if (ends(".js")) return "text/javascript; charset=utf-8";
  if (ends(".css")) return "text/css; charset=utf-8";
  if (ends(".svg")) return "image/svg+xml";
  return "application/octet-stream";
}

// `relative` under the installed data folder (bin/../share/gproj) of the running program, if
// `marker` (a file under it) exists there; else empty.
std::string Installed(const std::string& relative, const std::string& marker) {
  char exe[4096];
  const ssize_t n = readlink("/proc/self/exe", exe, sizeof(exe) - 1);
  if (n <= 0) return "";
  std::string dir(exe, static_cast<size_t>(n));
  dir = dir.substr(0, dir.find_last_of('/'));  // .../bin
  const std::string candidate = dir + "/../" GPROJ_INSTALL_DATADIR "/gproj/" + relative;
  std::ifstream probe(candidate + "/" + marker);
  if (!probe) return "";
  char real[PATH_MAX];
  return realpath(candidate.c_str(), real) ? std::string(real) : candidate;
}

}  // namespace

std::string DefaultWebDir() {
  const std::string installed = Installed("web", "app/index.html");
  return installed.empty() ? GPROJ_WEB_DIR : installed;
}

std::string DefaultExamplesDir() {
  const std::string installed = Installed("examples", "noisy_grid_21x21.obj");
  return installed.empty() ? GPROJ_EXAMPLES_DIR : installed;
}

nlohmann::json ReadDroppedMesh(const nlohmann::json& body, const RequestLimits& limits) {
  nlohmann::json mesh = body;
  std::string field = "mesh";
  if (mesh.is_object() && mesh.contains("name")) {
    const nlohmann::json& name = mesh.at("name");
    if (!name.is_string() || name.get_ref<const std::string&>().empty() ||
        name.get_ref<const std::string&>().size() > 255)
      throw RequestError("name: expected the file's name (1 to 255 characters)");
    field = name.get<std::string>();
    mesh.erase("name");
  }
  return ReadMeshJson(mesh, field, limits);
}

std::map<std::string, WebFile> LoadWebFiles(const std::string& web_dir, std::string* missing) {
  // URL path -> file under web_dir: the app's own files, then the packages' (web/package.json).
  static const std::pair<const char*, const char*> kFiles[] = {
      {"/", "app/index.html"},
      {"/app.js", "app/app.js"},
      {"/style.css", "app/style.css"},
      {"/vendor/three.module.js", "node_modules/three/build/three.module.js"},
      {"/vendor/OrbitControls.js", "node_modules/three/examples/jsm/controls/OrbitControls.js"},
      {"/vendor/lil-gui.esm.js", "node_modules/lil-gui/dist/lil-gui.esm.js"},
      {"/vendor/lil-gui.css", "node_modules/lil-gui/dist/lil-gui.css"},
  };
  std::map<std::string, WebFile> files;
  missing->clear();
  for (const auto& [url, relative] : kFiles) {
    const std::string path = web_dir + "/" + relative;
    WebFile file;
    file.type = TypeOf(path);
    if (!ReadWhole(path, &file.content)) {
      if (missing->empty()) *missing = path;
      continue;
    }
    files[url] = std::move(file);
  }
  if (!missing->empty()) {
    files.clear();
    files["/"] = {
        "<!doctype html><meta charset=utf-8><title>gproj</title><body data-status=failed>"
        "<h1>gproj serve</h1><p>The web app is not installed: " +
            *missing +
            " is missing. Install its packages with <code>npm ci --prefix web</code> "
            "(the quick start does) and restart <code>gproj serve</code>. The API "
            "answers at <a href=/api>/api</a>.</p>",
        "text/html; charset=utf-8"};
  }
  return files;
}

std::vector<Example> LoadExamples(const std::string& examples_dir, const RequestLimits& limits) {
  struct Shipped {
    const char* title;
    const char* problem;
    // input -> file; the first is the main one, and names the example
    std::vector<std::pair<const char*, const char*>> inputs;
    nlohmann::json options;
    nlohmann::json outputs;
  };
  // Guide values of the Marionette plan (the demo's): a sine along row 0, a bow along column 0.
  nlohmann::json row = nlohmann::json::array(), column = nlohmann::json::array();
  for (int j = 0; j <= 20; ++j) row.push_back(std::round(1e4 * 0.4 * std::sin(j / 4.0)) / 1e4);
  for (int i = 0; i <= 20; ++i)
    column.push_back(std::round(1e4 * 0.3 * (1 - std::cos(i / 5.0))) / 1e4);
  const std::vector<Shipped> shipped = {
      {"Noisy 21 x 21 quad grid",
       "planarize",
       {{"mesh", "noisy_grid_21x21.obj"}},
       nlohmann::json::object(),
       {"face_values"}},
      {"Surface of revolution, 13 x 17: circular quads",
       "planarize",
       {{"mesh", "revolution_13x17.obj"}},
       {{"circular", true}},
       {"face_values"}},
      {"Jittered asymptotic grid of Enneper's surface: H-net",
       "hnet",
       {{"mesh", "enneper_41x41_jitter3.obj"}, {"reference", "enneper_41x41.obj"}},
       {{"samples", 4}},
       {"surface_mesh", "face_values"}},
      {"Marionette: a 20 x 20 plan lifted from two guide curves",
       "marionette",
       {{"plan", "marionette_plan_21x21.obj"}},
       {{"row", row}, {"column", column}},
       nlohmann::json::array()},
      {"Marionette: a plan with a valence-6 vertex, six guides",
       "marionette",
       {{"plan", "marionette_plan_valence6.obj"}, {"guides", "marionette_valence6_guides.txt"}},
       nlohmann::json::object(),
       nlohmann::json::array()},
      {"Weingarten: a freeform 10 x 10 B-spline, curvature isolines aligned",
       "weingarten",
       {{"surface", "freeform_10x10.json"}},
       nlohmann::json::object(),
       {"surface_mesh", "diagram"}},
      {"Weingarten: a bump made CMC, H = -0.1 (003 Fig. 3)",
       "weingarten",
       {{"surface", "bump_14x14.json"}},
       {{"preset", "fig3"}, {"linear", {1, 0, 0.1}}},
       {"surface_mesh", "diagram"}},
  };
  std::vector<Example> examples;
  for (const Shipped& s : shipped) {
    Example example;
    example.title = s.title;
    example.problem = s.problem;
    example.main = s.inputs.front().first;
    example.options = s.options;
    example.outputs = s.outputs;
    for (const auto& [input, file] : s.inputs) {
      const std::string path = examples_dir + "/" + file;
      std::string content;
      if (!ReadWhole(path, &content))
        throw InputError(path + ": cannot read the shipped example (gproj serve --examples)");
      const std::string name = file, format = name.substr(name.rfind('.') + 1);
      nlohmann::json value;
      if (format == "obj" || format == "off" || format == "ply") {
        value = ReadMeshJson({{format, content}}, path, limits);
        if (example.preview.is_null()) example.preview = value;
      } else if (format == "json") {
        const BSplineSurface surface = ParseBSplineJson(content, path);
        value = nlohmann::json::parse(content);
        if (example.preview.is_null())
          example.preview = MeshJson(SampleSurfaceMesh(surface, 4 * surface.nu, 4 * surface.nv));
      } else {
        value = content;
      }
      if (example.name.empty()) example.name = name.substr(0, name.rfind('.'));
      example.inputs[input] = std::move(value);
    }
    examples.push_back(std::move(example));
  }
  return examples;
}

nlohmann::json ExampleJson(const Example& example, bool inputs) {
  nlohmann::json json = {{"name", example.name},
                         {"title", example.title},
                         {"problem", example.problem},
                         {"options", example.options},
                         {"outputs", example.outputs}};
  json["main"] = example.main;
  if (inputs) {
    json["inputs"] = example.inputs;
    json["preview"] = example.preview;
  }
  return json;
}

}  // namespace gproj::service
