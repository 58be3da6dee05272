#pragma once
// Rational tensor-product Bézier patches: the rational bilinear patches of H-nets (004 eq. 1)
// and their images under inversions (rational biquadratic Darboux cyclide patches). Points,
// derivatives up to second order and curvature, exactly from the homogeneous control points.

#include <Eigen/Core>
#include <vector>

namespace gproj {

// The highest degree a patch may have (the image of a bilinear patch under an inversion has 2).
inline constexpr int kMaxPatchDegree = 8;

// point(u, v) = Σ B_i(u) B_j(v) H_ij.head<3>() / Σ B_i(u) B_j(v) H_ij[3] on (u, v) ∈ [0, 1]²,
// B the Bernstein polynomials of degree (degree_u, degree_v) and H_ij the homogeneous control
// points (w x, w y, w z, w).
struct RationalBezierPatch {
  int degree_u = 1, degree_v = 1;
  std::vector<Eigen::Vector4d> control;  // H_ij at i * (degree_v + 1) + j

  RationalBezierPatch() = default;
  RationalBezierPatch(int du, int dv);  // 1 ≤ du, dv ≤ kMaxPatchDegree
  Eigen::Vector4d& At(int i, int j) { return control[i * (degree_v + 1) + j]; }
  const Eigen::Vector4d& At(int i, int j) const { return control[i * (degree_v + 1) + j]; }
};

// A point of a patch with its partial derivatives.
struct PatchJet {
  Eigen::Vector3d point, du, dv, duu, duv, dvv;
};
PatchJet EvaluateJet(const RationalBezierPatch& patch, double u, double v);
Eigen::Vector3d EvaluatePoint(const RationalBezierPatch& patch, double u, double v);

// The unit normal du × dv / |du × dv| and the Gaussian and mean curvature with respect to it
// (second fundamental form L = x_uu · n, M = x_uv · n, N = x_vv · n).
struct PatchCurvature {
  Eigen::Vector3d normal;
  double gaussian = 0.0, mean = 0.0;
};
PatchCurvature CurvatureOf(const PatchJet& jet);

// The Bernstein coefficients of the product of two polynomials given by theirs: f of degree
// (fu, fv), g of degree (gu, gv), each at i * (degree_v + 1) + j; the product has degree
// (fu + gu, fv + gv).
std::vector<double> MultiplyBernstein(const std::vector<double>& f, int fu, int fv,
                                      const std::vector<double>& g, int gu, int gv);

}  // namespace gproj
