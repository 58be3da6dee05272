#include "gproj/problems/circular/canal_from_curves.h"

#include <Eigen/Geometry>
#include <algorithm>
#include <cmath>
#include <cstdio>

#include "gproj/geometry/mesh/closest_point.h"
#include "gproj/problems/circular/canal_surface.h"
#include "gproj/problems/circular/circular_mesh.h"

namespace gproj::circular {
namespace {

std::string Format(const char* pattern, int k, double value) {
  char text[240];
  std::snprintf(text, sizeof(text), pattern, k, value);
  return text;
}

// The point of `circle` nearest to p (any point of it if p is on its axis).
Eigen::Vector3d NearestOnCircle(const Circle& circle, const Eigen::Vector3d& p) {
  Eigen::Vector3d d = p - circle.centre;
  d -= d.dot(circle.normal) * circle.normal;
  if (d.norm() < 1e-14 * (1.0 + circle.radius)) d = circle.normal.unitOrthogonal();
  return circle.centre + circle.radius * d.normalized();
}

// The point of `circle` nearest to the polyline: the best of 720 angles, refined by golden
// sections on the bracketing interval.
Eigen::Vector3d NearestOnCircleTo(const Circle& circle, const PolylineClosestPoint& line) {
  const Eigen::Vector3d e1 = circle.normal.unitOrthogonal(), e2 = circle.normal.cross(e1);
  auto at = [&](double a) {
    return Eigen::Vector3d(circle.centre + circle.radius * (std::cos(a) * e1 + std::sin(a) * e2));
  };
  auto distance = [&](double a) { return (line.Closest(at(a)) - at(a)).norm(); };
  constexpr int kSteps = 720;
  double best = 0.0, nearest = HUGE_VAL;
  for (int i = 0; i < kSteps; ++i) {
    const double a = 2.0 * M_PI * i / kSteps, d = distance(a);
    if (d < nearest) nearest = d, best = a;
  }
  double lo = best - 2.0 * M_PI / kSteps, hi = best + 2.0 * M_PI / kSteps;
  const double g = 0.5 * (std::sqrt(5.0) - 1.0);
  // Golden sections: one new distance per step, the other point carried over.
  double a = hi - g * (hi - lo), b = lo + g * (hi - lo);
  double fa = distance(a), fb = distance(b);
  for (int i = 0; i < 60; ++i) {
    if (fa < fb) {
      hi = b, b = a, fb = fa;
      a = hi - g * (hi - lo), fa = distance(a);
    } else {
      lo = a, a = b, fa = fb;
      b = lo + g * (hi - lo), fb = distance(b);
    }
  }
  return at(0.5 * (lo + hi));
}

}  // namespace

bool CanalFromCurvesOptions::IsValid(std::string* why) const {
  if (segments < 1 || segments > 100000) {
    *why = "segments must be in [1, 100000]";
    return false;
  }
  if (max_newton_steps < 1) {
    *why = "max_newton_steps must be >= 1";
    return false;
  }
  if (!(fit_tolerance > 0.0)) {
    *why = "fit_tolerance must be > 0";
    return false;
  }
  return true;
}

namespace {

// The normals n_k of the developable along curve 1: n_0 is `normal` made orthogonal to the
// curve's tangent at P_0 (the tangent at P_0 of the circle through P_0, P_1, P_2; the chord if
// they are collinear), and each next one its mirror image in the bisector plane of the edge.
// Mirror images keep every n_k orthogonal to the tangent of the circle through P_{k−1}, P_k,
// P_{k+1} wherever the curve is a circle (exact on circles and lines).
std::vector<Eigen::Vector3d> DevelopableNormals(const std::vector<Eigen::Vector3d>& curve1,
                                                const Eigen::Vector3d& normal, double length) {
  Eigen::Vector3d t0 = (curve1[1] - curve1[0]).normalized();
  const Circle first = CircleThrough<double>(curve1[0], curve1[1], curve1[2]);
  if (std::isfinite(first.radius) && first.radius < 1e8 * length)
    t0 = first.normal.cross(curve1[0] - first.centre).normalized();
  Eigen::Vector3d n0 = normal - normal.dot(t0) * t0;
  if (!normal.allFinite() || !(n0.norm() > 1e-6 * normal.norm()))
    throw InputError(
        "the normal at P_0 runs along the curve (or is zero): it fixes no "
        "developable of normals");
  std::vector<Eigen::Vector3d> normals = {n0.normalized()};
  for (size_t k = 0; k + 1 < curve1.size(); ++k) {
    const Eigen::Vector3d e = (curve1[k + 1] - curve1[k]).normalized();
    const Eigen::Vector3d& nk = normals.back();
    normals.push_back(nk - 2.0 * nk.dot(e) * e);
  }
  return normals;
}

// Sphere k by eq. 6: h(s) = σ s − |C(s) C'(s)| = 0 on the side σ of the second curve, by
// Newton's method from s = 0 (C = P_k); h'(s) = σ − u · n_k with u the unit vector from C'.
// Appends its centre, radius and fit residual to `out`; throws InputError when none fits.
void FitSphere(int k, const Eigen::Vector3d& p, const Eigen::Vector3d& nk,
               const PolylineClosestPoint& second_curve, const CanalFromCurvesOptions& options,
               double length, CanalFromCurves* out) {
  const double tolerance = options.fit_tolerance * length;
  const Eigen::Vector3d start = second_curve.Closest(p);
  if (!((start - p).norm() > 1e-9 * length))
    throw InputError(
        Format("the second curve passes through point %d of the line of curvature "
               "(a sphere of radius 0 there): the curves must not touch (%.3g)",
               k, (start - p).norm()));
  const double sigma = (start - p).dot(nk) >= 0.0 ? 1.0 : -1.0;
  double s = 0.0, residual = HUGE_VAL;
  for (int step = 0; step < options.max_newton_steps; ++step) {
    const Eigen::Vector3d c = p + s * nk, closest = second_curve.Closest(c);
    const Eigen::Vector3d away = c - closest;
    const double d = away.norm();
    residual = sigma * s - d;
    if (std::abs(residual) <= 1e-3 * tolerance) break;
    const double slope = sigma - (d > 0.0 ? away.dot(nk) / d : 0.0);
    if (!(std::abs(slope) > 1e-12)) break;
    s -= residual / slope;
  }
  const Eigen::Vector3d c = p + s * nk;
  const double fit = std::abs(std::abs(s) - (second_curve.Closest(c) - c).norm());
  if (!(fit <= tolerance) || !std::isfinite(s))
    throw InputError(
        Format("sphere %d: no centre on the normal line is as far from the second "
               "curve as from P_k (|R - dist| = %.3g after Newton's method)",
               k, fit));
  out->centres.push_back(c);
  out->radii.push_back(std::abs(s));
  out->fit_residuals.push_back(fit);
}

// 𝒞_k = S_k ∩ S_{k+1}; throws InputError when two spheres do not meet in a circle.
void IntersectSpheres(CanalFromCurves* out) {
  for (size_t k = 0; k + 1 < out->centres.size(); ++k) {
    const Eigen::Vector3d axis = out->centres[k + 1] - out->centres[k];
    const double d = axis.norm(), r0 = out->radii[k], r1 = out->radii[k + 1];
    const int i = static_cast<int>(k);
    if (!(d > 0.0))
      throw InputError(Format("spheres %d and %d are concentric: they share no circle", i, i + 1));
    const double a = (d * d + r0 * r0 - r1 * r1) / (2.0 * d), rho2 = r0 * r0 - a * a;
    if (!(rho2 > 0.0))
      throw InputError(
          Format("spheres %d and the next do not meet (their circle would have "
                 "squared radius %.3g): refine the line of curvature",
                 i, rho2));
    Circle circle;
    circle.normal = axis / d;
    circle.centre = out->centres[k] + a * circle.normal;
    circle.radius = std::sqrt(rho2);
    out->circles.push_back(circle);
  }
}

// The net between consecutive circles: first vertices nearest to the line of curvature, the
// first circle's arc (the shorter way round) to its point nearest to the second curve.
CyclidicStrip NetBetweenCircles(const std::vector<Eigen::Vector3d>& curve1,
                                const PolylineClosestPoint& second_curve,
                                const std::vector<Circle>& circles) {
  CyclidicStrip net;
  net.circles = circles;
  for (size_t k = 0; k < circles.size(); ++k)
    net.strip.p.push_back(NearestOnCircle(circles[k], 0.5 * (curve1[k] + curve1[k + 1])));
  net.strip.q = net.strip.p;
  net.strip.q[0] = NearestOnCircleTo(circles[0], second_curve);
  Circle& c0 = net.circles[0];
  const Eigen::Vector3d from = net.strip.p[0] - c0.centre, to = net.strip.q[0] - c0.centre;
  if (c0.normal.dot(from.cross(to)) < 0.0) c0.normal = -c0.normal;
  return net;
}

// How closely the surface's circles pass the two curves: each circle's first vertex from the
// line of curvature, and each sphere's contact point with the second curve from the nearer of
// the sphere's two circles; then MeasureCircularMesh's measures.
NamedValues MeasureFit(const CyclidicStrip& net, const PolylineClosestPoint& first_curve,
                       const PolylineClosestPoint& second_curve, const CanalFromCurves& out) {
  const int n = static_cast<int>(out.circles.size());
  double curve1_distance = 0.0, curve2_distance = 0.0, sphere_fit = 0.0;
  for (int k = 0; k < n; ++k)
    curve1_distance =
        std::max(curve1_distance, (net.strip.p[k] - first_curve.Closest(net.strip.p[k])).norm());
  for (int k = 0; k <= n; ++k) {
    const Eigen::Vector3d contact = second_curve.Closest(out.centres[k]);
    double nearest = HUGE_VAL;
    for (int c : {k - 1, k})
      if (c >= 0 && c < n) nearest = std::min(nearest, DistanceToCircle(contact, out.circles[c]));
    curve2_distance = std::max(curve2_distance, nearest);
  }
  for (double f : out.fit_residuals) sphere_fit = std::max(sphere_fit, f);
  NamedValues measures = {{"max_sphere_fit", sphere_fit},
                          {"max_curve1_distance", curve1_distance},
                          {"max_curve2_distance", curve2_distance}};
  const NamedValues circular = MeasureCircularMesh(out.mesh);
  measures.insert(measures.end(), circular.begin(), circular.end());
  return measures;
}

// FitCanalToCurves on curves scaled so that curve 1 has unit length.
CanalFromCurves FitAtUnitScale(const std::vector<Eigen::Vector3d>& curve1,
                               const std::vector<Eigen::Vector3d>& curve2,
                               const Eigen::Vector3d& normal,
                               const CanalFromCurvesOptions& options) {
  const double length = 1.0;
  const PolylineClosestPoint first_curve(curve1), second_curve(curve2);
  CanalFromCurves out;
  out.normals = DevelopableNormals(curve1, normal, length);
  for (size_t k = 0; k < curve1.size(); ++k)
    FitSphere(static_cast<int>(k), curve1[k], out.normals[k], second_curve, options, length, &out);
  IntersectSpheres(&out);
  const CyclidicStrip net = NetBetweenCircles(curve1, second_curve, out.circles);
  out.mesh = MeshCanalSurface(net, options.segments);
  out.measures = MeasureFit(net, first_curve, second_curve, out);
  return out;
}

}  // namespace

CanalFromCurves FitCanalToCurves(const std::vector<Eigen::Vector3d>& curve1,
                                 const std::vector<Eigen::Vector3d>& curve2,
                                 const Eigen::Vector3d& normal,
                                 const CanalFromCurvesOptions& options) {
  std::string why;
  if (!options.IsValid(&why)) throw InputError(why);
  const int n = static_cast<int>(curve1.size()) - 1;
  if (n < 2) throw InputError("the line of curvature needs at least 3 points");
  if (curve2.size() < 2) throw InputError("the second curve needs at least 2 points");
  double length = 0.0;
  for (int k = 0; k < n; ++k) {
    const double l = (curve1[k + 1] - curve1[k]).stableNorm();
    if (!(l > 0.0)) throw InputError(Format("curve 1: points %d and %d coincide", k, k + 1));
    length += l;
  }
  if (!std::isfinite(length)) throw InputError("curve 1 is too long to measure");
  const Eigen::Vector3d origin = curve1[0];
  auto to_unit = [&](const std::vector<Eigen::Vector3d>& curve) {
    std::vector<Eigen::Vector3d> unit;
    unit.reserve(curve.size());
    for (const Eigen::Vector3d& p : curve) unit.push_back((p - origin) / length);
    return unit;
  };
  const double largest = normal.cwiseAbs().maxCoeff();
  const Eigen::Vector3d direction =
      largest > 0.0 && std::isfinite(largest) ? Eigen::Vector3d(normal / largest) : normal;
  CanalFromCurves out = FitAtUnitScale(to_unit(curve1), to_unit(curve2), direction, options);
  for (Eigen::Vector3d& c : out.centres) c = c * length + origin;
  for (double& r : out.radii) r *= length;
  for (double& f : out.fit_residuals) f *= length;
  for (Circle& c : out.circles) {
    c.centre = c.centre * length + origin;
    c.radius *= length;
  }
  for (auto v : out.mesh.vertices()) {
    const auto& q = out.mesh.point(v);
    const Eigen::Vector3d p = Eigen::Vector3d(q[0], q[1], q[2]) * length + origin;
    out.mesh.set_point(v, PolyMesh::Point(p.x(), p.y(), p.z()));
  }
  for (NamedValue& m : out.measures)
    if (m.name == "max_sphere_fit" || m.name == "max_curve1_distance" ||
        m.name == "max_curve2_distance")
      m.value *= length;
  return out;
}

}  // namespace gproj::circular
