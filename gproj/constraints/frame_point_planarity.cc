#include "gproj/constraints/frame_point_planarity.h"

#include <algorithm>

namespace gproj {

int FramePointPlanarity::AddEdge(int normal, int b0, int b1, int b2, int b3, int b4, int b5,
                                 double w_left, double w_right) {
  w_left_.push_back(w_left);
  w_right_.push_back(w_right);
  return AddElement({normal, b0, b1, b2, b3, b4, b5});
}

void FramePointPlanarity::SetShapeParameters(int e, double w_left, double w_right) {
  w_left_[e] = w_left;
  w_right_[e] = w_right;
}

void FramePointPlanarity::EvaluateElement(int e, const double* x, double* phi, double* jac) const {
  constexpr int kDim = 21;
  std::fill(jac, jac + 4 * kDim, 0.0);
  const double* n = x;
  auto b = [x](int i) { return x + 3 + 3 * i; };
  // Each of rows 0..2 is n · (Σ_i c_i b_i) with Σ c_i = 0.
  const double wl = w_left_[e], wr = w_right_[e];
  const double coefficients[3][6] = {
      {-1.0, 1.0 / (1.0 + wl), wl / (1.0 + wl), 0.0, 0.0, 0.0},  // f1 − b0
      {-1.0, 0.0, 0.0, 1.0, 0.0, 0.0},                           // b3 − b0
      {-1.0, 0.0, 0.0, 0.0, wr / (1.0 + wr), 1.0 / (1.0 + wr)},  // f4 − b0
  };
  for (int r = 0; r < 3; ++r) {
    double* row = jac + r * kDim;
    phi[r] = 0.0;
    for (int c = 0; c < 3; ++c) {
      double direction = 0.0;
      for (int i = 0; i < 6; ++i) direction += coefficients[r][i] * b(i)[c];
      phi[r] += n[c] * direction;
      row[c] = direction;
      for (int i = 0; i < 6; ++i) row[3 + 3 * i + c] = coefficients[r][i] * n[c];
    }
  }
  phi[3] = n[0] * n[0] + n[1] * n[1] + n[2] * n[2] - 1.0;
  for (int c = 0; c < 3; ++c) jac[3 * kDim + c] = 2.0 * n[c];
}

bool FramePointPlanarity::RowTouches(int, int row, int local) const {
  if (local < 3) return true;
  if (row == 3) return false;
  const int vertex = (local - 3) / 3;
  static constexpr bool kUses[3][6] = {{true, true, true, false, false, false},
                                       {true, false, false, true, false, false},
                                       {true, false, false, false, true, true}};
  return kUses[row][vertex];
}

}  // namespace gproj
