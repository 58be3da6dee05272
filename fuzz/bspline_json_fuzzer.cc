// libFuzzer target: B-spline surface JSON through ReadBSplineJson.
#include "fuzz/fuzz_input.h"
#include "gproj/geometry/surface/bspline_surface.h"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  return gproj::fuzz::ReadFromFile(data, size, ".json",
                                   [](const std::string& path) { gproj::ReadBSplineJson(path); });
}
