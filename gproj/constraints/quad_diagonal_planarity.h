#pragma once
// Quad planarity by the diagonal-distance approximation of 004 §3.2, option (ii):
//   φ(b0, b1, b2, b3) = n · d,  n = b02 × b13 / ‖b02 × b13‖,  d = (b0 + b2 − b1 − b3) / 2,
// (F_quad = φ²). φ is not quadratic, so its exact gradient (normal included) is used: with
// frozen n the linearisation misses terms of the size of ‖d‖/‖b02‖, which is O(1) for the
// quads of a vertex star, and the iteration diverges.
// Items {b0, b1, b2, b3} (vertices, dimension 3); one row. A vertex star of valence n is made
// planar by n − 2 such quads, without auxiliary variables.

#include <cmath>
#include <string>
#include <utility>

#include "gproj/solver/term.h"

namespace gproj {

struct QuadDiagonalPlanarityResidual {
  template <typename T>
  void operator()(const T* b0, const T* b1, const T* b2, const T* b3, T* r) const {
    T a[3], e[3], d[3];
    for (int k = 0; k < 3; ++k) {
      a[k] = b2[k] - b0[k];
      e[k] = b3[k] - b1[k];
      d[k] = 0.5 * (b0[k] + b2[k] - b1[k] - b3[k]);
    }
    const T c[3] = {a[1] * e[2] - a[2] * e[1], a[2] * e[0] - a[0] * e[2],
                    a[0] * e[1] - a[1] * e[0]};
    const T length2 = c[0] * c[0] + c[1] * c[1] + c[2] * c[2];
    const T cd = c[0] * d[0] + c[1] * d[1] + c[2] * d[2];
    using std::sqrt;
    // Parallel diagonals have no normal: the row is left inert (zero, with zero derivatives,
    // still touching every vertex so that the pattern does not depend on the starting point).
    r[0] = length2 == 0.0 ? 0.0 * cd : cd / sqrt(length2);
  }
};

class QuadDiagonalPlanarity : public Term<NoData, QuadDiagonalPlanarityResidual, 1, 3, 3, 3, 3> {
 public:
  explicit QuadDiagonalPlanarity(std::string name = "star_planarity", double weight = 1.0)
      : Term(std::move(name), QuadDiagonalPlanarityResidual{}, FamilyRole::kConstraint, weight) {}
};

}  // namespace gproj
