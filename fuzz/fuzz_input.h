#pragma once
// Shared by the libFuzzer targets: the readers take paths, so each input is written to a file
// of this process first. An InputError is the expected answer to bad input; anything else that
// escapes (another exception, a crash, a sanitizer report, a leak, a hang) is a bug.

#include <unistd.h>

#include <cstddef>
#include <cstdint>
#include <cstdio>
#include <string>

#include "gproj/common/input_error.h"

namespace gproj {
namespace fuzz {

// Writes the input to "<tmp>/gproj_fuzz_<pid><extension>" and calls read(path).
template <class Read>
int ReadFromFile(const std::uint8_t* data, std::size_t size, const char* extension, Read read) {
  static const std::string path =
      "/tmp/gproj_fuzz_" + std::to_string(static_cast<long long>(getpid())) + extension;
  std::FILE* file = std::fopen(path.c_str(), "wb");
  if (file == nullptr) return 0;
  const bool written = std::fwrite(data, 1, size, file) == size;
  if (std::fclose(file) != 0 || !written) return 0;
  try {
    read(path);
  } catch (const InputError&) {
  }
  return 0;
}

}  // namespace fuzz
}  // namespace gproj
