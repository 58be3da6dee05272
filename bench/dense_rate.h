#pragma once
// The machine's dense floating-point rate, the yardstick for the sparse factorisation's rate:
// a square double-precision multiply through the BLAS that CHOLMOD calls (dgemm), and which
// library that BLAS is.

#include <string>

namespace gproj {

// GFLOP/s of C = A B for n × n matrices (2 n³ flops), best of `repeats` runs.
double DgemmGflops(int n = 3000, int repeats = 3);

// The file of the shared library that provides dgemm_ in this process, e.g.
// ".../openblas-pthread/libblas.so.3" ("unknown" when it cannot be found).
std::string BlasLibrary();

}  // namespace gproj
