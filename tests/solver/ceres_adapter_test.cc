#include "gproj/solver/ceres_adapter.h"

#include <gtest/gtest.h>

#include <Eigen/QR>

#include "gproj/solver/guided_projection.h"
#include "test_problems.h"

namespace gproj {
namespace {

TEST(CeresAdapterTest, SameObjectiveAsGuidedProjectionFromTheSameStart) {
  Problem gp = MakeCircleProblem(15, 0.05);
  Problem ceres = MakeCircleProblem(15, 0.05);
  SolverOptions options;
  options.fairness_weight = 0.2;
  options.residual_tolerance = 0.0;
  options.step_tolerance = 1e-14;
  options.max_iterations = 500;
  const SolverSummary summary = Solve(options, &gp);
  ASSERT_TRUE(summary.converged()) << summary.FullReport();
  CeresOptions ceres_options;
  ceres_options.fairness_weight = 0.2;
  const CeresSummary cs = SolveWithCeres(ceres_options, &ceres);
  ASSERT_TRUE(cs.IsSolutionUsable()) << cs.FullReport();
  const double e_gp = EvaluateObjective(&gp, 0.2, gp.x());
  const double e_ceres = EvaluateObjective(&ceres, 0.2, ceres.x());
  EXPECT_NEAR(e_gp, e_ceres, 1e-9 * e_ceres);
  // Ceres' cost is the same objective.
  EXPECT_NEAR(cs.final_cost, e_ceres, 1e-9 * e_ceres);
  EXPECT_LT((gp.x() - ceres.x()).lpNorm<Eigen::Infinity>(), 1e-6);
}

// Linear rows A x − b on one element touching 30 items of dimension 5 (150 scalars, 40 rows):
// residual blocks far wider than the constraint families' usual ones.
class WideLinearRows : public ConstraintFamily {
 public:
  WideLinearRows(const Eigen::MatrixXd& a, const Eigen::VectorXd& b)
      : ConstraintFamily("wide", static_cast<int>(a.rows())), a_(a), b_(b) {}
  void EvaluateElement(int, const double* x, double* phi, double* jac) const override {
    const Eigen::Map<const Eigen::VectorXd> v(x, a_.cols());
    Eigen::Map<Eigen::VectorXd>(phi, a_.rows()) = a_ * v - b_;
    Eigen::Map<Eigen::Matrix<double, Eigen::Dynamic, Eigen::Dynamic, Eigen::RowMajor>>(
        jac, a_.rows(), a_.cols()) = a_;
  }

 private:
  Eigen::MatrixXd a_;
  Eigen::VectorXd b_;
};

TEST(CeresAdapterTest, WideResidualBlocksGiveTheLeastSquaresSolution) {
  const int items = 30, dim = 5, rows = 200;
  const Eigen::MatrixXd a = Eigen::MatrixXd::Random(rows, items * dim);
  const Eigen::VectorXd b = Eigen::VectorXd::Random(rows);
  Problem problem;
  const int block = problem.layout().AddBlock("v", items, dim);
  problem.ResizeToLayout();
  std::vector<int> element;
  for (int i = 0; i < items; ++i) element.push_back(problem.layout().Item(block, i));
  problem.AddFamily<WideLinearRows>(a, b)->AddElement(element);
  CeresOptions options;
  options.fairness_weight = 0.0;
  const CeresSummary cs = SolveWithCeres(options, &problem);
  ASSERT_TRUE(cs.IsSolutionUsable()) << cs.FullReport();
  const Eigen::VectorXd exact = a.colPivHouseholderQr().solve(b);
  EXPECT_LT((problem.x() - exact).lpNorm<Eigen::Infinity>(), 1e-8);
}

TEST(CeresAdapterTest, ResidualBlocksMirrorFamilies) {
  Problem problem = MakeCircleProblem(6, 0.05);
  CeresOptions options;
  options.max_iterations = 0;
  const CeresSummary cs = SolveWithCeres(options, &problem);
  // 6 circle + 6 anchor + 4 smooth elements; 6 points of dimension 2.
  EXPECT_EQ(cs.num_residual_blocks, 16);
  EXPECT_EQ(cs.num_residuals, 6 + 12 + 8);
  EXPECT_EQ(cs.num_parameters, 12);
  EXPECT_NEAR(cs.initial_cost, EvaluateObjective(&problem, options.fairness_weight, problem.x()),
              1e-12);
}

}  // namespace
}  // namespace gproj
