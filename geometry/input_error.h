#pragma once
// The error of bad input at gproj's boundary (files, meshes, B-splines, options): its message
// is one line and names the file and the offending line / vertex / face / option and the rule
// broken, e.g.
//   "grid.obj:12: face 3 references vertex 40, but the file has 36 vertices".
// The command line prints it and exits 1 with nothing written.

#include <stdexcept>

namespace gproj {

class InputError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

}  // namespace gproj
