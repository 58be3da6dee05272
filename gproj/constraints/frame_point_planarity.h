#pragma once
// Frame-point planarity across an inner edge of an H-net (004 §2 Prop. 1, §3.2 F_frame):
// faces (b0 b1 b2 b3) and (b0 b3 b4 b5) share the edge b0b3; with the shape parameters W_l,
// W_r of the two patches frozen (normalised so that w = 1 except at b2 and b4, the corners
// opposite b0), the frame points
//   f1 = (b1 + W_l b2) / (1 + W_l),   f4 = (b5 + W_r b4) / (1 + W_r)
// must lie in one plane with b0 and b3. An auxiliary unit normal n per edge:
//   n·(f1 − b0) = 0,  n·(b3 − b0) = 0,  n·(f4 − b0) = 0,  n·n − 1 = 0.
// Items {n, b0, b1, b2, b3, b4, b5}; four rows.

#include <string>
#include <utility>

#include "gproj/solver/term.h"

namespace gproj {

// The frozen shape parameters of one edge's two patches.
struct FrameShape {
  double w_left = 1.0, w_right = 1.0;
};

struct FramePointPlanarityResidual {
  template <typename T>
  void operator()(const FrameShape& shape, const T* n, const T* b0, const T* b1, const T* b2,
                  const T* b3, const T* b4, const T* b5, T* r) const {
    const double wl = shape.w_left, wr = shape.w_right;
    const double l1 = 1.0 / (1.0 + wl), l2 = wl / (1.0 + wl);  // f1 = l1 b1 + l2 b2
    const double r5 = 1.0 / (1.0 + wr), r4 = wr / (1.0 + wr);  // f4 = r4 b4 + r5 b5
    r[0] = T(0.0);
    r[1] = T(0.0);
    r[2] = T(0.0);
    for (int c = 0; c < 3; ++c) {
      r[0] += n[c] * (-b0[c] + l1 * b1[c] + l2 * b2[c]);  // f1 − b0
      r[1] += n[c] * (-b0[c] + b3[c]);                    // b3 − b0
      r[2] += n[c] * (-b0[c] + r4 * b4[c] + r5 * b5[c]);  // f4 − b0
    }
    r[3] = n[0] * n[0] + n[1] * n[1] + n[2] * n[2] - 1.0;
  }
};

using FramePointPlanarityTerm =
    Term<FrameShape, FramePointPlanarityResidual, 4, 3, 3, 3, 3, 3, 3, 3>;

// The shape parameters change every round of the H-net solve, so the rows keep their automatic
// derivatives instead of a quadratic model read off once per solve.
class FramePointPlanarity : public FramePointPlanarityTerm {
 public:
  explicit FramePointPlanarity(double weight = 1.0, std::string name = "frame_planarity")
      : FramePointPlanarityTerm(std::move(name), FramePointPlanarityResidual{},
                                FamilyRole::kConstraint, weight) {}

  // Adds the edge b0b3; returns the element index.
  int AddEdge(int normal, int b0, int b1, int b2, int b3, int b4, int b5, double w_left,
              double w_right) {
    return Add({normal, b0, b1, b2, b3, b4, b5}, FrameShape{w_left, w_right});
  }
  // Sets the frozen shape parameters of element e.
  void SetShapeParameters(int e, double w_left, double w_right) {
    data(e) = FrameShape{w_left, w_right};
  }
};

// The same rows with the shape parameters W_l, W_r as unknowns (for meshes where no exact
// extension exists, 004 §3: "optimization can be employed also in scenarios where we have no
// theoretical guarantee that an H-net exists"), multiplied by (1 + W) / 2 so that they are
// polynomial (and equal the rows above at W = 1):
//   n·((b1 − b0) + W_l (b2 − b0)) / 2 = 0,  n·(b3 − b0) = 0,  n·((b5 − b0) + W_r (b4 − b0)) / 2 =
//   0, n·n − 1 = 0.
// Items {n, b0, b1, b2, b3, b4, b5, W_l, W_r}.
struct FramePointPlanarityWithWeightsResidual {
  template <typename T>
  void operator()(const T* n, const T* b0, const T* b1, const T* b2, const T* b3, const T* b4,
                  const T* b5, const T* wl, const T* wr, T* r) const {
    r[0] = T(0.0);
    r[1] = T(0.0);
    r[2] = T(0.0);
    for (int c = 0; c < 3; ++c) {
      r[0] += n[c] * ((b1[c] - b0[c]) + wl[0] * (b2[c] - b0[c])) * 0.5;
      r[1] += n[c] * (b3[c] - b0[c]);
      r[2] += n[c] * ((b5[c] - b0[c]) + wr[0] * (b4[c] - b0[c])) * 0.5;
    }
    r[3] = n[0] * n[0] + n[1] * n[1] + n[2] * n[2] - 1.0;
  }
};
using FramePointPlanarityWithWeights =
    Term<NoData, FramePointPlanarityWithWeightsResidual, 4, 3, 3, 3, 3, 3, 3, 3, 1, 1>;

// W near 1 (004 eq. 11): W − 1 = 0 and 1/W − 1 = 0, soft. Items {W}.
struct ShapeParameterNearOneResidual {
  template <typename T>
  void operator()(const T* w, T* r) const {
    r[0] = w[0] - 1.0;
    r[1] = 1.0 / w[0] - 1.0;
  }
};

}  // namespace gproj
