// libFuzzer target: H-net JSON (the input of `darboux`) through ParseHNetJson, and what
// `darboux` then does with a patchwork it accepts: the default inversion's skin, its measures and
// its JSON, at a low sampling.
#include <cstddef>
#include <cstdint>
#include <string>

#include "gproj/common/input_error.h"
#include "gproj/problems/nets/darboux.h"
#include "gproj/problems/nets/hnet_json.h"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  try {
    const gproj::nets::HNetPatchwork hnet = gproj::nets::ParseHNetJson(
        std::string(reinterpret_cast<const char*>(data), size), "fuzz.json");
    if (hnet.mesh.n_faces() > 64) return 0;  // the reader is the target; keep the skin small
    const gproj::nets::DarbouxSkin skin =
        gproj::nets::MakeDarbouxSkin(hnet, gproj::nets::DefaultInversion(hnet.mesh));
    gproj::nets::MeasureDarbouxSkin(hnet, skin, 2);
    gproj::nets::DarbouxSkinJson(hnet, skin).dump();
  } catch (const gproj::InputError&) {
  }
  return 0;
}
