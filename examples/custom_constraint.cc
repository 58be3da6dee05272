// Writing your own problem with gproj: points in the plane pulled onto the unit circle
// (‖p‖² − 1 = 0, a quadratic constraint), each kept near where it started (a soft term). The
// terms are written once, for any scalar type: gproj derives their derivatives and sparsity,
// and the same definitions run guided projection and the Ceres cross-check.
//
// In the gproj build: ./build/custom_constraint_example. Against an installed gproj:
//   cmake -S examples -B build-example -DCMAKE_PREFIX_PATH=PREFIX && cmake --build build-example
#include <cmath>
#include <cstdio>

#include "gproj/solver/ceres_adapter.h"
#include "gproj/solver/guided_projection.h"

// The custom constraint: one row per point p (an item of 2 scalars).
struct OnUnitCircle {
  template <typename T>
  void operator()(const T* p, T* r) const {
    r[0] = p[0] * p[0] + p[1] * p[1] - 1.0;
  }
};

// A soft term with data beside each element: the point's start position.
struct StayNear {
  template <typename T>
  void operator()(const Eigen::Vector2d& start, const T* p, T* r) const {
    r[0] = p[0] - start.x();
    r[1] = p[1] - start.y();
  }
};

gproj::Problem MakeProblem() {
  gproj::Problem problem;
  const int points = problem.layout().AddBlock("points", 5, 2);  // 5 items of 2 scalars
  problem.ResizeToLayout();
  // AddTerm<rows per element, scalars of each item…>(name, residual[, role, weight]).
  auto* circle = problem.AddTerm<1, 2>("on_unit_circle", OnUnitCircle{});
  auto* near = problem.AddTerm<Eigen::Vector2d, 2, 2>("stay_near", StayNear{},
                                                      gproj::FamilyRole::kSoft, 0.01);
  for (int i = 0; i < 5; ++i) {
    const Eigen::Vector2d start(0.5 + 0.3 * i, 1.0 - 0.2 * i);
    problem.x().segment<2>(problem.layout().Index(points, i, 0)) = start;
    circle->Add({problem.layout().Item(points, i)});
    near->Add({problem.layout().Item(points, i)}, start);
  }
  return problem;
}

int main() {
  // Guided projection with fixed weights stops at a stationary point of
  // ½ Σ w φ² (step tolerance), the objective Ceres minimises from the same terms.
  gproj::Problem problem = MakeProblem();
  gproj::SolverOptions options;
  options.step_tolerance = 1e-14;
  options.residual_tolerance = 0.0;
  const gproj::SolverSummary summary = gproj::Solve(options, &problem);
  std::printf("%s", summary.FullReport().c_str());

  gproj::Problem same = MakeProblem();
  const gproj::CeresSummary ceres_summary = gproj::SolveWithCeres({}, &same);
  std::printf("ceres: %s\n", ceres_summary.BriefReport().c_str());
  const double gp = gproj::EvaluateObjective(&problem, options.fairness_weight, problem.x());
  const double ceres = gproj::EvaluateObjective(&same, options.fairness_weight, same.x());
  std::printf("objective: guided projection %.12e, ceres %.12e\n", gp, ceres);
  const bool agree = std::abs(gp - ceres) <= 1e-8 * std::abs(gp);
  if (!agree) std::printf("the two solvers disagree\n");
  return summary.converged() && ceres_summary.IsSolutionUsable() && agree ? 0 : 1;
}
