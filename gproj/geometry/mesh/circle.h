#pragma once
// Circles in space and the circularity measure of quad meshes (000 §2: circular meshes).
// The templated helpers also run on Ceres Jets, so constructions built from them can be
// differentiated automatically.

#include <Eigen/Geometry>
#include <array>
#include <cmath>

#include "gproj/geometry/io/mesh_io.h"

namespace gproj {

template <typename T>
using Vec3 = Eigen::Matrix<T, 3, 1>;

template <typename T>
struct CircleT {
  Vec3<T> centre;
  Vec3<T> normal;  // unit normal of the circle's plane
  T radius;
};
using Circle = CircleT<double>;

// The circle through three points; its normal is (b − a) × (c − a), normalised. The points must
// not be collinear (the result is then non-finite).
template <typename T>
CircleT<T> CircleThrough(const Vec3<T>& a, const Vec3<T>& b, const Vec3<T>& c) {
  const Vec3<T> ab = b - a, ac = c - a;
  const Vec3<T> n = ab.cross(ac);
  const T n2 = n.squaredNorm();
  const Vec3<T> offset =
      (ac.squaredNorm() * n.cross(ab) + ab.squaredNorm() * ac.cross(n)) / (T(2) * n2);
  CircleT<T> circle;
  circle.centre = a + offset;
  circle.normal = n / sqrt(n2);
  circle.radius = offset.norm();
  return circle;
}

// Distance from p to the circle (as a curve in space).
double DistanceToCircle(const Eigen::Vector3d& p, const Circle& circle);

// Least-squares circle through the points: plane by principal axes, then the algebraic
// (Kåsa) circle fit in that plane. Needs at least three points not all collinear.
Circle FitCircle(const Eigen::Vector3d* points, int count);

// Concyclicity of one quad: the largest distance of its four vertices to their fitted circle.
double QuadConcyclicity(const std::array<Eigen::Vector3d, 4>& quad);

// Whether the quad a, b, c, d (nearly planar) is convex: every turn a → b → c, … has the sense of
// the diagonals' cross product (c − a) × (d − b). A crossed ("bow-tie") or degenerate quad is not.
bool IsConvexQuad(const std::array<Eigen::Vector3d, 4>& quad);

struct CircularityMeasures {
  double max_concyclicity = 0.0;   // max over faces of QuadConcyclicity / mean edge length
  double mean_concyclicity = 0.0;  // mean of the same
  int worst_face = -1;
  int folded_quads = 0;  // quads that are not convex (IsConvexQuad)
};
// Over the quads of `mesh` (other faces are skipped).
CircularityMeasures MeasureCircularity(const PolyMesh& mesh);

}  // namespace gproj
