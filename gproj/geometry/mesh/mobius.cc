#include "gproj/geometry/mesh/mobius.h"

#include <Eigen/Geometry>
#include <cmath>
#include <cstdio>
#include <limits>
#include <string>

#include "gproj/geometry/mesh/circle.h"

namespace gproj {
namespace {

// t for messages: "%g", never 300 digits or 0.000000.
std::string TText(double t) {
  char text[32];
  std::snprintf(text, sizeof(text), "%g", t);
  return text;
}

}  // namespace

Eigen::Vector3d Invert(const Eigen::Vector3d& p, const Eigen::Vector3d& centre, double ratio) {
  const Eigen::Vector3d d = p - centre;
  return centre + ratio / d.squaredNorm() * d;
}

PolyMesh InvertMesh(const PolyMesh& mesh, const Eigen::Vector3d& centre, double ratio) {
  if (!std::isfinite(ratio) || ratio == 0.0)
    throw InputError("inversion ratio must be finite and non-zero (got " + std::to_string(ratio) +
                     ")");
  if (!centre.allFinite()) throw InputError("inversion centre must be finite");
  double size = 0.0;
  for (auto v : mesh.vertices()) {
    const auto& p = mesh.point(v);
    size = std::max(size, (Eigen::Vector3d(p[0], p[1], p[2]) - centre).norm());
  }
  PolyMesh out = mesh;
  for (auto v : out.vertices()) {
    const auto& p = out.point(v);
    const Eigen::Vector3d q(p[0], p[1], p[2]);
    if ((q - centre).norm() <= 1e-12 * std::max(size, 1.0))
      throw InputError("vertex " + std::to_string(v.idx()) +
                       " lies at the inversion centre; its image would be at infinity");
    const Eigen::Vector3d r = Invert(q, centre, ratio);
    out.set_point(v, PolyMesh::Point(r.x(), r.y(), r.z()));
  }
  return out;
}

std::array<std::complex<double>, 2> MRevolutionCentres(std::complex<double> z1,
                                                       std::complex<double> z2,
                                                       std::complex<double> z3,
                                                       std::complex<double> z4, double t) {
  const std::complex<double> a = z2 - z1 + t * (z4 - z3);
  const std::complex<double> b = t * (z3 - z4) * (z1 + z2) - (z2 - z1) * (z3 + z4);
  const std::complex<double> d = z3 * z4 * (z2 - z1) + t * z1 * z2 * (z4 - z3);
  const double scale = std::abs(z2 - z1) + std::abs(z4 - z3);
  if (std::abs(a) <= 1e-14 * scale) {
    const double nan = std::numeric_limits<double>::quiet_NaN();
    if (std::abs(b) <= 1e-14 * scale * (std::abs(z1) + std::abs(z3) + 1.0))
      return {std::complex<double>(nan, nan), std::complex<double>(nan, nan)};
    return {-d / b, -d / b};
  }
  const std::complex<double> root = std::sqrt(b * b - 4.0 * a * d);
  // The root that avoids cancellation, then Vieta for the other.
  const std::complex<double> q = -0.5 * (b + (std::real(std::conj(b) * root) >= 0 ? root : -root));
  const std::complex<double> r1 = q / a;
  const std::complex<double> r2 = std::abs(q) > 0 ? d / q : r1;
  return {r1, r2};
}

std::vector<Eigen::Vector3d> MRevolutionCentres(const std::array<Eigen::Vector3d, 4>& quad,
                                                double t, double tolerance) {
  double size = 0.0;
  for (int i = 0; i < 4; ++i) size = std::max(size, (quad[i] - quad[(i + 1) % 4]).norm());
  if (!(size > 0.0)) throw InputError("the four points of the M-revolution quad coincide");
  const Eigen::Vector3d e1 = (quad[1] - quad[0]).normalized();
  Eigen::Vector3d n = (quad[1] - quad[0]).cross(quad[3] - quad[0]);
  if (!(n.norm() > 1e-12 * size * size))
    throw InputError("the M-revolution quad is degenerate (P1, P2, P4 collinear)");
  n.normalize();
  const double off_plane = std::abs(n.dot(quad[2] - quad[0]));
  if (off_plane > tolerance * size)
    throw InputError("the M-revolution points are not coplanar (P3 is " +
                     std::to_string(off_plane / size) + " quad sizes off the plane of P1 P2 P4)");
  const double off_circle = QuadConcyclicity(quad);
  if (off_circle > tolerance * size)
    throw InputError("the M-revolution points are not concyclic (distance " +
                     std::to_string(off_circle / size) + " quad sizes from their circle)");
  const Eigen::Vector3d e2 = n.cross(e1);
  std::complex<double> z[4];
  for (int i = 0; i < 4; ++i) {
    const Eigen::Vector3d d = quad[i] - quad[0];
    z[i] = {d.dot(e1), d.dot(e2)};
  }
  if (!std::isfinite(t)) throw InputError("t must be finite");
  const auto roots = MRevolutionCentres(z[0], z[1], z[2], z[3], t);
  const Circle circle = FitCircle(quad.data(), 4);
  std::vector<Eigen::Vector3d> centres;
  for (int k = 0; k < 2; ++k) {
    if (!std::isfinite(roots[k].real()) || !std::isfinite(roots[k].imag())) continue;
    const Eigen::Vector3d c = quad[0] + roots[k].real() * e1 + roots[k].imag() * e2;
    if (DistanceToCircle(c, circle) <= 1e-9 * size) continue;
    if (k == 1 && !centres.empty() && (centres[0] - c).norm() <= 1e-12 * size) continue;
    centres.push_back(c);
  }
  if (centres.empty())
    throw InputError("for t = " + TText(t) +
                     " every inversion centre lies on the quad's circle (the images would be "
                     "collinear); choose another t > 0");
  return centres;
}

QuadImage InvertQuad(const std::array<Eigen::Vector3d, 4>& quad, const Eigen::Vector3d& centre,
                     double ratio) {
  QuadImage image;
  for (int j = 0; j < 4; ++j) image.points[j] = Invert(quad[j], centre, ratio);
  const auto& p = image.points;
  const Eigen::Vector3d a = p[1] - p[0], b = p[2] - p[3];
  image.side_angle = std::atan2(a.cross(b).norm(), std::abs(a.dot(b)));
  image.diagonals = {(p[2] - p[0]).norm(), (p[3] - p[1]).norm()};
  return image;
}

MRevolutionChoice ChooseMRevolutionCentre(const std::array<Eigen::Vector3d, 4>& quad, double t,
                                          int root, double ratio) {
  MRevolutionChoice choice;
  choice.centres = MRevolutionCentres(quad, t);
  if (root < 0 || root >= static_cast<int>(choice.centres.size()))
    throw InputError("root " + std::to_string(root) + " asked, but t = " + TText(t) + " gives " +
                     std::to_string(choice.centres.size()) +
                     " centre(s) off the circle (roots 0.." +
                     std::to_string(choice.centres.size() - 1) + ")");
  choice.centre = choice.centres[root];
  choice.image = InvertQuad(quad, choice.centre, ratio);
  return choice;
}

}  // namespace gproj
