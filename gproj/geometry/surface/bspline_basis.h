#pragma once
// B-spline basis functions and their derivatives (The NURBS Book, A2.2–A2.3), written once for
// gproj's surfaces (bspline_surface.cc) and curves (the curvature-relation curve of 003
// §3.2.3). Allocation-free: the caller provides the scratch.

#include <algorithm>
#include <utility>

namespace gproj {

// Scratch doubles BasisFunctionDerivatives needs for degree p.
constexpr int BasisScratchSize(int p) { return (p + 1) * (p + 1) + 4 * (p + 1); }

// The non-zero basis functions N_{span−p+r}(t), r = 0..p, of degree p over the knots knot(i)
// (span with knot(span) ≤ t < knot(span + 1), t inside the domain) and their derivatives up to
// order n ≤ p: ders[k × (p + 1) + r] is the k-th derivative of N_{span−p+r} (k = 0..n).
template <typename Knot>
void BasisFunctionDerivatives(const Knot& knot, int p, int span, double t, int n, double* scratch,
                              double* ders) {
  // ndu(r, j), r ≤ j: the degree-j basis functions (upper triangle); ndu(j, r), j > r: knot
  // differences (lower triangle).
  double* ndu = scratch;
  double* left = ndu + (p + 1) * (p + 1);
  double* right = left + (p + 1);
  double* a = right + (p + 1);  // 2 × (p + 1)
  auto at = [p](double* m, int i, int j) -> double& { return m[i * (p + 1) + j]; };
  at(ndu, 0, 0) = 1.0;
  for (int j = 1; j <= p; ++j) {
    left[j] = t - knot(span + 1 - j);
    right[j] = knot(span + j) - t;
    double saved = 0.0;
    for (int r = 0; r < j; ++r) {
      at(ndu, j, r) = right[r + 1] + left[j - r];
      const double temp = at(ndu, r, j - 1) / at(ndu, j, r);
      at(ndu, r, j) = saved + right[r + 1] * temp;
      saved = left[j - r] * temp;
    }
    at(ndu, j, j) = saved;
  }
  for (int j = 0; j <= p; ++j) ders[j] = at(ndu, j, p);
  for (int r = 0; r <= p; ++r) {
    int s1 = 0, s2 = 1;
    at(a, 0, 0) = 1.0;
    for (int k = 1; k <= n; ++k) {
      double d = 0.0;
      const int rk = r - k, pk = p - k;
      if (r >= k) {
        at(a, s2, 0) = at(a, s1, 0) / at(ndu, pk + 1, rk);
        d = at(a, s2, 0) * at(ndu, rk, pk);
      }
      const int j1 = rk >= -1 ? 1 : -rk;
      const int j2 = r - 1 <= pk ? k - 1 : p - r;
      for (int j = j1; j <= j2; ++j) {
        at(a, s2, j) = (at(a, s1, j) - at(a, s1, j - 1)) / at(ndu, pk + 1, rk + j);
        d += at(a, s2, j) * at(ndu, rk + j, pk);
      }
      if (r <= pk) {
        at(a, s2, k) = -at(a, s1, k - 1) / at(ndu, pk + 1, r);
        d += at(a, s2, k) * at(ndu, r, pk);
      }
      ders[k * (p + 1) + r] = d;
      std::swap(s1, s2);
    }
  }
  double factor = p;
  for (int k = 1; k <= n; ++k) {
    for (int r = 0; r <= p; ++r) ders[k * (p + 1) + r] *= factor;
    factor *= p - k;
  }
}

}  // namespace gproj
