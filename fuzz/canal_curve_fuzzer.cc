// libFuzzer target: canal curve files (points, one a line) through ReadPoints.
#include "fuzz/fuzz_input.h"
#include "gproj/geometry/io/text_input.h"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  return gproj::fuzz::ReadFromFile(data, size, ".txt",
                                   [](const std::string& path) { gproj::ReadPoints(path); });
}
