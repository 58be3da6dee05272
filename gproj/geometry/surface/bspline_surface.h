#pragma once
// Tensor-product B-spline surfaces (003 §3.1.1, eq. 9):
//   s(u, v) = Σ_i Σ_j N_i^{d_u}(u) N_j^{d_v}(v) c_ij,
// any bi-degree, clamped knot vectors. Points and derivatives up to second order are linear in
// the control points; SampleMaps builds those linear maps once for a grid of parameter samples.
// JSON format (docs/formats.md): {"degree": [du, dv], "knots_u": [...], "knots_v": [...],
//                         "control_points": [[[x, y, z], ... nv], ... nu]}, control_points[i][j]
// with i along u.

#include <Eigen/Core>
#include <Eigen/SparseCore>
#include <array>
#include <functional>
#include <string>
#include <vector>

#include "gproj/geometry/io/mesh_io.h"

namespace gproj {

struct BSplineSurface {
  int degree_u = 3, degree_v = 3;
  std::vector<double> knots_u, knots_v;  // clamped: degree + 1 equal values at each end
  int nu = 0, nv = 0;                    // control points along u and v
  Eigen::MatrixX3d control;              // nu·nv × 3; row i * nv + j is c_ij

  int Index(int i, int j) const { return i * nv + j; }
  int num_control_points() const { return nu * nv; }
  // Parameter domain [knots[degree], knots[count − degree − 1]] in each direction.
  double u_min() const { return knots_u[degree_u]; }
  double u_max() const { return knots_u[knots_u.size() - degree_u - 1]; }
  double v_min() const { return knots_v[degree_v]; }
  double v_max() const { return knots_v[knots_v.size() - degree_v - 1]; }

  // (u, v) outside the domain is clamped to it.
  Eigen::Vector3d Point(double u, double v) const;
  // Derivatives at (u, v): [0] s, [1] s_u, [2] s_v, [3] s_uu, [4] s_uv, [5] s_vv.
  std::array<Eigen::Vector3d, 6> Derivatives(double u, double v) const;
};

// Checks every rule and throws InputError naming the rule (and `where`, e.g. the file):
// degrees ≥ 1; knot vector length = control points + degree + 1; knots finite and
// non-decreasing; clamped ends (degree + 1 equal knots); a non-empty domain; at least degree + 1
// control points per direction; control has nu·nv rows; every coordinate finite.
void ValidateBSpline(const BSplineSurface& surface, const std::string& where = "");

// JSON text ↔ surface. Parse errors and rule violations throw InputError naming `path` and the
// JSON field (e.g. "control_points[3][2]").
BSplineSurface ParseBSplineJson(const std::string& text, const std::string& path = "");
BSplineSurface ReadBSplineJson(const std::string& path);
// BSplineToJson validates first; numbers are written in the shortest form that reads back
// exactly.
std::string BSplineToJson(const BSplineSurface& surface);
// Atomic (temporary file, then rename), via WriteTextFileAtomically.
void WriteBSplineJson(const BSplineSurface& surface, const std::string& path);

// Clamped knot vector with uniform inner knots over [0, 1] for `count` control points.
std::vector<double> UniformClampedKnots(int count, int degree);

// Linear maps from the control points to s, s_u, s_v, s_uu, s_uv, s_vv at the samples
// (u_a, v_b), a = 0..su−1, b = 0..sv−1, sample index a * sv + b. The samples are the centres of
// a uniform su × sv subdivision of the parameter domain: u_a = u_min + (a + ½)(u_max − u_min)/su.
// Each map is (su·sv) × (nu·nv); applying it to `control` (nu·nv × 3) gives the derivative at
// every sample. Built once; they do not change while the control points move. Every row stores
// (du + 1)(dv + 1) entries, explicit zeros included (e.g. s_uu when du = 1).
struct SampleMaps {
  int su = 0, sv = 0;
  std::vector<double> u, v;  // su and sv parameter values
  std::array<Eigen::SparseMatrix<double, Eigen::RowMajor>, 6> d;
  int num_samples() const { return su * sv; }
  int Index(int a, int b) const { return a * sv + b; }
};
SampleMaps MakeSampleMaps(const BSplineSurface& surface, int su, int sv);

// Least-squares fit of a surface with the given degrees and nu × nv control points (uniform
// clamped knots over [0, 1]) to points f(u, v), (u, v) ∈ [0, 1]², sampled on a grid of
// `samples_per_control` × (nu, nv) points (multiresolution refit, 003 §4.1.1; also builds test
// surfaces from analytic ones).
BSplineSurface FitBSpline(const std::function<Eigen::Vector3d(double, double)>& f, int degree_u,
                          int degree_v, int nu, int nv, int samples_per_control = 4);

// Refit of `surface` onto a denser control net (nu × nv, same degrees) by least squares,
// the domain mapped to [0, 1]².
BSplineSurface RefitBSpline(const BSplineSurface& surface, int nu, int nv);

// Inserts `per_span` uniformly spaced knots inside every non-empty knot span in both directions
// (knot refinement, NURBS Book A5.4): the same surface with more control points.
BSplineSurface InsertKnotsUniform(const BSplineSurface& surface, int per_span);

// A freeform test and benchmark surface: bi-degree (degree, degree), uniform clamped knots,
// control point (i, j) at (x, y, a (0.3 sin 2x cos 1.5y + 0.2 x y + 0.15 x²)) on a uniform grid
// of [−1, 1]², a = amplitude.
BSplineSurface MakeWavyBSpline(int nu, int nv, int degree, double amplitude = 1.0);
// A bump over [−1, 1]² with a planar boundary (the start of 003 Fig. 3's fixtures; shipped as
// examples/data/bump_14x14.json): bi-degree (degree, degree), control point (i, j) at
// (x, y, 0.15 (1 − x²)(1 − y²)(1 + 0.3 x + 0.2 y²)) on a uniform grid.
BSplineSurface MakeBumpBSpline(int n, int degree = 4);

// Regularity: the smallest cosine between the unit normals (s_u × s_v) at neighbouring points
// of an (m + 1) × (n + 1) grid over the domain, and where (the parameters of the pair's first
// point). A regular surface sampled densely stays near 1; a fold, where s_u × s_v turns through
// zero, shows as a cosine near −1. A point where s_u × s_v = 0 counts as −1.
struct NormalTurn {
  double min_cosine = 1.0;
  double u = 0.0, v = 0.0;
};
NormalTurn MinNormalCosine(const BSplineSurface& surface, int m, int n);

// MinNormalCosine for a surface whose control points change (an optimisation checking every
// trial): the basis values at the grid are computed once, and each call costs two tensor
// contractions with no allocation.
class GridNormals {
 public:
  GridNormals() = default;
  // Throws InputError for an invalid surface or a grid smaller than 1 × 1.
  GridNormals(const BSplineSurface& surface, int m, int n);
  // control: the control points (row surface.Index(i, j)) of a surface with the knots and
  // degrees given to the constructor.
  NormalTurn MinCosine(const Eigen::MatrixX3d& control);

 private:
  int m_ = 0, n_ = 0, nv_ = 0, pu_ = 0, pv_ = 0;
  double u0_ = 0.0, u_step_ = 0.0, v0_ = 0.0, v_step_ = 0.0;
  std::vector<int> first_u_, first_v_;   // first control index of each grid parameter's span
  Eigen::MatrixXd bu_, dbu_, bv_, dbv_;  // basis values and first derivatives per grid parameter
  Eigen::MatrixX3d along_u_, along_du_;  // Σ_i N_i(u_a) c_ij and Σ_i N_i'(u_a) c_ij, row a nv + j
  std::vector<Eigen::Vector3d> normal_;
};

// The control net as a quad mesh (vertex i * nv + j), for pictures and `gproj` outputs.
PolyMesh ControlNetMesh(const BSplineSurface& surface);
// The surface sampled on an (m + 1) × (n + 1) grid of the domain as a quad mesh.
PolyMesh SampleSurfaceMesh(const BSplineSurface& surface, int m, int n);

}  // namespace gproj
