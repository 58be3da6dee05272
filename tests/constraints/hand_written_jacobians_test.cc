// Hand-written Jacobians against automatic differentiation. Families that keep a hand-written
// Jacobian (for speed, or because they predate terms) are checked here against the residual
// written once more as a function templated on the scalar type, as a term would be, and
// differentiated by forward-mode automatic differentiation (ceres::Jet): values and every
// derivative must agree to round-off, and a derivative the family declares structurally zero
// (RowTouches) must be zero.
#include <ceres/jet.h>
#include <gtest/gtest.h>

#include <Eigen/Geometry>
#include <array>
#include <cmath>
#include <random>

#include "gproj/constraints/closeness.h"
#include "gproj/constraints/curvature_auxiliaries.h"

namespace gproj {
namespace {

template <int N>
using Local = std::array<double, N>;

// A random local vector (fixed seed per call site through `seed`).
template <int N>
Local<N> RandomLocal(unsigned seed) {
  std::mt19937 rng(seed);
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  Local<N> x;
  for (double& v : x) v = u(rng);
  return x;
}

// Compares element e of `family` at x with the automatic derivatives of `residual` (a functor
// templated on the scalar: residual(const T* x_local, T* rows)).
template <int N, int Rows, typename Residual>
void ExpectMatchesAutomatic(const ConstraintFamily& family, int e, const Local<N>& x,
                            const Residual& residual) {
  ASSERT_EQ(family.rows_per_element(), Rows) << family.name();
  using Jet = ceres::Jet<double, N>;
  std::array<Jet, N> xj;
  for (int i = 0; i < N; ++i) xj[i] = Jet(x[i], i);
  std::array<Jet, Rows> rows;
  residual(xj.data(), rows.data());
  std::array<double, Rows> phi;
  std::array<double, Rows * N> jac;
  family.EvaluateElement(e, x.data(), phi.data(), jac.data());
  for (int r = 0; r < Rows; ++r) {
    EXPECT_NEAR(phi[r], rows[r].a, 1e-13 * (1.0 + std::abs(rows[r].a)))
        << family.name() << " row " << r;
    for (int l = 0; l < N; ++l) {
      const double automatic = rows[r].v[l];
      EXPECT_NEAR(jac[r * N + l], automatic, 1e-12 * (1.0 + std::abs(automatic)))
          << family.name() << " row " << r << " local " << l;
      if (!family.RowTouches(e, r, l)) {
        EXPECT_EQ(automatic, 0.0) << family.name() << " row " << r << " declared not to touch "
                                  << l;
      }
    }
  }
}

template <typename T>
using Vec3 = Eigen::Matrix<T, 3, 1>;

template <typename T>
Vec3<T> At(const T* x, int offset) {
  return Vec3<T>(x[offset], x[offset + 1], x[offset + 2]);
}

TEST(HandWrittenJacobianTest, ClosenessIsTheOffsetFromItsTarget) {
  const double target[3] = {0.3, -0.2, 0.7};
  Closeness family;
  family.AddTarget(0, target);
  ExpectMatchesAutomatic<3, 3>(family, 0, RandomLocal<3>(1), [&](const auto* v, auto* r) {
    for (int c = 0; c < 3; ++c) r[c] = v[c] - target[c];
  });
}

}  // namespace
}  // namespace gproj
