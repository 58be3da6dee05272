#pragma once
// The message of the InputError a call throws, for tests of bad-input messages.

#include <functional>
#include <string>

#include "gproj/common/input_error.h"

namespace gproj {

// What `f` throws as InputError; "(no error)" when it throws none.
inline std::string InputErrorOf(const std::function<void()>& f) {
  try {
    f();
  } catch (const InputError& e) {
    return e.what();
  }
  return "(no error)";
}

}  // namespace gproj
