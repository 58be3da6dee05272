#include "gproj/constraints/circular_quad.h"

#include <gtest/gtest.h>

#include <Eigen/Geometry>
#include <random>

#include "constraint_test_util.h"

namespace gproj {
namespace {

// Four points on a circle in a tilted plane, at the given angles.
std::array<Eigen::Vector3d, 4> CircularQuadAt(const double angles[4]) {
  const Eigen::Vector3d n = Eigen::Vector3d(1, 2, 2).normalized();
  const Eigen::Vector3d e1 = n.unitOrthogonal(), e2 = n.cross(e1);
  const Eigen::Vector3d c(0.3, -1.0, 2.0);
  std::array<Eigen::Vector3d, 4> q;
  for (int j = 0; j < 4; ++j)
    q[j] = c + 1.7 * (std::cos(angles[j]) * e1 + std::sin(angles[j]) * e2);
  return q;
}

std::vector<double> Local(const Eigen::Matrix<double, 7, 1>& aux,
                          const std::array<Eigen::Vector3d, 4>& q) {
  std::vector<double> x(19);
  for (int c = 0; c < 7; ++c) x[c] = aux[c];
  for (int j = 0; j < 4; ++j)
    for (int c = 0; c < 3; ++c) x[7 + 3 * j + c] = q[j][c];
  return x;
}

double MaxResidual(const CircularQuad& family, const std::vector<double>& x) {
  std::vector<double> phi(10), jac(190);
  family.EvaluateElement(0, x.data(), phi.data(), jac.data());
  double worst = 0.0;
  for (double p : phi) worst = std::max(worst, std::abs(p));
  return worst;
}

TEST(CircularQuadTest, GradientMatchesFiniteDifferences) {
  CircularQuad family;
  family.AddQuad(0, 1, 2, 3, 4);
  family.Prepare();  // the term declared quadratic: evaluated from its coefficients
  std::mt19937 rng(5);
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  for (int trial = 0; trial < 5; ++trial) {
    std::vector<double> x(19);
    for (double& v : x) v = u(rng);
    ExpectGradientMatchesFiniteDifferences(family, 0, x);
  }
}

TEST(CircularQuadTest, ZeroResidualOnConcyclicQuadWithItsAuxiliary) {
  CircularQuad family;
  family.AddQuad(0, 1, 2, 3, 4);
  family.Prepare();  // the term declared quadratic: evaluated from its coefficients
  const double angles[4] = {0.1, 1.2, 2.9, 4.4};
  const auto q = CircularQuadAt(angles);
  EXPECT_LT(MaxResidual(family, Local(CircularQuad::InitialAuxiliary(q), q)), 1e-13);
}

TEST(CircularQuadTest, PlanarButNotConcyclicQuadHasResidual) {
  CircularQuad family;
  family.AddQuad(0, 1, 2, 3, 4);
  family.Prepare();  // the term declared quadratic: evaluated from its coefficients
  const double angles[4] = {0.1, 1.2, 2.9, 4.4};
  auto q = CircularQuadAt(angles);
  q[2] += 0.1 * (q[2] - q[0]);  // stays in the plane, leaves the circle
  // Whatever centre and radius: the four squared distances cannot all equal ρ.
  const auto aux = CircularQuad::InitialAuxiliary(q);
  EXPECT_GT(MaxResidual(family, Local(aux, q)), 1e-3);
}

}  // namespace
}  // namespace gproj
