// libFuzzer target: closed-strip files through ReadClosedStrip.
#include "fuzz/fuzz_input.h"
#include "gproj/problems/marionette/marionette_inputs.h"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  return gproj::fuzz::ReadFromFile(data, size, ".txt", [](const std::string& path) {
    gproj::marionette::ReadClosedStrip(path);
  });
}
