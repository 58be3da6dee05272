#pragma once
// What `gproj serve` answers besides the API: the web app's files (web/app and the npm packages
// it uses, read once at start, so no request ever names a file on the server) and the shipped
// examples the app can open (examples/data, read once at start as well).

#include <map>
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "gproj/service/run_request.h"

namespace gproj::service {

// POST /api/meshes: {"name": "FILE.obj", "obj" | "off" | "ply": contents} (or a mesh as
// {"vertices", "faces"}) read and checked as a run's mesh input is -> {"vertices", "faces"}, how
// the web app shows a file opened or dropped. Throws RequestError naming the file (its name) and
// line, or the field.
nlohmann::json ReadDroppedMesh(const nlohmann::json& body, const RequestLimits& limits);

struct WebFile {
  std::string content;
  std::string type;  // Content-Type
};

// URL path ("/", "/app.js", "/vendor/three.module.js", ...) -> file. `web_dir` holds app/ and
// node_modules/ (npm ci --prefix web). When a package is missing, "/" is a page that says how
// to install it and *missing names it.
std::map<std::string, WebFile> LoadWebFiles(const std::string& web_dir, std::string* missing);

// Where gproj serve reads the web app (web/: app/ and node_modules/) and the examples
// (examples/data) when not told: an installed gproj's share/gproj/web and share/gproj/examples
// (found from the running program's path, so an installed tree may be moved), else the source
// tree it was built from.
std::string DefaultWebDir();
std::string DefaultExamplesDir();

// A shipped example: the files of examples/data a problem runs on, named by its main file's
// stem (noisy_grid_21x21), as `/?example=NAME` takes it.
struct Example {
  std::string name;     // the main file's name without its extension
  std::string title;    // one line for a menu
  std::string problem;  // the problem it is shipped for (another may be chosen)
  std::string main;     // the input `preview` shows (e.g. "mesh", "plan", "surface")
  nlohmann::json inputs = nlohmann::json::object();   // input name -> value, as a run takes it
  nlohmann::json options = nlohmann::json::object();  // problem options
  nlohmann::json outputs = nlohmann::json::array();   // optional outputs worth asking for
  // {"vertices", "faces"}: the main input's mesh, or a B-spline sampled as its surface_mesh
  // output is (4 samples per control point each way), so the result can be compared with it.
  nlohmann::json preview;
};

// The examples of `examples_dir` (examples/data) the web app offers; throws InputError naming a
// file that cannot be read.
std::vector<Example> LoadExamples(const std::string& examples_dir, const RequestLimits& limits);

// {"name", "title", "problem", "main", "options", "outputs"} (with "inputs" and "preview" when
// `inputs`).
nlohmann::json ExampleJson(const Example& example, bool inputs);

}  // namespace gproj::service
