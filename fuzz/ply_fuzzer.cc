// libFuzzer target: PLY meshes through ReadMesh (reading and validation).
#include "fuzz/fuzz_input.h"
#include "gproj/geometry/io/mesh_io.h"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  return gproj::fuzz::ReadFromFile(data, size, ".ply",
                                   [](const std::string& path) { gproj::ReadMesh(path); });
}
