#include "gproj/geometry/surface/rational_bezier.h"

#include <Eigen/Geometry>
#include <array>
#include <cassert>
#include <cmath>

namespace gproj {
namespace {

// Binomial coefficient for the small degrees of patches.
double Binomial(int n, int k) {
  if (k < 0 || k > n) return 0.0;
  double b = 1.0;
  for (int i = 1; i <= k; ++i) b = b * (n - k + i) / i;
  return b;
}

// Bernstein polynomials of degree n at t, B_0..B_n, zero beyond (no allocation: patches are
// evaluated at every sample of their measures).
using Basis = std::array<double, kMaxPatchDegree + 1>;
Basis Bernstein(int n, double t) {
  Basis b{};
  for (int i = 0; i <= n; ++i) b[i] = Binomial(n, i) * std::pow(t, i) * std::pow(1.0 - t, n - i);
  return b;
}

// B_i^n and its first and second derivatives at t.
struct BasisJet {
  Basis value{}, first{}, second{};
};
BasisJet BernsteinJet(int n, double t) {
  BasisJet jet;
  jet.value = Bernstein(n, t);
  const Basis b1 = Bernstein(n - 1, t), b2 = Bernstein(n - 2, t);
  const auto at = [](const Basis& b, int i) { return i >= 0 ? b[i] : 0.0; };
  for (int i = 0; i <= n; ++i) {
    if (n >= 1) jet.first[i] = n * (at(b1, i - 1) - at(b1, i));
    if (n >= 2) jet.second[i] = n * (n - 1) * (at(b2, i - 2) - 2.0 * at(b2, i - 1) + at(b2, i));
  }
  return jet;
}

}  // namespace

RationalBezierPatch::RationalBezierPatch(int du, int dv)
    : degree_u(du), degree_v(dv), control((du + 1) * (dv + 1), Eigen::Vector4d::Zero()) {
  assert(du >= 1 && dv >= 1 && du <= kMaxPatchDegree && dv <= kMaxPatchDegree);
}

PatchJet EvaluateJet(const RationalBezierPatch& patch, double u, double v) {
  const BasisJet bu = BernsteinJet(patch.degree_u, u), bv = BernsteinJet(patch.degree_v, v);
  // The homogeneous point and its derivatives.
  Eigen::Vector4d h = Eigen::Vector4d::Zero(), hu = h, hv = h, huu = h, huv = h, hvv = h;
  for (int i = 0; i <= patch.degree_u; ++i)
    for (int j = 0; j <= patch.degree_v; ++j) {
      const Eigen::Vector4d& c = patch.At(i, j);
      h += bu.value[i] * bv.value[j] * c;
      hu += bu.first[i] * bv.value[j] * c;
      hv += bu.value[i] * bv.first[j] * c;
      huu += bu.second[i] * bv.value[j] * c;
      huv += bu.first[i] * bv.first[j] * c;
      hvv += bu.value[i] * bv.second[j] * c;
    }
  // x = N / W: W x = N differentiated once and twice.
  const double w = h[3];
  PatchJet jet;
  jet.point = h.head<3>() / w;
  jet.du = (hu.head<3>() - hu[3] * jet.point) / w;
  jet.dv = (hv.head<3>() - hv[3] * jet.point) / w;
  jet.duu = (huu.head<3>() - 2.0 * hu[3] * jet.du - huu[3] * jet.point) / w;
  jet.duv = (huv.head<3>() - hu[3] * jet.dv - hv[3] * jet.du - huv[3] * jet.point) / w;
  jet.dvv = (hvv.head<3>() - 2.0 * hv[3] * jet.dv - hvv[3] * jet.point) / w;
  return jet;
}

Eigen::Vector3d EvaluatePoint(const RationalBezierPatch& patch, double u, double v) {
  const Basis bu = Bernstein(patch.degree_u, u), bv = Bernstein(patch.degree_v, v);
  Eigen::Vector4d h = Eigen::Vector4d::Zero();
  for (int i = 0; i <= patch.degree_u; ++i)
    for (int j = 0; j <= patch.degree_v; ++j) h += bu[i] * bv[j] * patch.At(i, j);
  return h.head<3>() / h[3];
}

PatchCurvature CurvatureOf(const PatchJet& jet) {
  PatchCurvature c;
  const Eigen::Vector3d cross = jet.du.cross(jet.dv);
  c.normal = cross.normalized();
  const double e = jet.du.squaredNorm(), f = jet.du.dot(jet.dv), g = jet.dv.squaredNorm();
  const double l = jet.duu.dot(c.normal), m = jet.duv.dot(c.normal), n = jet.dvv.dot(c.normal);
  const double det = e * g - f * f;
  c.gaussian = (l * n - m * m) / det;
  c.mean = (l * g - 2.0 * m * f + n * e) / (2.0 * det);
  return c;
}

std::vector<double> MultiplyBernstein(const std::vector<double>& f, int fu, int fv,
                                      const std::vector<double>& g, int gu, int gv) {
  const int pu = fu + gu, pv = fv + gv;
  std::vector<double> p((pu + 1) * (pv + 1), 0.0);
  for (int i = 0; i <= fu; ++i)
    for (int j = 0; j <= fv; ++j)
      for (int k = 0; k <= gu; ++k)
        for (int l = 0; l <= gv; ++l) {
          const double scale = Binomial(fu, i) * Binomial(gu, k) / Binomial(pu, i + k) *
                               Binomial(fv, j) * Binomial(gv, l) / Binomial(pv, j + l);
          p[(i + k) * (pv + 1) + j + l] += scale * f[i * (fv + 1) + j] * g[k * (gv + 1) + l];
        }
  return p;
}

}  // namespace gproj
