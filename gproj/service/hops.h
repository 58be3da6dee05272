#pragma once
// Grasshopper's Hops component as a client of the service: one Hops component per problem of
// the registry, described in Hops' JSON (GET /hops lists them, GET /hops/<problem> describes
// one) and solved through POST /solve, whose body names the component in "pointer" and gives
// each input as a data tree ({"ParamName", "InnerTree": {"{0}": [{"type", "data"}]}}).
//
// Hops passes meshes in Rhino's archive format, which needs OpenNURBS; gproj's components take a
// mesh as two inputs instead, NAME_points (Point list) and NAME_faces (Integer list, a flat
// list of four vertex ids per quad; a polygon-mesh input also takes NAME_corners, the vertices
// per face, default 3), which Grasshopper's Deconstruct Mesh and list components give. Options
// are inputs with the schema's defaults and ranges (list-valued options as Text, written as on
// the command line). Outputs: each result mesh as NAME_points (and NAME_faces plus
// NAME_face_sizes unless it keeps the input's connectivity), JSON outputs as Text, then
// converged, status, iterations, one Number per logged measure (the final value) and the
// report (Text, JSON).

#include <nlohmann/json.hpp>
#include <string>

#include "gproj/problems/run/registry.h"
#include "gproj/service/run_request.h"

namespace gproj::service {

// Whether a problem has a Hops component (every problem).
bool HasHopsComponent(const ProblemSpec& spec);
// The component's description (GET /hops/<name>): Uri, Name, Nickname, Description, Category,
// Subcategory, Inputs, Outputs.
nlohmann::json HopsDescription(const ProblemSpec& spec);
// Every component's description (GET /hops).
nlohmann::json HopsComponents(const Registry& registry);

// The problem a solve body's "pointer" names ("hops/planarize", as Hops sends it, or
// "/hops/planarize"); null when it names none.
const ProblemSpec* HopsProblem(const nlohmann::json& body, const Registry& registry);
// A Hops solve body as the service's run request JSON ({"problem", "inputs", "options",
// "outputs"}), for ParseRunRequest. Throws RequestError naming the parameter.
nlohmann::json HopsRunRequest(const nlohmann::json& body, const ProblemSpec& spec);
// The solve answer: one value per output of the description, in its order, each a data tree on
// branch "0"; `errors` and `warnings` as Hops shows them on the component.
nlohmann::json HopsAnswer(const ProblemSpec& spec, const RunResult* result,
                          const nlohmann::json& report, const std::string& status,
                          const std::vector<std::string>& errors,
                          const std::vector<std::string>& warnings);

}  // namespace gproj::service
