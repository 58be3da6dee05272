#pragma once
// The HTTP service's requests and answers as JSON: a run request ({"problem", "inputs",
// "options", "outputs"}) read into the registry's RunInputs, checked as the command line and
// Python check theirs, and a run's result (meshes as vertices and faces, texts, arrays) as JSON.
// Every error is a RequestError naming the field ("inputs.mesh.faces[12]: ...").

#include <nlohmann/json.hpp>
#include <set>
#include <string>

#include "gproj/common/input_error.h"
#include "gproj/problems/run/registry.h"

namespace gproj::service {

// Bad request content: the message starts with the field it names.
class RequestError : public InputError {
 public:
  using InputError::InputError;
};

// What one request may hold, checked before anything is allocated for it.
struct RequestLimits {
  long long max_vertices = 2'000'000;  // per mesh input
  long long max_faces = 2'000'000;     // per mesh input
  long long max_points = 1'000'000;    // per curve or vertex-id list
};

struct RunRequest {
  const ProblemSpec* spec = nullptr;
  RunInputs inputs;
  nlohmann::json options = nlohmann::json::object();
  std::set<std::string> outputs;  // the required outputs and those asked for
  bool weld = false;
  bool soft_free_start = false;  // a re-solve's (RunContext::soft_free_start)
};

// JSON nested deeper than this is refused before it is built (copying and printing a document
// recurse once per level); a run request is 4 levels deep, a B-spline 5.
constexpr int kMaxJsonDepth = 64;

// A request body as JSON; throws RequestError naming where it is not JSON or nests deeper than
// kMaxJsonDepth.
nlohmann::json ParseRequestJson(const std::string& text);

// JSON as text for an answer: invalid UTF-8 (a byte of a file name or a text input quoted in a
// message) replaced, never an exception.
std::string DumpJson(const nlohmann::json& value);

// Reads a run request:
//   problem  a problem of `registry`
//   inputs   input name -> value: a mesh as {"vertices": [[x,y,z],...], "faces": [[i,j,k,l],...]}
//            or as a file's contents {"obj" | "off" | "ply": "..."}; vertex ids as a list of
//            0-based ids; a curve as a list of [x,y,z]; a B-spline as its JSON object; a text as
//            a string; a JSON input (an H-net) as its object or its text. No value names a file on
//            the server.
//   options  option name -> value, as Python's keywords (checked by the schema)
//   outputs  optional outputs wanted besides the required ones (e.g. ["face_values"])
//   weld     merge coincident vertices of the input meshes (default false)
// Throws RequestError naming the field; options are checked (OptionError, an InputError).
RunRequest ParseRunRequest(const nlohmann::json& body, const Registry& registry,
                           const RequestLimits& limits);

// {"vertices": [[x,y,z],...], "faces": [[i,j,k],...]}.
nlohmann::json MeshJson(const PolyMesh& mesh);

// A mesh value of a request ({"vertices", "faces"} or {"obj" | "off" | "ply": contents}) read and
// checked as a run request's mesh input is (the readers' checks and the limits), returned as
// {"vertices", "faces"}: how the web app shows a file before it runs anything on it. Throws
// RequestError naming `field`.
nlohmann::json ReadMeshJson(const nlohmann::json& value, const std::string& field,
                            const RequestLimits& limits);

// The outputs of a finished run: meshes as MeshJson, JSON texts as objects, other texts (SVG,
// CSV, segment OBJ) as strings, arrays as lists of rows; non-finite numbers as null.
nlohmann::json ResultJson(const ProblemSpec& spec, const RunResult& result);

}  // namespace gproj::service
