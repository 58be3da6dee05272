#include "gproj/problems/circular/m_revolution.h"

#include <Eigen/Geometry>
#include <algorithm>
#include <array>
#include <cmath>
#include <cstdio>

#include "gproj/geometry/mesh/circle.h"

namespace gproj::circular {

bool MRevolutionOptions::IsValid(std::string* why) const {
  if (!(t > 0.0) || !std::isfinite(t)) {
    *why = "t must be a finite number > 0";
    return false;
  }
  if (root != 0 && root != 1) {
    *why = "the root must be 0 or 1";
    return false;
  }
  if (!up.allFinite()) {
    *why = "the up direction must be finite";
    return false;
  }
  if (arch_segments < 2 || arch_segments > 100000) {
    *why = "the arch needs 2 to 100000 segments";
    return false;
  }
  return true;
}

namespace {

std::string Format(const char* format, double a, double b = 0.0) {
  char text[256];
  std::snprintf(text, sizeof(text), format, a, b);
  return text;
}

// The largest distance of a curve point, P2 or P3 from P1: the scale of the checks.
double CurveExtent(const std::vector<Eigen::Vector3d>& curve, const Eigen::Vector3d& p2,
                   const Eigen::Vector3d& p3) {
  const Eigen::Vector3d& p1 = curve.front();
  double extent = 0.0;
  for (const Eigen::Vector3d& p : curve) extent = std::max(extent, (p - p1).norm());
  return std::max({extent, (p2 - p1).norm(), (p3 - p1).norm()});
}

// Throws InputError for invalid options, a curve of fewer than 2 points, non-finite points,
// two of P1..P4 that coincide, or a mesh too large.
void CheckMRevolutionInput(const std::vector<Eigen::Vector3d>& curve, const Eigen::Vector3d& p2,
                           const Eigen::Vector3d& p3, const MRevolutionOptions& options) {
  std::string why;
  if (!options.IsValid(&why)) throw InputError(why);
  if (curve.size() < 2)
    throw InputError("the curve needs at least 2 points (P1 first, P4 last), got " +
                     std::to_string(curve.size()));
  for (size_t i = 0; i < curve.size(); ++i)
    if (!curve[i].allFinite())
      throw InputError("curve point " + std::to_string(i) + " is not finite");
  if (!p2.allFinite() || !p3.allFinite()) throw InputError("P2 and P3 must be finite");
  const double extent = CurveExtent(curve, p2, p3);
  const std::array<Eigen::Vector3d, 4> quad = {curve.front(), p2, p3, curve.back()};
  const std::array<const char*, 4> names = {"P1 (the curve's start)", "P2", "P3",
                                            "P4 (the curve's end)"};
  for (int i = 0; i < 4; ++i)
    for (int j = i + 1; j < 4; ++j)
      if ((quad[i] - quad[j]).norm() <= 1e-9 * extent)
        throw InputError(std::string(names[i]) + " and " + names[j] +
                         " coincide: the four points must be distinct");
  if (static_cast<double>(curve.size()) * (options.arch_segments + 1) > 5e7)
    throw InputError(
        "the mesh would have " +
        std::to_string(static_cast<double>(curve.size()) * (options.arch_segments + 1)) +
        " vertices (curve points × (arch segments + 1)); at most 5e7");
}

// ChooseMRevolutionCentre for the quad P1 P2 P3 P4, its errors saying which point is off.
MRevolutionChoice ChooseCentre(const std::array<Eigen::Vector3d, 4>& quad,
                               const MRevolutionOptions& options, double extent) {
  try {
    return ChooseMRevolutionCentre(quad, options.t, options.root, 1.0);
  } catch (const InputError& e) {
    const std::string what = e.what();
    if (what.find("on the quad's circle") != std::string::npos)
      throw InputError(what +
                       " (or P2 and P3 are out of order: P1, P2, P3, P4 must follow each "
                       "other around the circle)");
    if (what.find("concyclic") != std::string::npos) {
      // Which point is off: P3 against the circle through P1, P2, P4, and P2 against P1 P3 P4.
      const Eigen::Vector3d a[3] = {quad[0], quad[1], quad[3]}, b[3] = {quad[0], quad[2], quad[3]};
      const double off3 = DistanceToCircle(quad[2], FitCircle(a, 3)) / extent;
      const double off2 = DistanceToCircle(quad[1], FitCircle(b, 3)) / extent;
      throw InputError(
          Format("P2 and P3 must lie on one circle with P1 and P4: `p3` is %.3g "
                 "curve extents from the circle through P1, P2, P4 (`p2`: %.3g from "
                 "the one through P1, P3, P4)",
                 off3, off2));
    }
    throw;
  }
}

// The normal of the drawing plane P1 P2 P4 on the side of `up` (else with z ≥ 0); throws
// InputError when `up` lies in the plane or a curve point is off it.
Eigen::Vector3d DrawingNormal(const std::vector<Eigen::Vector3d>& curve, const Eigen::Vector3d& p2,
                              const MRevolutionOptions& options, double extent) {
  const Eigen::Vector3d &p1 = curve.front(), &p4 = curve.back();
  Eigen::Vector3d normal = (p2 - p1).cross(p4 - p1).normalized();
  if (options.up.norm() > 0.0) {
    if (std::abs(normal.dot(options.up.normalized())) < 1e-6)
      throw InputError("`up` lies in the drawing plane: it must point to one side of it");
    if (normal.dot(options.up) < 0.0) normal = -normal;
  } else if (normal.z() < -1e-6) {
    normal = -normal;
  }
  for (size_t i = 1; i + 1 < curve.size(); ++i) {
    const double off = std::abs(normal.dot(curve[i] - p1)) / extent;
    if (off > 1e-8)
      throw InputError("curve point " + std::to_string(i) +
                       Format(" is %.3g curve extents off the plane of P1, P2, P4: the curve must "
                              "lie in the plane of the circle",
                              off));
  }
  return normal;
}

// The curve's image (the meridian); sets the axis of the trapezoid P1'P2'P3'P4' (the
// perpendicular bisector of P1'P2' in the drawing plane). Throws InputError for a curve point
// at the inversion centre or one whose image lies on the axis.
std::vector<Eigen::Vector3d> Meridian(const std::vector<Eigen::Vector3d>& curve,
                                      const Eigen::Vector3d& normal, double extent,
                                      MRevolutionSurface* out) {
  const Eigen::Vector3d& c = out->choice.centre;
  for (size_t i = 0; i < curve.size(); ++i)
    if ((curve[i] - c).norm() <= 1e-6 * extent)
      throw InputError("curve point " + std::to_string(i) +
                       Format(" is %.3g curve extents from the inversion centre: its image runs "
                              "off to infinity (choose another t or root)",
                              (curve[i] - c).norm() / extent));
  std::vector<Eigen::Vector3d> meridian;
  for (const Eigen::Vector3d& p : curve) meridian.push_back(Invert(p, c, out->ratio));
  const Eigen::Vector3d q1 = out->choice.image.points[0], q2 = out->choice.image.points[1];
  out->axis_point = 0.5 * (q1 + q2);
  out->axis_direction = normal.cross(q2 - q1).normalized();
  double meridian_extent = 0.0;
  for (const Eigen::Vector3d& p : meridian)
    meridian_extent = std::max(meridian_extent, (p - meridian.front()).norm());
  for (size_t i = 0; i < meridian.size(); ++i) {
    const Eigen::Vector3d r = meridian[i] - out->axis_point;
    const double radius = (r - r.dot(out->axis_direction) * out->axis_direction).norm();
    if (radius <= 1e-9 * meridian_extent)
      throw InputError("curve point " + std::to_string(i) +
                       " maps onto the axis of revolution: its parallel would be a point (choose "
                       "another t or root)");
  }
  return meridian;
}

// Turns the meridian by π about the axis, towards +normal first (out->revolution), and maps it
// back (out->mesh, the curve's own points at j = 0 so that the guide stays exact).
void Revolve(const std::vector<Eigen::Vector3d>& curve,
             const std::vector<Eigen::Vector3d>& meridian, const Eigen::Vector3d& normal, int m,
             MRevolutionSurface* out) {
  const Eigen::Vector3d& c = out->choice.centre;
  const int rows = static_cast<int>(meridian.size());
  std::vector<PolyMesh::VertexHandle> rv, mv;
  double sense = 1.0;
  {
    const Eigen::Vector3d r = meridian[0] - out->axis_point;
    const Eigen::Vector3d turned = Eigen::AngleAxisd(M_PI / 2, out->axis_direction) * r;
    if (turned.dot(normal) < 0.0) sense = -1.0;
  }
  for (int i = 0; i < rows; ++i)
    for (int j = 0; j <= m; ++j) {
      const double angle = sense * M_PI * j / m;
      const Eigen::Vector3d p = out->axis_point + Eigen::AngleAxisd(angle, out->axis_direction) *
                                                      (meridian[i] - out->axis_point);
      rv.push_back(out->revolution.add_vertex(PolyMesh::Point(p.x(), p.y(), p.z())));
      // f⁻¹ = f; the curve's own points where they are (j = 0), so the guide stays exact.
      const Eigen::Vector3d back = j == 0 ? curve[i] : Invert(p, c, out->ratio);
      mv.push_back(out->mesh.add_vertex(PolyMesh::Point(back.x(), back.y(), back.z())));
    }
  for (int i = 0; i + 1 < rows; ++i)
    for (int j = 0; j < m; ++j) {
      const int a = i * (m + 1) + j, b = (i + 1) * (m + 1) + j;
      out->revolution.add_face({rv[a], rv[b], rv[b + 1], rv[a + 1]});
      out->mesh.add_face({mv[a], mv[b], mv[b + 1], mv[a + 1]});
    }
}

// The checks: f⁻¹(f(P_i)) against P_i, the far meridian's ends against P2 and P3, the arches'
// planes (all per curve extent).
void MeasureMRevolution(const std::vector<Eigen::Vector3d>& curve,
                        const std::vector<Eigen::Vector3d>& meridian, const Eigen::Vector3d& p2,
                        const Eigen::Vector3d& p3, int m, double extent, MRevolutionSurface* out) {
  const int rows = static_cast<int>(meridian.size());
  for (int i = 0; i < rows; ++i)
    out->curve_roundtrip =
        std::max(out->curve_roundtrip,
                 (Invert(meridian[i], out->choice.centre, out->ratio) - curve[i]).norm() / extent);
  const auto at = [&](int i, int j) {
    return Eigen::Vector3d(out->mesh.point(out->mesh.vertex_handle(i * (m + 1) + j)).data());
  };
  out->far_meridian_miss = std::max((at(0, m) - p2).norm(), (at(rows - 1, m) - p3).norm()) / extent;
  for (int i = 0; i < rows; ++i) {
    // The arch's plane: through its ends and a middle point.
    const Eigen::Vector3d a = at(i, 0), b = at(i, m / 2), e = at(i, m);
    const Eigen::Vector3d n = (b - a).cross(e - a).normalized();
    for (int j = 0; j <= m; ++j)
      out->arch_planarity = std::max(out->arch_planarity, std::abs(n.dot(at(i, j) - a)) / extent);
  }
}

}  // namespace

MRevolutionSurface BuildMRevolutionSurface(const std::vector<Eigen::Vector3d>& curve,
                                           const Eigen::Vector3d& p2, const Eigen::Vector3d& p3,
                                           const MRevolutionOptions& options) {
  CheckMRevolutionInput(curve, p2, p3, options);
  const double extent = CurveExtent(curve, p2, p3);
  // The drawing plane: P1, P2, P4 (MRevolutionCentres checks P3 and concyclicity).
  const std::array<Eigen::Vector3d, 4> quad = {curve.front(), p2, p3, curve.back()};
  MRevolutionSurface out;
  out.choice = ChooseCentre(quad, options, extent);
  const Eigen::Vector3d normal = DrawingNormal(curve, p2, options, extent);
  out.ratio = (curve.front() - out.choice.centre).squaredNorm();
  out.choice.image = InvertQuad(quad, out.choice.centre, out.ratio);
  const std::vector<Eigen::Vector3d> meridian = Meridian(curve, normal, extent, &out);
  Revolve(curve, meridian, normal, options.arch_segments, &out);
  MeasureMRevolution(curve, meridian, p2, p3, options.arch_segments, extent, &out);
  return out;
}

}  // namespace gproj::circular
