#include "gproj/constraints/umbrella_fairness.h"

#include <gtest/gtest.h>

#include <cmath>
#include <random>

#include "constraint_test_util.h"

namespace gproj {
namespace {

TEST(UmbrellaFairnessTest, GradientMatchesFiniteDifferences) {
  for (int neighbours : {3, 5, 6}) {
    UmbrellaFairness family(3);
    std::vector<int> items(neighbours + 1);
    for (int i = 0; i <= neighbours; ++i) items[i] = i;
    family.AddElement(items);
    std::mt19937 rng(11 + neighbours);
    std::uniform_real_distribution<double> u(-1.0, 1.0);
    std::vector<double> x(3 * (neighbours + 1));
    for (double& v : x) v = u(rng);
    ExpectGradientMatchesFiniteDifferences(family, 0, x);
  }
}

// Zero at the centroid of its neighbours (a flat or curved umbrella alike), 2 × the offset from
// it otherwise; at a valence-4 vertex the mean of the two second differences.
TEST(UmbrellaFairnessTest, MeasuresTheOffsetFromTheNeighboursCentroid) {
  UmbrellaFairness family(3);
  family.AddElement({0, 1, 2, 3});
  std::vector<double> x = {0.0, 0.0, 0.0};
  for (int k = 0; k < 3; ++k) {
    const double a = 2.0 * M_PI * k / 3;
    x.insert(x.end(), {std::cos(a), std::sin(a), 0.5});
  }
  x[2] = 0.5;  // at the centroid
  std::vector<double> phi(3), jac(3 * x.size());
  family.EvaluateElement(0, x.data(), phi.data(), jac.data());
  for (int c = 0; c < 3; ++c) EXPECT_NEAR(phi[c], 0.0, 1e-14);
  x[2] = 0.8;
  family.EvaluateElement(0, x.data(), phi.data(), jac.data());
  EXPECT_NEAR(phi[2], -0.6, 1e-14);

  UmbrellaFairness four(1);
  four.AddElement({0, 1, 2, 3, 4});
  const std::vector<double> y = {0.3, 1.0, -2.0, 4.0, 0.5};  // v, a, b, c, d (a opposite c)
  std::vector<double> p(1), j(5);
  four.EvaluateElement(0, y.data(), p.data(), j.data());
  EXPECT_NEAR(p[0], 0.5 * ((1.0 - 0.6 + 4.0) + (-2.0 - 0.6 + 0.5)), 1e-14);
}

}  // namespace
}  // namespace gproj
