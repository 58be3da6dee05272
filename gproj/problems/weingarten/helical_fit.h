#pragma once
// How far a surface is from a helical one (003 Fig. 4: "surface colors display the deviation of
// the surface from a helical one … expressed as percentage of the corresponding helical surface
// radius"; (d): "surface points projected on a half-plane through helical motion").
//
// A uniform helical motion has the velocity field v(x) = c × x + c̄ (a linear complex; pitch
// p = c·c̄ / |c|², p = 0 a rotation). A surface is helical when v is tangent to it everywhere:
// n · v(x) = (x × n) · c + n · c̄ = 0 at every point x with normal n. FitHelicalMotion takes the
// (c, c̄), |c| = 1, that minimises Σ (n · v(x))² over sample points (Pottmann & Randrup,
// "Rotational and helical surface approximation for reverse engineering", Computing 60, 1998).
// MeasureHelicalDeviation then moves every point along its helix back to one half-plane
// through the axis: a helical surface lands on a single profile curve there. The spread of
// the landed points about a fitted profile (a polynomial graph over the cloud's principal
// axis) is the deviation, in % of the mean distance to the axis (the surface's radius).

#include <Eigen/Core>
#include <vector>

#include "gproj/geometry/surface/bspline_surface.h"

namespace gproj::weingarten {

struct HelicalMotion {
  Eigen::Vector3d axis_point = Eigen::Vector3d::Zero();  // the axis' point closest to the origin
  Eigen::Vector3d axis = Eigen::Vector3d::UnitZ();       // unit direction
  double pitch = 0.0;     // advance along the axis per radian of turn (0: a rotation)
  double residual = 0.0;  // RMS of n · v(x) over the points, |c| = 1 (a sine times a distance)
};

// points, normals: N × 3 (unit normals), N ≥ 6. Throws InputError when fewer points are given
// or the sizes differ.
HelicalMotion FitHelicalMotion(const Eigen::MatrixX3d& points, const Eigen::MatrixX3d& normals);

struct HelicalDeviation {
  HelicalMotion motion;
  double mean_radius = 0.0;  // mean distance of the points to the axis
  double max_percent = 0.0;  // max distance to the profile / mean_radius × 100
  double mean_percent = 0.0;
  // The landed points in the half-plane: (distance to the axis, height along it).
  std::vector<Eigen::Vector2d> profile_points;
};

// The surface sampled on an (m + 1) × (n + 1) grid of its domain; profile_degree: the
// polynomial degree of the fitted profile.
HelicalDeviation MeasureHelicalDeviation(const BSplineSurface& surface, int m, int n,
                                         int profile_degree = 6);

// A helical test surface and perturbations of it: the profile z = 0.3 (r − 1.5)², r ∈ [1, 2],
// turned by half a turn (θ ∈ [0, π]) about the z-axis, advancing `pitch` per radian; z gains
// bump · exp(−20 ((u − ½)² + (v − 0.4)²)) (a local dent), pitch_drift · θ² (the pitch changing
// along the turn) and profile_drift · (r − 1.5)² · v (the profile changing along the turn).
// Fitted by a B-spline of nu × nv control points and bi-degree (degree, degree).
struct HelicalTestSurface {
  double pitch = 0.4;
  double bump = 0.0, pitch_drift = 0.0, profile_drift = 0.0;
};
BSplineSurface MakeHelicalBSpline(int nu, int nv, int degree, const HelicalTestSurface& spec = {});

}  // namespace gproj::weingarten
