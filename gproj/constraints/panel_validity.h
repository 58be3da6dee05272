#pragma once
// Valid panels (Tang et al. 2014 §4; docs/method.md, "Inequalities"): bounds that keep a quad mesh
// buildable while other rows make it planar, circular or asymptotic.
//   Corner angles: for corner i of quad (v0, v1, v2, v3)
//     sin∠_i = ((v_{i+1} − v_i) × (v_{i−1} − v_i)) · N / (|v_{i+1} − v_i| |v_{i−1} − v_i| |N|),
//     N = (v2 − v0) × (v3 − v1)  (the diagonals' normal),
//   and g_i = sin∠_i − s_i ≥ 0 keeps ∠_i in [arcsin s_i, 180° − arcsin s_i]: the signed sine is
//   negative at a reflex corner, so s_i > 0 on all four corners means a convex, unfolded quad.
//   Edge lengths: g = (v_b − v_a) · u − ℓ_min ≥ 0 with u the edge's unit direction in the input,
//   and ℓ_max² − |v_b − v_a|² ≥ 0. The lower row keeps its gradient at zero length (|e|² − ℓ²
//   does not: an edge collapsed past it stayed collapsed) and counts a flipped edge as broken.
// Both are added through AddInequalities (one slack per row, eliminated with the auxiliaries).

#include <array>
#include <cmath>
#include <tuple>
#include <utility>

#include "gproj/geometry/mesh/quad_shape.h"
#include "gproj/solver/inequality.h"

namespace gproj {

// Lower bounds s_i on the four corner sines of one quad.
struct QuadCornerBounds {
  std::array<double, 4> min_sine = {0.0, 0.0, 0.0, 0.0};
};

struct QuadCornerResidual {
  template <typename T>
  void operator()(const QuadCornerBounds& bounds, const T* v0, const T* v1, const T* v2,
                  const T* v3, T* r) const {
    QuadCornerSines(v0, v1, v2, v3, r);
    for (int i = 0; i < 4; ++i) r[i] -= bounds.min_sine[i];
  }
};

// One bound on an edge: a lower bound `length` along `direction` (unit), or, with a zero
// direction, an upper bound `length` on |v_b − v_a|.
struct EdgeLengthBound {
  std::array<double, 3> direction = {0.0, 0.0, 0.0};
  double length = 0.0;
};

struct EdgeLengthResidual {
  template <typename T>
  void operator()(const EdgeLengthBound& bound, const T* a, const T* b, T* r) const {
    const auto& u = bound.direction;
    if (u[0] != 0.0 || u[1] != 0.0 || u[2] != 0.0) {
      r[0] = (b[0] - a[0]) * u[0] + (b[1] - a[1]) * u[1] + (b[2] - a[2]) * u[2] - bound.length;
      return;
    }
    const T squared = (b[0] - a[0]) * (b[0] - a[0]) + (b[1] - a[1]) * (b[1] - a[1]) +
                      (b[2] - a[2]) * (b[2] - a[2]);
    r[0] = bound.length * bound.length - squared;
  }
};

using QuadCornerTerm = InequalityTerm<QuadCornerBounds, QuadCornerResidual, 4, 3, 3, 3, 3>;

// Polygons of N ≥ 5 corners: corner i's sine is measured against the polygon's vector-area
// normal N = Σ_k v_k × v_{k+1} (the quads' diagonal normal has no analogue), with the same
// sign convention: g_i = sin∠_i − s_i ≥ 0.
template <int N>
struct PolygonCornerBounds {
  std::array<double, N> min_sine{};
};

// The signed corner sines of an n-gon against its vector-area normal (any scalar type).
template <typename T>
void PolygonCornerSines(const T* const* v, int n, T* sines) {
  T normal[3] = {T(0.0), T(0.0), T(0.0)};
  for (int k = 0; k < n; ++k) {
    const T* a = v[k];
    const T* b = v[(k + 1) % n];
    normal[0] += a[1] * b[2] - a[2] * b[1];
    normal[1] += a[2] * b[0] - a[0] * b[2];
    normal[2] += a[0] * b[1] - a[1] * b[0];
  }
  using std::sqrt;
  const T tiny(1e-300);
  const T n_norm =
      sqrt(normal[0] * normal[0] + normal[1] * normal[1] + normal[2] * normal[2] + tiny);
  for (int i = 0; i < n; ++i) {
    const T* p = v[i];
    const T* next = v[(i + 1) % n];
    const T* prev = v[(i + n - 1) % n];
    T a[3], b[3];
    for (int c = 0; c < 3; ++c) a[c] = next[c] - p[c], b[c] = prev[c] - p[c];
    const T cross_n = (a[1] * b[2] - a[2] * b[1]) * normal[0] +
                      (a[2] * b[0] - a[0] * b[2]) * normal[1] +
                      (a[0] * b[1] - a[1] * b[0]) * normal[2];
    const T a_norm = sqrt(a[0] * a[0] + a[1] * a[1] + a[2] * a[2] + tiny);
    const T b_norm = sqrt(b[0] * b[0] + b[1] * b[1] + b[2] * b[2] + tiny);
    sines[i] = cross_n / (a_norm * b_norm * n_norm);
  }
}

// g(bounds, v_0, …, v_{N−1}, r).
template <int N>
struct PolygonCornerResidual {
  template <typename T, typename... Rest>
  void operator()(const PolygonCornerBounds<N>& bounds, const T* v0, Rest... rest) const {
    static_assert(sizeof...(Rest) == N, "N corners, then the residual");
    const auto args = std::forward_as_tuple(v0, rest...);
    const T* v[N];
    Collect(args, v, std::make_index_sequence<N>());
    T* r = std::get<N>(args);
    PolygonCornerSines(v, N, r);
    for (int i = 0; i < N; ++i) r[i] -= bounds.min_sine[i];
  }

 private:
  template <typename Tuple, typename T, size_t... I>
  static void Collect(const Tuple& args, const T** v, std::index_sequence<I...>) {
    ((v[I] = std::get<I>(args)), ...);
  }
};
using EdgeLengthTerm = InequalityTerm<EdgeLengthBound, EdgeLengthResidual, 1, 3, 3>;

}  // namespace gproj
