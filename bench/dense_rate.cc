#include "dense_rate.h"

#include <dlfcn.h>

#include <algorithm>
#include <chrono>
#include <vector>

extern "C" void dgemm_(const char* transa, const char* transb, const int* m, const int* n,
                       const int* k, const double* alpha, const double* a, const int* lda,
                       const double* b, const int* ldb, const double* beta, double* c,
                       const int* ldc);

namespace gproj {

double DgemmGflops(int n, int repeats) {
  std::vector<double> a(static_cast<size_t>(n) * n), b(a.size()), c(a.size(), 0.0);
  for (size_t i = 0; i < a.size(); ++i) {
    a[i] = 1.0 + 1e-3 * static_cast<double>(i % 97);
    b[i] = 1.0 - 1e-3 * static_cast<double>(i % 89);
  }
  const double alpha = 1.0, beta = 0.0;
  double best = 1e300;
  for (int r = 0; r < repeats; ++r) {
    const auto start = std::chrono::steady_clock::now();
    dgemm_("N", "N", &n, &n, &n, &alpha, a.data(), &n, b.data(), &n, &beta, c.data(), &n);
    best = std::min(
        best, std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count());
  }
  return 2.0 * n * static_cast<double>(n) * n / best / 1e9;
}

std::string BlasLibrary() {
  Dl_info info;
  if (dladdr(reinterpret_cast<void*>(&dgemm_), &info) == 0 || info.dli_fname == nullptr)
    return "unknown";
  char resolved[4096];
  return realpath(info.dli_fname, resolved) != nullptr ? resolved : info.dli_fname;
}

}  // namespace gproj
