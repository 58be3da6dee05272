// One conformance suite run over every sparse Cholesky backend.
#include "gproj/solver/sparse_cholesky.h"

#include <gtest/gtest.h>

#include <Eigen/Dense>
#include <random>
#include <set>

namespace gproj {
namespace {

// A random sparse n × m matrix in CSC with `per_col` entries per column.
CscMatrix RandomCsc(int n, int m, int per_col, uint32_t seed) {
  std::mt19937 rng(seed);
  std::uniform_int_distribution<int> row(0, n - 1);
  std::uniform_real_distribution<double> value(-1.0, 1.0);
  CscMatrix a;
  a.num_rows = n;
  a.num_cols = m;
  a.col_begin.push_back(0);
  for (int c = 0; c < m; ++c) {
    std::set<int> rows;
    while (static_cast<int>(rows.size()) < per_col) rows.insert(row(rng));
    for (int r : rows) {
      a.row_index.push_back(r);
      a.values.push_back(value(rng));
    }
    a.col_begin.push_back(a.nnz());
  }
  return a;
}

Eigen::MatrixXd Dense(const CscMatrix& a) {
  Eigen::MatrixXd d = Eigen::MatrixXd::Zero(a.num_rows, a.num_cols);
  for (int c = 0; c < a.num_cols; ++c)
    for (int k = a.col_begin[c]; k < a.col_begin[c + 1]; ++k) d(a.row_index[k], c) = a.values[k];
  return d;
}

class SparseCholeskyTest : public ::testing::TestWithParam<LinearSolverType> {};

TEST_P(SparseCholeskyTest, SolvesRandomSpdSystemLikeDenseReference) {
  const int n = 60, m = 150;
  CscMatrix a = RandomCsc(n, m, 4, 11);
  auto cholesky = CreateSparseCholesky(GetParam(), 1);
  std::string message;
  ASSERT_TRUE(cholesky->Analyze(a, MatrixForm::kAAt, &message)) << message;
  const Eigen::MatrixXd ad = Dense(a);
  std::mt19937 rng(2);
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  // Refactorise with new values and a new β on the same pattern, as the solver does.
  for (double beta : {1e-6, 1e-2, 1.0}) {
    for (double& v : a.values) v = u(rng);
    const Eigen::MatrixXd ad2 = Dense(a);
    const Eigen::MatrixXd normal = ad2 * ad2.transpose() + beta * Eigen::MatrixXd::Identity(n, n);
    Eigen::VectorXd b = Eigen::VectorXd::NullaryExpr(n, [&]() { return u(rng); });
    ASSERT_TRUE(cholesky->Factorize(a, beta, &message)) << message;
    Eigen::VectorXd x(n);
    ASSERT_TRUE(cholesky->Solve(b.data(), x.data(), &message)) << message;
    const Eigen::VectorXd reference = normal.ldlt().solve(b);
    EXPECT_LT((x - reference).norm() / reference.norm(), 1e-9) << "beta " << beta;
    EXPECT_LT((normal * x - b).norm() / b.norm(), 1e-9);
  }
  EXPECT_GT(cholesky->FactorNonZeros(), n - 1);
  (void)ad;
}

// One backend object analysing a second pattern of another size (as the quad remeshing does for
// its two solves) solves that one right, and frees what the first needed (ASan checks).
TEST_P(SparseCholeskyTest, ASecondAnalysisOfAnotherSizeSolvesItsSystem) {
  auto cholesky = CreateSparseCholesky(GetParam(), 1);
  std::string message;
  for (const int n : {40, 25}) {
    const CscMatrix a = RandomCsc(n, 3 * n, 4, 7 + n);
    ASSERT_TRUE(cholesky->Analyze(a, MatrixForm::kAAt, &message)) << message;
    ASSERT_TRUE(cholesky->Factorize(a, 1e-3, &message)) << message;
    const Eigen::MatrixXd ad = Dense(a);
    const Eigen::MatrixXd normal = ad * ad.transpose() + 1e-3 * Eigen::MatrixXd::Identity(n, n);
    const Eigen::VectorXd b = Eigen::VectorXd::LinSpaced(n, -1.0, 1.0);
    Eigen::VectorXd x(n);
    ASSERT_TRUE(cholesky->Solve(b.data(), x.data(), &message)) << message;
    EXPECT_LT((normal * x - b).norm() / b.norm(), 1e-9) << n;
  }
}

TEST_P(SparseCholeskyTest, ReportsSingularMatrix) {
  // A Aᵀ with a zero row in A and β = 0 is singular.
  CscMatrix a = RandomCsc(10, 20, 3, 4);
  for (int k = 0; k < a.nnz(); ++k)
    if (a.row_index[k] == 3) a.values[k] = 0.0;
  auto cholesky = CreateSparseCholesky(GetParam(), 1);
  std::string message;
  ASSERT_TRUE(cholesky->Analyze(a, MatrixForm::kAAt, &message)) << message;
  EXPECT_FALSE(cholesky->Factorize(a, 0.0, &message));
  EXPECT_NE(message.find("positive definite"), std::string::npos) << message;
}

INSTANTIATE_TEST_SUITE_P(Backends, SparseCholeskyTest,
                         ::testing::Values(LinearSolverType::kCholmod, LinearSolverType::kEigen),
                         [](const ::testing::TestParamInfo<LinearSolverType>& info) {
                           return std::string(info.param == LinearSolverType::kCholmod ? "Cholmod"
                                                                                       : "Eigen");
                         });

TEST(SparseCholeskyBackendsTest, CholmodAndEigenGiveTheSameStep) {
  const int n = 80, m = 200;
  const CscMatrix a = RandomCsc(n, m, 5, 21);
  Eigen::VectorXd b = Eigen::VectorXd::LinSpaced(n, -1.0, 2.0);
  Eigen::VectorXd x[2];
  const LinearSolverType types[2] = {LinearSolverType::kCholmod, LinearSolverType::kEigen};
  for (int t = 0; t < 2; ++t) {
    auto cholesky = CreateSparseCholesky(types[t], 1);
    std::string message;
    ASSERT_TRUE(cholesky->Analyze(a, MatrixForm::kAAt, &message));
    ASSERT_TRUE(cholesky->Factorize(a, 1e-6, &message));
    x[t].resize(n);
    ASSERT_TRUE(cholesky->Solve(b.data(), x[t].data(), &message));
  }
  EXPECT_LT((x[0] - x[1]).norm() / x[1].norm(), 1e-10);
}

// CHOLMOD's flop count of the factorisation (the bench's factor_gflops): for a dense n × n
// factor it is Σ_j (column count)² = n(n + 1)(2n + 1)/6 ≈ n³/3; a diagonal matrix costs n.
TEST(SparseCholeskyBackendsTest, CholmodCountsTheFactorisationFlops) {
  const int n = 50;
  CscMatrix dense = RandomCsc(n, 3 * n, n, 5);  // every column full: A Aᵀ is dense
  auto cholesky = CreateSparseCholesky(LinearSolverType::kCholmod, 1);
  std::string message;
  EXPECT_EQ(cholesky->FactorFlops(), 0.0);
  ASSERT_TRUE(cholesky->Analyze(dense, MatrixForm::kAAt, &message)) << message;
  EXPECT_GE(cholesky->FactorFlops(), n * n * n / 3.0);
  EXPECT_LE(cholesky->FactorFlops(), n * (n + 1.0) * (2.0 * n + 1.0) / 6.0 + 2.0 * n * n);
  auto sparse = CreateSparseCholesky(LinearSolverType::kCholmod, 1);
  CscMatrix identity;
  identity.num_rows = identity.num_cols = n;
  for (int c = 0; c < n; ++c) {
    identity.col_begin.push_back(c);
    identity.row_index.push_back(c);
    identity.values.push_back(1.0);
  }
  identity.col_begin.push_back(n);
  ASSERT_TRUE(sparse->Analyze(identity, MatrixForm::kSymmetric, &message)) << message;
  EXPECT_LE(sparse->FactorFlops(), 2.0 * n);
  EXPECT_GT(sparse->FactorFlops(), 0.0);
  EXPECT_LT(sparse->FactorFlops(), cholesky->FactorFlops() / 100.0);
}

// Every fill-reducing ordering gives the same solution; they differ in fill. The names parse
// back to the orderings.
TEST(SparseCholeskyBackendsTest, EveryOrderingGivesTheSameStep) {
  const int n = 300, m = 900;
  const CscMatrix a = RandomCsc(n, m, 3, 31);
  const Eigen::VectorXd b = Eigen::VectorXd::LinSpaced(n, -1.0, 2.0);
  Eigen::VectorXd reference;
  std::set<int64_t> fills;
  for (FillOrdering ordering : {FillOrdering::kAuto, FillOrdering::kAmd, FillOrdering::kMetis,
                                FillOrdering::kNestedDissection}) {
    FillOrdering parsed = FillOrdering::kAuto;
    ASSERT_TRUE(ParseFillOrdering(FillOrderingName(ordering), &parsed));
    EXPECT_EQ(parsed, ordering);
    auto cholesky = CreateSparseCholesky(LinearSolverType::kCholmod, 1, ordering);
    std::string message;
    ASSERT_TRUE(cholesky->Analyze(a, MatrixForm::kAAt, &message)) << message;
    ASSERT_TRUE(cholesky->Factorize(a, 1e-6, &message)) << message;
    Eigen::VectorXd x(n);
    ASSERT_TRUE(cholesky->Solve(b.data(), x.data(), &message)) << message;
    if (reference.size() == 0) reference = x;
    EXPECT_LT((x - reference).norm() / reference.norm(), 1e-10) << FillOrderingName(ordering);
    fills.insert(cholesky->FactorNonZeros());
  }
  EXPECT_GE(fills.size(), 2u);  // the orderings were applied
  FillOrdering parsed;
  EXPECT_FALSE(ParseFillOrdering("colamd", &parsed));
}

// A matrix over `groups` groups of 3 variables whose every column touches whole groups (two
// vertices' coordinates, as a planarity or fairness row does), like A of a mesh problem.
CscMatrix GroupedCsc(int groups, int m, uint32_t seed) {
  std::mt19937 rng(seed);
  std::uniform_int_distribution<int> group(0, groups - 1);
  std::uniform_real_distribution<double> value(-1.0, 1.0);
  CscMatrix a;
  a.num_rows = 3 * groups;
  a.num_cols = m;
  a.col_begin.push_back(0);
  for (int c = 0; c < m; ++c) {
    std::set<int> touched = {group(rng), group(rng)};
    for (int g : touched)
      for (int d = 0; d < 3; ++d) {
        a.row_index.push_back(3 * g + d);
        a.values.push_back(value(rng));
      }
    a.col_begin.push_back(a.nnz());
  }
  return a;
}

// The upper triangle of A Aᵀ.
CscMatrix UpperNormal(const CscMatrix& a) {
  const Eigen::MatrixXd n = Dense(a) * Dense(a).transpose();
  CscMatrix s;
  s.num_rows = s.num_cols = a.num_rows;
  s.col_begin.push_back(0);
  for (int c = 0; c < a.num_rows; ++c) {
    for (int r = 0; r <= c; ++r)
      if (n(r, c) != 0.0 || r == c) {
        s.row_index.push_back(r);
        s.values.push_back(n(r, c));
      }
    s.col_begin.push_back(s.nnz());
  }
  return s;
}

// Ordering the graph of the groups (a vertex's coordinates as one node): every ordering keeps
// each group's variables together, the step is the one of the scalar ordering, for A Aᵀ and
// for a symmetric matrix alike; a grouping that does not cover the matrix is ignored.
TEST(SparseCholeskyBackendsTest, GroupedOrderingKeepsGroupsTogetherAndTheStep) {
  const int groups = 200;
  const CscMatrix a = GroupedCsc(groups, 700, 41);
  const CscMatrix s = UpperNormal(a);
  const Eigen::VectorXd b = Eigen::VectorXd::LinSpaced(3 * groups, -1.0, 2.0);
  std::vector<int> group_begin;
  for (int g = 0; g <= groups; ++g) group_begin.push_back(3 * g);
  for (MatrixForm form : {MatrixForm::kAAt, MatrixForm::kSymmetric}) {
    const CscMatrix& m = form == MatrixForm::kAAt ? a : s;
    Eigen::VectorXd reference;
    for (FillOrdering ordering : {FillOrdering::kAuto, FillOrdering::kAmd, FillOrdering::kMetis,
                                  FillOrdering::kNestedDissection}) {
      for (bool grouped : {false, true}) {
        auto cholesky = CreateSparseCholesky(LinearSolverType::kCholmod, 1, ordering);
        if (grouped) cholesky->SetGroups(group_begin);
        std::string message;
        ASSERT_TRUE(cholesky->Analyze(m, form, &message)) << message;
        ASSERT_TRUE(cholesky->Factorize(m, 1e-6, &message)) << message;
        Eigen::VectorXd x(3 * groups);
        ASSERT_TRUE(cholesky->Solve(b.data(), x.data(), &message)) << message;
        if (reference.size() == 0) reference = x;
        EXPECT_LT((x - reference).norm() / reference.norm(), 1e-9) << FillOrderingName(ordering);
        const std::vector<int> perm = cholesky->FillPermutation();
        ASSERT_EQ(perm.size(), 3u * groups);
        int split = 0;  // groups whose variables are not consecutive in the elimination order
        for (int k = 0; k < 3 * groups; k += 3)
          if (perm[k] / 3 != perm[k + 1] / 3 || perm[k] / 3 != perm[k + 2] / 3) ++split;
        if (grouped)
          EXPECT_EQ(split, 0) << FillOrderingName(ordering);
        else if (ordering == FillOrdering::kAmd)
          EXPECT_GT(split, 0);  // AMD on the scalars interleaves the groups
        EXPECT_GT(cholesky->FactorFlops(), 0.0);
      }
    }
  }
  auto cholesky = CreateSparseCholesky(LinearSolverType::kCholmod, 1);
  cholesky->SetGroups({0, 3, 6});  // covers 6 variables of 600: ignored
  std::string message;
  ASSERT_TRUE(cholesky->Analyze(a, MatrixForm::kAAt, &message)) << message;
  ASSERT_TRUE(cholesky->Factorize(a, 1e-6, &message)) << message;
}

}  // namespace
}  // namespace gproj
