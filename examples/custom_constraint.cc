// Defining a new constraint family takes one small class: say which items an element
// touches, then write its rows' values and gradients. The same definition drives guided
// projection and the Ceres cross-check.
//
// Here: points in the plane pulled onto the unit circle (‖p‖² − 1 = 0, quadratic), kept
// close to where they started. Run: ./build/custom_constraint_example
#include <cstdio>

#include "solver/ceres_adapter.h"
#include "solver/guided_projection.h"

namespace {

// ‖p‖² − 1 = 0 for a 2-D point p; one row per element, items {p}.
class OnUnitCircle : public gproj::ConstraintFamily {
 public:
  OnUnitCircle() : ConstraintFamily("on_unit_circle", /*rows_per_element=*/1) {}
  void EvaluateElement(int, const double* p, double* phi, double* jac) const override {
    phi[0] = p[0] * p[0] + p[1] * p[1] - 1.0;
    jac[0] = 2.0 * p[0];
    jac[1] = 2.0 * p[1];
  }
};

// p − p⁰ = 0, a soft regulariser (two rows, items {p}).
class StayNear : public gproj::ConstraintFamily {
 public:
  StayNear() : ConstraintFamily("stay_near", 2, gproj::FamilyRole::kSoft, 0.01) {}
  void Add(int item, double x, double y) {
    targets_.push_back(x);
    targets_.push_back(y);
    AddElement({item});
  }
  void EvaluateElement(int e, const double* p, double* phi, double* jac) const override {
    phi[0] = p[0] - targets_[2 * e];
    phi[1] = p[1] - targets_[2 * e + 1];
    jac[0] = 1.0, jac[1] = 0.0, jac[2] = 0.0, jac[3] = 1.0;
  }
  bool RowTouches(int, int row, int local) const override { return row == local; }

 private:
  std::vector<double> targets_;
};

gproj::Problem MakeProblem() {
  gproj::Problem problem;
  const int points = problem.layout().AddBlock("points", 5, 2);
  problem.ResizeToLayout();
  auto* circle = problem.AddFamily<OnUnitCircle>();
  auto* near = problem.AddFamily<StayNear>();
  for (int i = 0; i < 5; ++i) {
    const double x = 0.5 + 0.3 * i, y = 1.0 - 0.2 * i;
    problem.x().segment<2>(problem.layout().Index(points, i, 0)) << x, y;
    circle->AddElement({problem.layout().Item(points, i)});
    near->Add(problem.layout().Item(points, i), x, y);
  }
  return problem;
}

}  // namespace

int main() {
  gproj::Problem problem = MakeProblem();
  gproj::SolverOptions options;
  options.step_tolerance = 1e-14;
  options.residual_tolerance = 0.0;
  const gproj::SolverSummary summary = gproj::Solve(options, &problem);
  std::printf("%s", summary.FullReport().c_str());

  gproj::Problem same = MakeProblem();
  gproj::CeresOptions ceres_options;
  const ceres::Solver::Summary ceres_summary = gproj::SolveWithCeres(ceres_options, &same);
  std::printf("ceres: %s\n", ceres_summary.BriefReport().c_str());
  std::printf("objective: gproj %.12e, ceres %.12e\n",
              gproj::EvaluateObjective(&problem, options.fairness_weight, problem.x()),
              gproj::EvaluateObjective(&same, options.fairness_weight, same.x()));
  return summary.converged() ? 0 : 1;
}
