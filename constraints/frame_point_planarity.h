#pragma once
// Frame-point planarity across an inner edge of an H-net (004 §2 Prop. 1, §3.2 F_frame):
// faces (b0 b1 b2 b3) and (b0 b3 b4 b5) share the edge b0b3; with the shape parameters W_l,
// W_r of the two patches frozen (normalised so that w = 1 except at b2 and b4, the corners
// opposite b0), the frame points
//   f1 = (b1 + W_l b2) / (1 + W_l),   f4 = (b5 + W_r b4) / (1 + W_r)
// must lie in one plane with b0 and b3. An auxiliary unit normal n per edge:
//   n·(f1 − b0) = 0,  n·(b3 − b0) = 0,  n·(f4 − b0) = 0,  n·n − 1 = 0.
// Items {n, b0, b1, b2, b3, b4, b5}; four rows.

#include <vector>

#include "solver/constraint_family.h"

namespace gproj {

class FramePointPlanarity : public ConstraintFamily {
 public:
  explicit FramePointPlanarity(double weight = 1.0, std::string name = "frame_planarity")
      : ConstraintFamily(std::move(name), 4, FamilyRole::kConstraint, weight) {}

  // Adds the edge b0b3; returns the element index.
  int AddEdge(int normal, int b0, int b1, int b2, int b3, int b4, int b5, double w_left,
              double w_right);
  // Sets the frozen shape parameters of element e.
  void SetShapeParameters(int e, double w_left, double w_right);

  void EvaluateElement(int e, const double* x, double* phi, double* jac) const override;
  bool RowTouches(int e, int row, int local) const override;

 private:
  std::vector<double> w_left_, w_right_;
};

}  // namespace gproj
