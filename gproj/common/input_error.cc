#include "gproj/common/input_error.h"

#include <unistd.h>

#include <cstdio>

namespace gproj {
namespace {

// Physical memory in bytes; 0 when unknown.
double PhysicalMemory() {
#if defined(_SC_PHYS_PAGES) && defined(_SC_PAGE_SIZE)
  const long pages = sysconf(_SC_PHYS_PAGES);
  const long page_size = sysconf(_SC_PAGE_SIZE);
  if (pages > 0 && page_size > 0) return static_cast<double>(pages) * page_size;
#endif
  return 0.0;
}

}  // namespace

void CheckMemory(const std::string& what, double bytes) {
  const double available = PhysicalMemory();
  if (available > 0.0 && bytes > available) {
    char buffer[160];
    std::snprintf(buffer, sizeof(buffer),
                  " needs about %.3g GB of memory, more than the %.3g GB this machine has",
                  bytes / 1e9, available / 1e9);
    throw InputError(what + buffer);
  }
}

void RefuseNulByte(const std::string& text, const std::string& pre) {
  const std::size_t at = text.find('\0');
  if (at != std::string::npos)
    throw InputError(pre + "a NUL byte at byte " + std::to_string(at) + ": not a JSON text");
}

}  // namespace gproj
