#include "gproj/solver/guided_projection.h"

#include <gtest/gtest.h>

#include <Eigen/Dense>

#include "gproj/solver/ceres_adapter.h"
#include "gproj/solver/internal/linearized_system.h"
#include "test_problems.h"

namespace gproj {
namespace {

// Dense J (m × n), φ (m) and row weights (m) by evaluating the families directly.
void DenseLinearization(Problem& problem, double fairness_weight, Eigen::MatrixXd* j,
                        Eigen::VectorXd* phi, Eigen::VectorXd* w) {
  const VariableLayout& layout = problem.layout();
  const int n = layout.num_variables();
  std::vector<Eigen::VectorXd> rows;
  std::vector<double> values, weights;
  for (int f = 0; f < problem.num_families(); ++f) {
    const ConstraintFamily& fam = problem.family(f);
    double weight = fam.weight();
    if (fam.role() == FamilyRole::kFairness) weight *= fairness_weight * fairness_weight;
    for (int e = 0; e < fam.num_elements(); ++e) {
      std::vector<int> index;
      for (int k = 0; k < fam.element_num_items(e); ++k)
        for (int c = 0; c < layout.ItemDim(fam.element_items(e)[k]); ++c)
          index.push_back(layout.ItemOffset(fam.element_items(e)[k]) + c);
      std::vector<double> xl(index.size()), p(fam.rows_per_element()),
          jl(fam.rows_per_element() * index.size());
      for (size_t l = 0; l < index.size(); ++l) xl[l] = problem.x()[index[l]];
      fam.EvaluateElement(e, xl.data(), p.data(), jl.data());
      for (int r = 0; r < fam.rows_per_element(); ++r) {
        Eigen::VectorXd row = Eigen::VectorXd::Zero(n);
        for (size_t l = 0; l < index.size(); ++l) row[index[l]] += jl[r * index.size() + l];
        rows.push_back(row);
        values.push_back(p[r]);
        weights.push_back(weight);
      }
    }
  }
  j->resize(rows.size(), n);
  for (size_t r = 0; r < rows.size(); ++r) j->row(r) = rows[r];
  *phi = Eigen::Map<Eigen::VectorXd>(values.data(), values.size());
  *w = Eigen::Map<Eigen::VectorXd>(weights.data(), weights.size());
}

class GuidedProjectionTest : public ::testing::TestWithParam<LinearSolverType> {};

TEST_P(GuidedProjectionTest, OneStepEqualsDenseReferenceSolve) {
  Problem problem = MakeCircleProblem(12, 0.05);
  Eigen::MatrixXd j;
  Eigen::VectorXd phi, w;
  const double omega_f = 0.3, epsilon = 0.01;
  DenseLinearization(problem, omega_f, &j, &phi, &w);
  const int n = problem.layout().num_variables();
  const Eigen::MatrixXd normal =
      j.transpose() * w.asDiagonal() * j + epsilon * epsilon * Eigen::MatrixXd::Identity(n, n);
  const Eigen::VectorXd expected =
      problem.x() + normal.ldlt().solve(-(j.transpose() * w.asDiagonal() * phi));

  SolverOptions options;
  options.max_iterations = 1;
  options.fairness_weight = omega_f;
  options.epsilon = epsilon;
  options.linear_solver = GetParam();
  const SolverSummary summary = Solve(options, &problem);
  EXPECT_EQ(summary.termination, TerminationType::kNoConvergence);
  ASSERT_EQ(summary.num_steps(), 1);
  EXPECT_LT((problem.x() - expected).norm() / expected.norm(), 1e-12);
  EXPECT_NEAR(summary.iterations[0].energy, 0.5 * phi.dot(w.asDiagonal() * phi),
              1e-12 * summary.iterations[0].energy);
}

TEST_P(GuidedProjectionTest, FixedPointIsStationaryForTheWeightedObjective) {
  Problem problem = MakeCircleProblem(20, 0.1);
  SolverOptions options;
  options.max_iterations = 200;
  options.residual_tolerance = 0.0;
  options.step_tolerance = 1e-14;
  options.linear_solver = GetParam();
  const SolverSummary summary = Solve(options, &problem);
  ASSERT_TRUE(summary.converged()) << summary.FullReport();
  Eigen::MatrixXd j;
  Eigen::VectorXd phi, w;
  DenseLinearization(problem, options.fairness_weight, &j, &phi, &w);
  const Eigen::VectorXd gradient = j.transpose() * w.asDiagonal() * phi;
  EXPECT_LT(gradient.lpNorm<Eigen::Infinity>(), 1e-10);
  // Energy never increased along the way (small steps of a well-posed problem).
  for (int k = 1; k <= summary.num_steps(); ++k)
    EXPECT_LE(summary.iterations[k].energy, summary.iterations[k - 1].energy * (1 + 1e-12));
}

TEST_P(GuidedProjectionTest, FadingSoftWeightsDriveConstraintsToZero) {
  Problem problem = MakeCircleProblem(20, 1.0);
  SolverOptions options;
  options.soft_weight_decay = 0.1;
  options.soft_weight_floor = 1e-14;
  options.residual_tolerance = 1e-12;
  options.linear_solver = GetParam();
  const SolverSummary summary = Solve(options, &problem);
  ASSERT_TRUE(summary.converged()) << summary.FullReport();
  EXPECT_LE(summary.iterations.back().max_constraint, 1e-12);
  EXPECT_LT(summary.num_steps(), 15);
  EXPECT_NEAR(summary.iterations.back().soft_scale,
              std::max(std::pow(0.1, summary.num_steps()), 1e-14), 1e-20);
}

// The residual-tied schedule: the soft factor falls by min(decay, κ r_k) per iteration, r_k the
// constraint residual of the iterate the step starts from; with fixed weights (decay 1) or
// without constraint rows it is the plain decay.
TEST(GuidedProjectionScheduleTest, SoftWeightsFollowTheConstraintResidual) {
  SolverOptions options;
  options.soft_weight_decay = 0.5;
  options.soft_weight_residual_factor = 2.0;
  options.max_iterations = 6;
  options.residual_tolerance = 0.0;
  Problem problem = MakeCircleProblem(20, 1.0);
  const SolverSummary summary = Solve(options, &problem);
  ASSERT_EQ(summary.num_steps(), 6) << summary.FullReport();
  bool faster = false;  // some iteration fell by more than the plain decay
  for (int k = 0; k < 6; ++k) {
    const IterationRecord& r = summary.iterations[k];
    const double factor = std::min(0.5, 2.0 * r.max_constraint);
    EXPECT_DOUBLE_EQ(summary.iterations[k + 1].soft_scale, r.soft_scale * factor) << k;
    faster = faster || factor < 0.5;
  }
  EXPECT_TRUE(faster);
  SolverOptions fixed = options;
  fixed.soft_weight_decay = 1.0;
  Problem same = MakeCircleProblem(20, 1.0);
  EXPECT_EQ(Solve(fixed, &same).iterations.back().soft_scale, 1.0);
  // Anchors and smoothing only: no constraint residual to follow.
  Problem soft_only;
  const int block = soft_only.layout().AddBlock("points", 3, 2);
  soft_only.ResizeToLayout();
  auto* anchor = soft_only.AddFamily<Anchor>(1.0);
  for (int i = 0; i < 3; ++i) anchor->Add(soft_only.layout().Item(block, i), i, 0.5 * i);
  const SolverSummary plain = Solve(options, &soft_only);
  EXPECT_DOUBLE_EQ(plain.iterations.back().soft_scale, std::pow(0.5, plain.num_steps()));
}

INSTANTIATE_TEST_SUITE_P(Backends, GuidedProjectionTest,
                         ::testing::Values(LinearSolverType::kCholmod, LinearSolverType::kEigen),
                         [](const ::testing::TestParamInfo<LinearSolverType>& info) {
                           return std::string(info.param == LinearSolverType::kCholmod ? "Cholmod"
                                                                                       : "Eigen");
                         });

// A row that becomes NaN once x leaves the start.
class NanAwayFromStart : public ConstraintFamily {
 public:
  NanAwayFromStart() : ConstraintFamily("fragile", 1) {}
  void EvaluateElement(int, const double* p, double* phi, double* jac) const override {
    phi[0] = p[0] > 0.5 ? std::sqrt(-1.0) : p[0] - 1.0;
    jac[0] = 1.0;
    jac[1] = 0.0;
  }
};

TEST(GuidedProjectionFailureTest, NonFiniteValueIsReportedWithFamilyAndElement) {
  Problem problem = MakeCircleProblem(4, 0.1);
  problem.AddFamily<NanAwayFromStart>()->AddElement({2});
  problem.x()[4] = 0.6;  // item 2, x coordinate: NaN already at the start
  const SolverSummary summary = Solve(SolverOptions(), &problem);
  EXPECT_EQ(summary.termination, TerminationType::kFailure);
  EXPECT_NE(summary.message.find("'fragile', element 0"), std::string::npos) << summary.message;
  EXPECT_TRUE(problem.x().allFinite());
}

// Gradients so large that the normal matrix overflows: every factorisation fails.
class Overflowing : public ConstraintFamily {
 public:
  Overflowing() : ConstraintFamily("overflowing", 1) {}
  void EvaluateElement(int, const double* p, double* phi, double* jac) const override {
    phi[0] = 1.0;
    jac[0] = 1e200;
    jac[1] = 1e200;
  }
};

TEST(GuidedProjectionFailureTest, FailedFactorisationRaisesEpsilonThenStops) {
  Problem problem = MakeCircleProblem(4, 0.1);
  problem.AddFamily<Overflowing>()->AddElement({1});
  const Eigen::VectorXd start = problem.x();
  SolverOptions options;
  options.max_retries = 3;
  const SolverSummary summary = Solve(options, &problem);
  EXPECT_EQ(summary.termination, TerminationType::kFailure);
  EXPECT_NE(summary.message.find("after 3 increases of epsilon"), std::string::npos)
      << summary.message;
  EXPECT_EQ(problem.x(), start);  // nothing non-finite was accepted
}

// Rosenbrock's residuals 10 (y − x²) and 1 − x on one 2-scalar item: from (−1.2, 1) the plain
// Gauss–Newton step overshoots into a much higher energy.
class Rosenbrock : public ConstraintFamily {
 public:
  Rosenbrock() : ConstraintFamily("rosenbrock", 2) {}
  void EvaluateElement(int, const double* p, double* phi, double* jac) const override {
    phi[0] = 10.0 * (p[1] - p[0] * p[0]);
    phi[1] = 1.0 - p[0];
    jac[0] = -20.0 * p[0], jac[1] = 10.0, jac[2] = -1.0, jac[3] = 0.0;
  }
};

Problem MakeRosenbrockProblem() {
  Problem problem;
  const int block = problem.layout().AddBlock("xy", 1, 2);
  problem.ResizeToLayout();
  problem.x() << -1.2, 1.0;
  problem.AddFamily<Rosenbrock>()->AddElement({problem.layout().Item(block, 0)});
  return problem;
}

TEST(GuidedProjectionMonotoneTest, MonotoneStepsNeverRaiseTheEnergy) {
  SolverOptions options;
  options.max_iterations = 100;
  options.residual_tolerance = 1e-10;
  Problem plain = MakeRosenbrockProblem();
  const SolverSummary p = Solve(options, &plain);
  ASSERT_GE(p.iterations.size(), 2u);
  EXPECT_GT(p.iterations[1].energy, 10.0 * p.iterations[0].energy);  // the overshoot

  options.monotone = true;
  options.step_control = StepControl::kDamping;
  Problem monotone = MakeRosenbrockProblem();
  Eigen::Vector2d first = Eigen::Vector2d::Zero();
  const SolverSummary m =
      Solve(options, &monotone, [&](const IterationRecord& r, const Eigen::VectorXd& x) {
        if (r.iteration == 1) first = x;
        return CallbackResult::kContinue;
      });
  EXPECT_EQ(m.termination, TerminationType::kConvergence) << m.FullReport();
  // The kept first step solves (JᵀJ + ε² I) d = −Jᵀr at the start, with the ε it reports: the
  // rejected trials did not change the linearisation.
  const Eigen::Vector2d x0(-1.2, 1.0), r0(10.0 * (x0[1] - x0[0] * x0[0]), 1.0 - x0[0]);
  Eigen::Matrix2d j0;
  j0 << -20.0 * x0[0], 10.0, -1.0, 0.0;
  const double beta = m.iterations[1].epsilon * m.iterations[1].epsilon;
  const Eigen::Vector2d expected =
      x0 -
      (j0.transpose() * j0 + beta * Eigen::Matrix2d::Identity()).ldlt().solve(j0.transpose() * r0);
  EXPECT_LT((first - expected).norm(), 1e-10)
      << first.transpose() << " vs " << expected.transpose();
  for (size_t k = 1; k < m.iterations.size(); ++k)
    EXPECT_LE(m.iterations[k].energy, m.iterations[k - 1].energy) << "iteration " << k;
  EXPECT_GT(m.iterations[1].retries, 0);  // the first step was damped
  EXPECT_NEAR(monotone.x()[0], 1.0, 1e-6);
  EXPECT_NEAR(monotone.x()[1], 1.0, 1e-6);
}

TEST(GuidedProjectionMonotoneTest, StopsWhenNoStepLowersTheEnergy) {
  SolverOptions options;
  options.monotone = true;
  options.max_rejections = 0;  // the overshooting first step is the only try
  Problem problem = MakeRosenbrockProblem();
  const SolverSummary s = Solve(options, &problem);
  // Stopped at the start, far from a zero of the rows: a stall, not convergence.
  EXPECT_EQ(s.termination, TerminationType::kStalled);
  EXPECT_FALSE(s.converged());
  EXPECT_NE(s.message.find("no step lowers the energy"), std::string::npos) << s.message;
  EXPECT_NE(s.message.find("above the residual tolerance 1.0e-10"), std::string::npos) << s.message;
  EXPECT_EQ(s.num_steps(), 0);
  EXPECT_EQ(problem.x(), Eigen::Vector2d(-1.2, 1.0));
  // Asked for a stationary point only (no residual tolerance), the same stop is convergence.
  options.residual_tolerance = 0.0;
  Problem again = MakeRosenbrockProblem();
  EXPECT_EQ(Solve(options, &again).termination, TerminationType::kConvergence);
}

// Rows that contradict each other (x = 0 and x = 2): the step vanishes at x = 1 with both rows
// at |phi| = 1, which is a stall short of the residual tolerance, never convergence.
TEST(GuidedProjectionTest, AVanishedStepAboveTheResidualToleranceIsAStall) {
  Problem problem;
  const int block = problem.layout().AddBlock("x", 1, 1);
  problem.ResizeToLayout();
  auto* rows = problem.AddTerm<double, 1, 1>(
      "targets", [](double t, const auto* x, auto* r) { r[0] = x[0] - t; });
  rows->Add({problem.layout().Item(block, 0)}, 0.0);
  rows->Add({problem.layout().Item(block, 0)}, 2.0);
  SolverOptions options;
  options.step_tolerance = 1e-9;
  const SolverSummary s = Solve(options, &problem);
  EXPECT_EQ(s.termination, TerminationType::kStalled) << s.FullReport();
  EXPECT_FALSE(s.converged());
  EXPECT_NEAR(problem.x()[0], 1.0, 1e-6);
  EXPECT_NEAR(s.iterations.back().max_constraint, 1.0, 1e-6);
  EXPECT_NE(s.message.find("step tolerance met with the max constraint residual 1.000e+00"),
            std::string::npos)
      << s.message;
}

TEST(GuidedProjectionMonotoneTest, TrialPointsAreProjected) {
  SolverOptions options;
  options.max_iterations = 100;
  int calls = 0;
  // Keep y = x² (Rosenbrock's valley): the first residual then vanishes at every iterate.
  options.project_trial = [&calls](Eigen::VectorXd* x) {
    ++calls;
    (*x)[1] = (*x)[0] * (*x)[0];
  };
  Problem problem = MakeRosenbrockProblem();
  int off_valley = 0;
  const SolverSummary s =
      Solve(options, &problem, [&](const IterationRecord& r, const Eigen::VectorXd& x) {
        if (r.iteration > 0 && std::abs(x[1] - x[0] * x[0]) > 1e-12) ++off_valley;
        return CallbackResult::kContinue;
      });
  EXPECT_EQ(s.termination, TerminationType::kConvergence) << s.FullReport();
  EXPECT_EQ(calls, s.num_steps());
  EXPECT_GT(calls, 0);
  EXPECT_EQ(off_valley, 0);
  EXPECT_NEAR(problem.x()[0], 1.0, 1e-6);
}

// A trial the predicate refuses is never kept: on Rosenbrock's valley with x ≤ 0.5 admissible
// (the minimum is at x = 1), every iterate stays admissible, plain or monotone, and the run
// still moves towards the minimum up to the admissible set's edge.
// Refused trials are never kept, with plain steps, damping and the dogleg (which shrinks its
// radius instead of refactorising).
TEST(GuidedProjectionMonotoneTest, RefusedTrialsAreNeverKept) {
  for (int mode = 0; mode < 3; ++mode) {
    SolverOptions options;
    options.max_iterations = 60;
    options.monotone = mode > 0;
    options.step_control = mode == 2 ? StepControl::kDogleg : StepControl::kDamping;
    int refused = 0;
    options.admissible_trial = [&refused](const Eigen::VectorXd& x) {
      refused += x[0] > 0.5;
      return x[0] <= 0.5;
    };
    Problem problem = MakeRosenbrockProblem();
    double worst = -HUGE_VAL;
    const SolverSummary s =
        Solve(options, &problem, [&](const IterationRecord&, const Eigen::VectorXd& x) {
          worst = std::max(worst, x[0]);
          return CallbackResult::kContinue;
        });
    EXPECT_NE(s.termination, TerminationType::kFailure) << s.FullReport();
    EXPECT_GT(refused, 0) << mode;
    EXPECT_LE(worst, 0.5) << mode;
    EXPECT_GT(problem.x()[0], 0.3) << mode << "\n" << s.FullReport();
    if (mode == 2)
      for (const IterationRecord& r : s.iterations)
        EXPECT_LE(r.factorizations, 1) << "iteration " << r.iteration;
  }
}

TEST(GuidedProjectionDoglegTest, RejectedTrialsCostNoFactorisation) {
  SolverOptions options;
  options.max_iterations = 100;
  options.residual_tolerance = 1e-10;
  options.monotone = true;
  options.step_control = StepControl::kDogleg;
  Problem problem = MakeRosenbrockProblem();
  Eigen::Vector2d first = Eigen::Vector2d::Zero();
  const SolverSummary s =
      Solve(options, &problem, [&](const IterationRecord& r, const Eigen::VectorXd& x) {
        if (r.iteration == 1) first = x;
        return CallbackResult::kContinue;
      });
  ASSERT_EQ(s.termination, TerminationType::kConvergence) << s.FullReport();
  EXPECT_NEAR(problem.x()[0], 1.0, 1e-6);
  EXPECT_NEAR(problem.x()[1], 1.0, 1e-6);
  int rejected = 0;
  for (size_t k = 1; k < s.iterations.size(); ++k) {
    const IterationRecord& r = s.iterations[k];
    EXPECT_LE(r.energy, s.iterations[k - 1].energy) << "iteration " << k;
    EXPECT_EQ(r.factorizations, 1) << "iteration " << k;
    if (k == 1) EXPECT_EQ(r.epsilon, options.epsilon);  // no growth for the rejections
    rejected += r.trials - 1;
  }
  EXPECT_GT(rejected, 0);
  ASSERT_GT(s.iterations[1].trials, 1) << s.FullReport();
  // The kept first step is on the dogleg path of the start's linearisation: between the
  // Cauchy point c and the Gauss–Newton step d (or on the segment from 0 to c), at the D-norm
  // of d halved once per rejection.
  const Eigen::Vector2d x0(-1.2, 1.0), r0(10.0 * (x0[1] - x0[0] * x0[0]), 1.0 - x0[0]);
  Eigen::Matrix2d j0;
  j0 << -20.0 * x0[0], 10.0, -1.0, 0.0;
  const double beta = options.epsilon * options.epsilon;
  const Eigen::Matrix2d normal = j0.transpose() * j0;
  const Eigen::Vector2d g = -j0.transpose() * r0;
  const Eigen::Vector2d d = (normal + beta * Eigen::Matrix2d::Identity()).ldlt().solve(g);
  const Eigen::Vector2d scale2 = normal.diagonal().array() + beta;
  const Eigen::Vector2d p = g.cwiseQuotient(scale2);
  const Eigen::Vector2d c = p * (g.dot(p) / (j0 * p).squaredNorm());
  auto dnorm = [&](const Eigen::Vector2d& v) { return std::sqrt(v.dot(v.cwiseProduct(scale2))); };
  const Eigen::Vector2d taken = first - x0;
  EXPECT_NEAR(dnorm(taken), dnorm(d) / std::pow(2.0, s.iterations[1].trials - 1), 1e-10);
  Eigen::Matrix2d basis;
  basis << c, d - c;
  const Eigen::Vector2d coefficients = basis.fullPivLu().solve(taken);  // taken = α c + τ (d − c)
  const bool on_segment = std::abs(coefficients[0] - 1.0) < 1e-9 && coefficients[1] >= -1e-9 &&
                          coefficients[1] <= 1.0 + 1e-9;
  const bool towards_cauchy =
      std::abs(coefficients[1]) < 1e-9 && coefficients[0] > 0.0 && coefficients[0] <= 1.0 + 1e-9;
  EXPECT_TRUE(on_segment || towards_cauchy) << coefficients.transpose();
}

TEST(GuidedProjectionDoglegTest, StopsAtTheStartWhenTheRadiusRunsOut) {
  SolverOptions options;
  options.monotone = true;
  options.step_control = StepControl::kDogleg;
  options.max_rejections = 0;
  Problem problem = MakeRosenbrockProblem();
  const SolverSummary s = Solve(options, &problem);
  EXPECT_EQ(s.termination, TerminationType::kStalled) << s.FullReport();
  EXPECT_NE(s.message.find("trust radius reduced to"), std::string::npos) << s.message;
  // The residual named is the start's (Rosenbrock's first row, 10 (1 − 1.44) = −4.4).
  EXPECT_NE(s.message.find("max constraint residual 4.400e+00"), std::string::npos) << s.message;
  EXPECT_EQ(s.num_steps(), 0);
  EXPECT_EQ(problem.x(), Eigen::Vector2d(-1.2, 1.0));
}

// A GuidedProjectionSolver keeps its analysis for re-solves of the same rows, and rebuilds it
// when the linear algebra asked for changes; a re-solve's iterates are those of a fresh solve.
TEST(GuidedProjectionSolverTest, ReSolvesReuseTheAnalysisUntilTheOptionsChangeIt) {
  Problem problem = MakeCircleProblem(6, 0.1);
  Problem fresh = MakeCircleProblem(6, 0.1);
  const Eigen::VectorXd start = problem.x();
  SolverOptions options;
  GuidedProjectionSolver solver(&problem);
  const SolverSummary first = solver.Solve(options);
  EXPECT_FALSE(first.analysis_reused);
  problem.x() = start;
  const SolverSummary second = solver.Solve(options);
  EXPECT_TRUE(second.analysis_reused);
  EXPECT_EQ(second.analysis_seconds, 0.0);
  EXPECT_EQ(second.eliminated_variables, first.eliminated_variables);
  const SolverSummary reference = Solve(options, &fresh);
  EXPECT_EQ(second.num_steps(), reference.num_steps());
  EXPECT_LT((problem.x() - fresh.x()).lpNorm<Eigen::Infinity>(), 1e-12);
  options.linear_solver = LinearSolverType::kEigen;
  problem.x() = start;
  EXPECT_FALSE(solver.Solve(options).analysis_reused);
}

// Re-solves with monotone dogleg steps and shifted constraints take the iterates of a fresh
// solve from the same state: no shift, radius or damping carried over.
TEST(GuidedProjectionSolverTest, AReSolveTakesTheIteratesOfAFreshSolve) {
  SolverOptions options;
  options.monotone = true;
  options.shifted_constraints = true;
  options.max_iterations = 30;
  Problem problem = MakeRosenbrockProblem();
  GuidedProjectionSolver solver(&problem);
  solver.Solve(options);
  const Eigen::Vector2d restart(-0.5, 1.5);
  problem.x() = restart;
  const SolverSummary again = solver.Solve(options);
  ASSERT_TRUE(again.analysis_reused);
  Problem fresh = MakeRosenbrockProblem();
  fresh.x() = restart;
  const SolverSummary reference = Solve(options, &fresh);
  ASSERT_EQ(again.num_steps(), reference.num_steps());
  for (int k = 0; k <= again.num_steps(); ++k) {
    EXPECT_EQ(again.iterations[k].energy, reference.iterations[k].energy) << k;
    EXPECT_EQ(again.iterations[k].trials, reference.iterations[k].trials) << k;
  }
  EXPECT_EQ(problem.x(), fresh.x());
}

// An item held when the set-up was built is left out of its pattern: releasing it rebuilds
// the set-up, so the item moves again; holding one later keeps the set-up and the item still.
TEST(GuidedProjectionSolverTest, ReleasingAHeldItemRebuildsTheSetUp) {
  Problem problem = MakeCircleProblem(6, 0.1);
  const Eigen::VectorXd start = problem.x();
  problem.SetConstant(0);
  SolverOptions options;
  GuidedProjectionSolver solver(&problem);
  solver.Solve(options);
  EXPECT_EQ(problem.x().head(2), start.head(2));
  problem.SetConstant(0, false);
  problem.x() = start;
  const SolverSummary released = solver.Solve(options);
  EXPECT_FALSE(released.analysis_reused);
  Problem fresh = MakeCircleProblem(6, 0.1);
  Solve(options, &fresh);
  EXPECT_LT((problem.x() - fresh.x()).lpNorm<Eigen::Infinity>(), 1e-12);
  EXPECT_GT((problem.x().head(2) - start.head(2)).norm(), 1e-4);
  problem.SetConstant(1);
  const Eigen::VectorXd before = problem.x();
  problem.x().segment(2, 2) += Eigen::Vector2d(0.05, -0.02);
  const Eigen::Vector2d pinned = problem.x().segment(2, 2);
  const SolverSummary held = solver.Solve(options);
  EXPECT_TRUE(held.analysis_reused);
  EXPECT_EQ(Eigen::Vector2d(problem.x().segment(2, 2)), pinned);
  EXPECT_NE(problem.x(), before);
}

TEST(GuidedProjectionFailureTest, InvalidOptionsAreRejected) {
  Problem problem = MakeCircleProblem(4, 0.1);
  SolverOptions options;
  options.epsilon = 0.0;
  std::string why;
  EXPECT_FALSE(options.IsValid(&why));
  EXPECT_NE(why.find("epsilon"), std::string::npos);
  SolverOptions rejections;
  rejections.max_rejections = -1;
  EXPECT_FALSE(rejections.IsValid(&why));
  EXPECT_NE(why.find("max_rejections"), std::string::npos);
  SolverOptions tied;
  tied.epsilon_min = -1e-6;
  EXPECT_FALSE(tied.IsValid(&why));
  EXPECT_NE(why.find("epsilon_min"), std::string::npos);
  tied.epsilon_min = 0.0;
  tied.soft_weight_residual_factor = NAN;
  EXPECT_FALSE(tied.IsValid(&why));
  EXPECT_NE(why.find("soft_weight_residual_factor"), std::string::npos);
  const SolverSummary summary = Solve(options, &problem);
  EXPECT_EQ(summary.termination, TerminationType::kFailure);
  EXPECT_NE(summary.message.find("invalid options"), std::string::npos);
}

TEST(GuidedProjectionCallbackTest, CallbackSeesEveryIterationAndCanStop) {
  Problem problem = MakeCircleProblem(10, 0.1);
  int calls = 0;
  const SolverSummary summary =
      Solve(SolverOptions(), &problem, [&](const IterationRecord& r, const Eigen::VectorXd&) {
        EXPECT_EQ(r.iteration, calls);
        ++calls;
        return r.iteration == 2 ? CallbackResult::kAbort : CallbackResult::kContinue;
      });
  EXPECT_EQ(calls, 3);
  EXPECT_EQ(summary.termination, TerminationType::kUserAbort);
  ASSERT_EQ(summary.iterations.size(), 3u);
  EXPECT_EQ(summary.iterations[2].families.size(), 3u);
  EXPECT_EQ(summary.iterations[2].families[0].name, "on_circle");
}

TEST(LinearizedSystemTest, PatternHonoursRowTouches) {
  Problem problem = MakeCircleProblem(5, 0.1);
  LinearizedSystem system(&problem);
  // on_circle: 5 rows × 2 entries; anchor (declares one entry per row): 10 rows × 1;
  // smooth (keeps the default, every row touches all 6 locals): 3 elements × 2 rows × 6.
  EXPECT_EQ(system.a().nnz(), 5 * 2 + 10 * 1 + 3 * 2 * 6);
  EXPECT_EQ(system.num_rows(), 5 + 10 + 6);
}

}  // namespace
}  // namespace gproj

namespace gproj {
namespace {

// Held items: no derivative, no motion (bit for bit), in guided projection and in Ceres.
TEST(ConstantItemTest, HeldPointsStayBitForBitWhileTheOthersConverge) {
  for (bool ceres : {false, true}) {
    Problem problem = MakeCircleProblem(20, 1.0);
    const VariableLayout& layout = problem.layout();
    const int held[] = {3, 11};
    for (int i : held) {
      auto p = problem.x().segment<2>(layout.Index(0, i, 0));
      p.normalize();                                // on the circle, so every row can vanish
      problem.x()[layout.Index(0, i, 0)] += 1e-17;  // a value a step would round away
      problem.SetConstant(layout.Item(0, i));
    }
    EXPECT_TRUE(problem.IsConstant(layout.Item(0, 3)));
    EXPECT_FALSE(problem.IsConstant(layout.Item(0, 4)));
    const Eigen::VectorXd start = problem.x();
    if (ceres) {
      CeresOptions options;
      options.soft_scale = 1e-6;
      options.max_iterations = 100;
      SolveWithCeres(options, &problem);
    } else {
      SolverOptions options;
      options.soft_weight_decay = 0.1;
      options.soft_weight_floor = 1e-14;
      options.residual_tolerance = 1e-12;
      ASSERT_TRUE(Solve(options, &problem).converged());
    }
    for (int i : held)
      for (int c = 0; c < 2; ++c)
        EXPECT_EQ(problem.x()[layout.Index(0, i, c)], start[layout.Index(0, i, c)]) << ceres;
    for (int i = 0; i < 20; ++i)
      EXPECT_NEAR(problem.x().segment<2>(layout.Index(0, i, 0)).norm(), 1.0, ceres ? 1e-4 : 1e-9)
          << ceres;  // Ceres minimises one fixed-weight objective: the soft rows leave ~1e-5
    EXPECT_GT((problem.x() - start).norm(), 0.1);
  }
}

}  // namespace
}  // namespace gproj

namespace gproj {
namespace {

// min ‖p − (3, 0)‖² subject to x + y = 1: the projection (2, −1). With equal weights a penalty
// stops halfway; shifted constraint targets reach the constrained minimiser exactly.
TEST(ShiftedConstraintTest, ReachesTheConstrainedMinimiserInsteadOfTheWeightBalance) {
  for (bool shifted : {false, true}) {
    Problem problem;
    const int block = problem.layout().AddBlock("p", 1, 2);
    problem.ResizeToLayout();
    const int item = problem.layout().Item(block, 0);
    problem.AddTerm<1, 2>("line", [](const auto* p, auto* r) { r[0] = p[0] + p[1] - 1.0; })
        ->Add({item});
    problem
        .AddTerm<2, 2>(
            "target", [](const auto* p, auto* r) { r[0] = p[0] - 3.0, r[1] = p[1]; },
            FamilyRole::kSoft, 1.0)
        ->Add({item});
    SolverOptions options;
    options.shifted_constraints = shifted;
    options.residual_tolerance = 0.0;
    options.step_tolerance = 1e-15;
    options.max_iterations = 60;
    const SolverSummary summary = Solve(options, &problem);
    const Eigen::Vector2d p = problem.x().head<2>();
    if (shifted) {
      EXPECT_NEAR(p.x(), 2.0, 1e-12) << summary.FullReport();
      EXPECT_NEAR(p.y(), -1.0, 1e-12);
    } else {
      EXPECT_GT(std::abs(p.x() + p.y() - 1.0), 0.1);  // the penalty's balance
    }
  }
}

}  // namespace
}  // namespace gproj
