#pragma once
// Möbius transformations of meshes (000 §2.3) and the M-revolution inverse problem (000 §5.1).
// Inversion with centre C and ratio k (000 eq. 1):  CM' = k / ‖CM‖² · CM.
// It is an involution, preserves circles and spheres, and so maps circular meshes to circular
// meshes.

#include <Eigen/Core>
#include <array>
#include <complex>
#include <vector>

#include "gproj/geometry/io/mesh_io.h"

namespace gproj {

Eigen::Vector3d Invert(const Eigen::Vector3d& p, const Eigen::Vector3d& centre, double ratio);

// Inverts every vertex. Throws InputError naming the vertex that coincides with the centre
// (its image would be at infinity) or when the ratio is zero or not finite.
PolyMesh InvertMesh(const PolyMesh& mesh, const Eigen::Vector3d& centre, double ratio);

// The M-revolution inverse problem (000 §5.1): z1..z4 are four concyclic points of the plane
// (as complex numbers). For a real t, the centres z_C whose inversion maps the quad z1 z2 z3 z4
// to one whose sides z1'z2' and z4'z3' are parallel with (z2' − z1') = t (z3' − z4') (000 eq.
// 7–8), i.e. an isosceles trapezoid, are the roots of
//   A z_C² + B z_C + D = 0,
//   A = z2 − z1 + t (z4 − z3),  B = t (z3 − z4)(z1 + z2) − (z2 − z1)(z3 + z4),
//   D = z3 z4 (z2 − z1) + t z1 z2 (z4 − z3).
// (000 eq. 9 prints B with the opposite sign; expanding eq. 8 gives the B above, and only this
// sign makes the images trapezoids, as the tests check.) Returns both roots; when A = 0 (the
// quad is already such a trapezoid for this t) the single root of the linear equation is
// returned twice, and when A = B = 0 both entries are NaN.
std::array<std::complex<double>, 2> MRevolutionCentres(std::complex<double> z1,
                                                       std::complex<double> z2,
                                                       std::complex<double> z3,
                                                       std::complex<double> z4, double t);

// A root may lie on the quad's own circle: the images are then collinear (the circle maps to a
// line), parallel only trivially. This happens for t < 0 (the parallel sides would cross).
//
// The same for four coplanar points in space: their plane gets an orthonormal frame, the problem
// is solved in it, and the centres off the quad's circle are returned in space (one or two).
// Throws InputError when the points are not coplanar and concyclic to `tolerance` (relative to
// the quad's size), are degenerate, or when no root lies off the circle.
std::vector<Eigen::Vector3d> MRevolutionCentres(const std::array<Eigen::Vector3d, 4>& quad,
                                                double t, double tolerance = 1e-8);

// The image of a quad P1 P2 P3 P4 under an inversion, as the M-revolution check needs it: the
// angle between the image's sides P1'P2' and P4'P3' (0: parallel) and its diagonals |P1'P3'|,
// |P2'P4'| (equal for an isosceles trapezoid).
struct QuadImage {
  std::array<Eigen::Vector3d, 4> points;
  double side_angle = 0.0;  // radians, in [0, π/2]
  std::array<double, 2> diagonals{};
};
QuadImage InvertQuad(const std::array<Eigen::Vector3d, 4>& quad, const Eigen::Vector3d& centre,
                     double ratio);

// The inversion centre of an M-revolution (000 §5.1): root `root` (0 or 1) of
// MRevolutionCentres(quad, t), with all the roots and the quad's image under that inversion.
// Throws InputError when `root` is not one of the roots found (naming how many there are).
struct MRevolutionChoice {
  Eigen::Vector3d centre;
  std::vector<Eigen::Vector3d> centres;
  QuadImage image;
};
MRevolutionChoice ChooseMRevolutionCentre(const std::array<Eigen::Vector3d, 4>& quad, double t,
                                          int root, double ratio);

}  // namespace gproj
