#pragma once
// The error of bad input at gproj's boundary (files, meshes, B-splines, options): its message
// is one line and names the file and the offending line / vertex / face / option and the rule
// broken, e.g.
//   "grid.obj:12: face 3 references vertex 40, but the file has 36 vertices".
// The command line prints it and exits 1 with nothing written.

#include <stdexcept>
#include <string>

namespace gproj {

class InputError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

// Throws InputError "<what> needs about N GB of memory, more than the M GB this machine has"
// when `bytes` (an estimate made before allocating) exceeds the physical memory; no check where
// that cannot be queried.
void CheckMemory(const std::string& what, double bytes);

// Throws InputError "<pre>a NUL byte at byte N: not a JSON text" when `text` holds one (JSON
// readers take a NUL for the end of the input, so whatever follows it would go unread).
void RefuseNulByte(const std::string& text, const std::string& pre);

}  // namespace gproj
