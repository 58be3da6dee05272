// libFuzzer target: the HTTP service's request bodies (a run request, or a Hops solve when it
// names a "pointer") through the service's JSON parser (depth-limited), HopsRunRequest and
// ParseRunRequest, as the server reads them before any run starts; and the same body as the web
// app's dropped mesh (POST /api/meshes).
#include <cstddef>
#include <cstdint>
#include <string>

#include "gproj/service/hops.h"
#include "gproj/service/run_request.h"
#include "gproj/service/web_app.h"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const std::string text(reinterpret_cast<const char*>(data), size);
  gproj::service::RequestLimits limits;
  limits.max_vertices = limits.max_faces = limits.max_points = 10000;
  const gproj::Registry& registry = gproj::Registry::Builtin();
  try {
    const nlohmann::json body = gproj::service::ParseRequestJson(text);
    if (const gproj::ProblemSpec* spec = gproj::service::HopsProblem(body, registry))
      gproj::service::ParseRunRequest(gproj::service::HopsRunRequest(body, *spec), registry,
                                      limits);
    else
      gproj::service::ParseRunRequest(body, registry, limits);
  } catch (const gproj::InputError&) {
  }
  try {
    gproj::service::ReadDroppedMesh(gproj::service::ParseRequestJson(text), limits);
  } catch (const gproj::InputError&) {
  }
  return 0;
}
