#include "gproj/constraints/polyline_fairness.h"

#include <gtest/gtest.h>

#include <random>

#include "constraint_test_util.h"

namespace gproj {
namespace {

class PolylineFairnessTest : public ::testing::TestWithParam<int> {};

TEST_P(PolylineFairnessTest, GradientMatchesFiniteDifferences) {
  const int order = GetParam();
  PolylineFairness family(order, 3);
  std::vector<int> items(order + 1);
  for (int i = 0; i <= order; ++i) items[i] = i;
  family.AddElement(items);
  std::mt19937 rng(5);
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  std::vector<double> x(3 * (order + 1));
  for (double& v : x) v = u(rng);
  ExpectGradientMatchesFiniteDifferences(family, 0, x);
}

TEST_P(PolylineFairnessTest, ZeroOnEquallySpacedPointsOfALine) {
  const int order = GetParam();
  PolylineFairness family(order, 3);
  std::vector<int> items(order + 1);
  for (int i = 0; i <= order; ++i) items[i] = i;
  family.AddElement(items);
  std::vector<double> x;
  for (int i = 0; i <= order; ++i) {
    x.push_back(0.5 + 1.5 * i);
    x.push_back(-2.0 + 0.25 * i);
    x.push_back(3.0 - 0.75 * i);
  }
  std::vector<double> phi(3), jac(3 * x.size());
  family.EvaluateElement(0, x.data(), phi.data(), jac.data());
  for (int c = 0; c < 3; ++c) EXPECT_NEAR(phi[c], 0.0, 1e-14);
  // A bend gives a non-zero row.
  x[4] += 0.1;
  family.EvaluateElement(0, x.data(), phi.data(), jac.data());
  EXPECT_NEAR(std::abs(phi[1]), order == 2 ? 0.2 : 0.3, 1e-12);
}

TEST(PolylineFairnessThirdOrderTest, VanishesOnAParabola) {
  PolylineFairness family(3, 1);
  family.AddElement({0, 1, 2, 3});
  std::vector<double> x = {0.0, 1.0, 4.0, 9.0}, phi(1), jac(4);
  family.EvaluateElement(0, x.data(), phi.data(), jac.data());
  EXPECT_NEAR(phi[0], 0.0, 1e-14);
}

INSTANTIATE_TEST_SUITE_P(Orders, PolylineFairnessTest, ::testing::Values(2, 3),
                         [](const ::testing::TestParamInfo<int>& info) {
                           return info.param == 2 ? "SecondDifferences" : "ThirdDifferences";
                         });

}  // namespace
}  // namespace gproj
