#include "gproj/solver/internal/schur_complement.h"

#include <gtest/gtest.h>

#include <Eigen/Dense>
#include <random>
#include <set>

namespace gproj {
namespace {

// Layout: 6 kept points (dim 3), then 4 eliminable items of dimension `aux_dim`. Every column
// touches 2–4 kept variables and at most one eliminated item.
struct Fixture {
  VariableLayout layout;
  CscMatrix a;
};

Fixture MakeFixture(int aux_dim, uint32_t seed) {
  Fixture f;
  f.layout.AddBlock("points", 6, 3);
  const int aux = f.layout.AddBlock("aux", 4, aux_dim, /*eliminable=*/true);
  const int n = f.layout.num_variables();
  std::mt19937 rng(seed);
  std::uniform_int_distribution<int> kept(0, 17), item(-1, 3);
  std::uniform_real_distribution<double> value(-1.0, 1.0);
  f.a.num_rows = n;
  f.a.col_begin.push_back(0);
  for (int c = 0; c < 60; ++c) {
    std::set<int> rows;
    while (rows.size() < 3) rows.insert(kept(rng));
    const int e = item(rng);
    if (e >= 0)
      for (int k = 0; k < aux_dim; ++k)
        if (k == 0 || value(rng) > 0) rows.insert(f.layout.Index(aux, e, k));
    for (int r : rows) {
      f.a.row_index.push_back(r);
      f.a.values.push_back(value(rng));
    }
    f.a.col_begin.push_back(f.a.nnz());
  }
  f.a.num_cols = 60;
  return f;
}

Eigen::MatrixXd Dense(const CscMatrix& a) {
  Eigen::MatrixXd d = Eigen::MatrixXd::Zero(a.num_rows, a.num_cols);
  for (int c = 0; c < a.num_cols; ++c)
    for (int k = a.col_begin[c]; k < a.col_begin[c + 1]; ++k) d(a.row_index[k], c) = a.values[k];
  return d;
}

class SchurComplementTest : public ::testing::TestWithParam<int> {};

TEST_P(SchurComplementTest, ReducedSolveEqualsFullSolve) {
  Fixture f = MakeFixture(GetParam(), 17);
  SchurComplement schur;
  std::string message;
  ASSERT_TRUE(schur.Init(f.layout, f.a, &message)) << message;
  EXPECT_EQ(schur.num_eliminated(), 4 * GetParam());
  EXPECT_EQ(schur.num_kept(), 18);
  const double beta = 1e-3;
  ASSERT_TRUE(schur.Form(f.a, beta, &message)) << message;
  const int n = f.a.num_rows;
  const Eigen::MatrixXd ad = Dense(f.a);
  const Eigen::MatrixXd normal = ad * ad.transpose() + beta * Eigen::MatrixXd::Identity(n, n);
  const Eigen::VectorXd g = Eigen::VectorXd::LinSpaced(n, -1.0, 1.0);
  const Eigen::VectorXd expected = normal.ldlt().solve(g);

  // Dense S from its upper triangle (+ β I), then the reduced solve and back substitution.
  Eigen::MatrixXd s = Eigen::MatrixXd::Zero(18, 18);
  for (int c = 0; c < 18; ++c)
    for (int k = schur.s().col_begin[c]; k < schur.s().col_begin[c + 1]; ++k) {
      s(schur.s().row_index[k], c) = schur.s().values[k];
      s(c, schur.s().row_index[k]) = schur.s().values[k];
    }
  s += beta * Eigen::MatrixXd::Identity(18, 18);
  Eigen::VectorXd reduced(18), d(n);
  schur.ReduceRhs(f.a, g, &reduced);
  const Eigen::VectorXd d_kept = s.ldlt().solve(reduced);
  schur.BackSubstitute(f.a, d_kept, g, &d);
  EXPECT_LT((d - expected).norm() / expected.norm(), 1e-10);
}

INSTANTIATE_TEST_SUITE_P(ItemDims, SchurComplementTest, ::testing::Values(1, 3, 12),
                         [](const ::testing::TestParamInfo<int>& info) {
                           return "Dim" + std::to_string(info.param);
                         });

TEST(SchurComplementRefusalTest, RowTouchingTwoEliminatedItemsIsRefused) {
  Fixture f = MakeFixture(3, 5);
  // Add a column touching items 0 and 1 of the eliminable block.
  f.a.row_index.push_back(f.layout.Index(1, 0, 0));
  f.a.row_index.push_back(f.layout.Index(1, 1, 0));
  f.a.values.push_back(1.0);
  f.a.values.push_back(1.0);
  f.a.col_begin.push_back(f.a.nnz());
  ++f.a.num_cols;
  SchurComplement schur;
  std::string message;
  EXPECT_FALSE(schur.Init(f.layout, f.a, &message));
  EXPECT_NE(message.find("touches two eliminated items"), std::string::npos) << message;
}

}  // namespace
}  // namespace gproj
