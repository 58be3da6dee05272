#pragma once
// M-revolution surfaces in one step (000 §5.1, Figs. 19–20, meshed as in §5.3): the inversion of
// a surface of revolution whose axis and inversion centre lie in one plane, from what a designer
// draws in that plane: a curve from P1 to P4 (it stays a boundary curvature line) and two more
// points P2, P3 on the circle through P1 and P4.
//   1. the inversion centre C maps P1 P2 P3 P4 to an isosceles trapezoid with
//      P1'P2' = t P4'P3' (000 eq. 7–9, geometry/mobius);
//   2. the curve's image is a meridian of a surface of revolution whose axis is the trapezoid's
//      axis of symmetry; turning it by π about that axis meshes the surface of revolution
//      (meridians × parallels: every quad an isosceles trapezoid, so circular);
//   3. the inversion again (an involution: f⁻¹ = f) maps that mesh back: a circular mesh through
//      the curve's own points, whose last meridian passes through P2 and P3 and whose parallels
//      are arches in planes perpendicular to the drawing plane (000 §5.1: "planar vertical
//      arches").
// The curve's discretisation is the mesh's (§5.3: the mesh is made on the surface of revolution
// from the images of the guide curve's points and mapped back by f⁻¹).

#include <Eigen/Core>
#include <string>
#include <vector>

#include "gproj/geometry/io/mesh_io.h"
#include "gproj/geometry/mesh/mobius.h"

namespace gproj::circular {

struct MRevolutionOptions {
  double t = 1.0;          // ratio of the trapezoid's parallel sides P1'P2' = t P4'P3' (> 0)
  int root = 0;            // which of the (up to) two centres
  int arch_segments = 16;  // quads along each arch (the parallels' half circles)
  // The arches rise to the side of the drawing plane this points to; it must not lie in the
  // plane. Zero (the default): +z, or the side of (P2 − P1) × (P4 − P1) when +z lies in it.
  Eigen::Vector3d up = Eigen::Vector3d::Zero();
  bool IsValid(std::string* why) const;
};

struct MRevolutionSurface {
  // Vertex (i, j) at index i (arch_segments + 1) + j: i along the curve, j along the arch from
  // the curve (j = 0) to the meridian through P2 and P3 (j = arch_segments).
  PolyMesh mesh;
  PolyMesh revolution;  // the surface of revolution it is the image of
  MRevolutionChoice choice;
  double ratio = 1.0;  // of the inversion (|C P1|², so P1 is fixed)
  Eigen::Vector3d axis_point = Eigen::Vector3d::Zero(), axis_direction = Eigen::Vector3d::Zero();
  // Checks, in units of the curve's extent: |f⁻¹(f(P_i)) − P_i| over the curve's points (the
  // j = 0 meridian against the input), the far meridian's ends against P2 and P3, and the
  // largest distance of an arch's points from its plane.
  double curve_roundtrip = 0.0, far_meridian_miss = 0.0, arch_planarity = 0.0;
};

// Throws InputError (naming the point or the rule) for fewer than 2 curve points, points that
// are not finite, P1..P4 not distinct, an `up` in the drawing plane, more than 5e7 vertices,
// an inversion centre within 1e-6 curve extents of the curve (its image would run off), a curve or
// P2, P3 out of the plane of P1, P2, P4 (relative 1e-8), P1 P2 P3 P4 not concyclic, a curve point
// on the axis of revolution (its parallel would be a point), a curve through the inversion centre,
// or invalid options.
MRevolutionSurface BuildMRevolutionSurface(const std::vector<Eigen::Vector3d>& curve,
                                           const Eigen::Vector3d& p2, const Eigen::Vector3d& p3,
                                           const MRevolutionOptions& options);

}  // namespace gproj::circular
