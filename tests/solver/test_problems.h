#pragma once
// Small problems shared by the solver tests.

#include <cmath>
#include <vector>

#include "gproj/solver/problem.h"

namespace gproj {

// ‖p‖² − r² = 0 for 2-D points.
class OnCircle : public ConstraintFamily {
 public:
  explicit OnCircle(double radius = 1.0) : ConstraintFamily("on_circle", 1), r2_(radius * radius) {}
  void EvaluateElement(int, const double* p, double* phi, double* jac) const override {
    phi[0] = p[0] * p[0] + p[1] * p[1] - r2_;
    jac[0] = 2 * p[0];
    jac[1] = 2 * p[1];
  }

 private:
  double r2_;
};

// p − p⁰ = 0 (soft).
class Anchor : public ConstraintFamily {
 public:
  explicit Anchor(double weight) : ConstraintFamily("anchor", 2, FamilyRole::kSoft, weight) {}
  void Add(int item, double x, double y) {
    t_.push_back(x);
    t_.push_back(y);
    AddElement({item});
  }
  void EvaluateElement(int e, const double* p, double* phi, double* jac) const override {
    phi[0] = p[0] - t_[2 * e];
    phi[1] = p[1] - t_[2 * e + 1];
    jac[0] = 1, jac[1] = 0, jac[2] = 0, jac[3] = 1;
  }
  bool RowTouches(int, int row, int local) const override { return row == local; }

 private:
  std::vector<double> t_;
};

// Consecutive points: second differences (fairness).
class Smooth : public ConstraintFamily {
 public:
  Smooth() : ConstraintFamily("smooth", 2, FamilyRole::kFairness) {}
  void EvaluateElement(int, const double* p, double* phi, double* jac) const override {
    for (int c = 0; c < 2; ++c) {
      phi[c] = p[c] - 2 * p[2 + c] + p[4 + c];
      for (int l = 0; l < 6; ++l) jac[c * 6 + l] = 0.0;
      jac[c * 6 + c] = 1, jac[c * 6 + 2 + c] = -2, jac[c * 6 + 4 + c] = 1;
    }
  }
};

// n points near the unit circle, anchored, smoothed along the chain.
inline Problem MakeCircleProblem(int n, double anchor_weight) {
  Problem problem;
  const int block = problem.layout().AddBlock("points", n, 2);
  problem.ResizeToLayout();
  auto* circle = problem.AddFamily<OnCircle>();
  auto* anchor = problem.AddFamily<Anchor>(anchor_weight);
  auto* smooth = problem.AddFamily<Smooth>();
  for (int i = 0; i < n; ++i) {
    const double t = 0.3 * i, r = 1.0 + 0.2 * std::sin(3.0 * i);
    const double x = r * std::cos(t), y = r * std::sin(t);
    problem.x().segment<2>(problem.layout().Index(block, i, 0)) << x, y;
    circle->AddElement({problem.layout().Item(block, i)});
    anchor->Add(problem.layout().Item(block, i), x, y);
    if (i >= 2)
      smooth->AddElement({problem.layout().Item(block, i - 2), problem.layout().Item(block, i - 1),
                          problem.layout().Item(block, i)});
  }
  return problem;
}

}  // namespace gproj
