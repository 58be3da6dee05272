// Hand-written Jacobians against automatic differentiation. The few families that keep a
// hand-written Jacobian are those a term cannot express: Closeness and PolylineFairness take
// items of any dimension (Python's blocks), CurvatureAuxiliaries a stencil of any number of
// control points. They are checked here against the residual
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
#include "gproj/constraints/polyline_fairness.h"

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

TEST(HandWrittenJacobianTest, PolylineFairnessSecondAndThirdDifferences) {
  PolylineFairness second(2, 3);
  second.AddElement({0, 1, 2});
  ExpectMatchesAutomatic<9, 3>(second, 0, RandomLocal<9>(5), [](const auto* x, auto* r) {
    for (int c = 0; c < 3; ++c) r[c] = x[c] - 2.0 * x[3 + c] + x[6 + c];
  });
  PolylineFairness third(3, 2);  // items of dimension 2
  third.AddElement({0, 1, 2, 3});
  ExpectMatchesAutomatic<8, 2>(third, 0, RandomLocal<8>(6), [](const auto* x, auto* r) {
    for (int c = 0; c < 2; ++c) r[c] = x[c] - 3.0 * x[2 + c] + 3.0 * x[4 + c] - x[6 + c];
  });
}

TEST(HandWrittenJacobianTest, CurvatureDefinitionsOfAFourPointStencil) {
  SampleStencil stencil;
  stencil.control = {0, 1, 2, 3};
  const Local<20> w = RandomLocal<20>(7);
  for (int k = 0; k < 5; ++k) stencil.weights[k].assign(w.begin() + 4 * k, w.begin() + 4 * k + 4);
  std::array<double, 12> magnitude;
  for (int r = 0; r < 12; ++r) magnitude[r] = 0.5 + 0.1 * r;
  CurvatureAuxiliaries family;
  family.AddSample(0, 1, {2, 3, 4, 5}, stencil, &magnitude);
  const double sigma = 1.0;  // √Δᵏ before the first update
  ExpectMatchesAutomatic<24, 12>(family, 0, RandomLocal<24>(8), [&](const auto* x, auto* r) {
    using T = std::decay_t<decltype(x[0])>;
    Vec3<T> d[5];
    for (int k = 0; k < 5; ++k) {
      d[k].setZero();
      for (int j = 0; j < 4; ++j) d[k] += stencil.weights[k][j] * At(x, 12 + 3 * j);
    }
    const Vec3<T> n = At(x, kN), cross = d[0].cross(d[1]);
    const T &E = x[kE], &F = x[kF], &G = x[kG], &D = x[kDelta], &L = x[kL], &M = x[kM], &N = x[kNn],
            &K = x[kK], &H = x[kH];
    for (int c = 0; c < 3; ++c) r[c] = n[c] - cross[c];
    r[3] = E - d[0].dot(d[0]);
    r[4] = F - d[0].dot(d[1]);
    r[5] = G - d[1].dot(d[1]);
    r[6] = D - (E * G - F * F);
    r[7] = sigma * L - d[2].dot(n);
    r[8] = sigma * M - d[3].dot(n);
    r[9] = sigma * N - d[4].dot(n);
    r[10] = K * D - (L * N - M * M);
    r[11] = 2.0 * H * D - (L * G - 2.0 * M * F + N * E);
    for (int row = 0; row < 12; ++row) r[row] /= magnitude[row];
  });
}

}  // namespace
}  // namespace gproj
