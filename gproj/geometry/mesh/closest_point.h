#pragma once
// Closest points on a reference surface given as a polygon mesh (triangulated by fans), through
// CGAL's AABB tree. Normals are the area-weighted vertex normals interpolated barycentrically,
// so tangent planes vary smoothly across the reference.

#include <Eigen/Core>
#include <memory>
#include <vector>

#include "gproj/geometry/io/mesh_io.h"

namespace gproj {

class ClosestPointQuery {
 public:
  // Throws InputError if the mesh has no faces.
  explicit ClosestPointQuery(const PolyMesh& mesh);
  ~ClosestPointQuery();
  ClosestPointQuery(const ClosestPointQuery&) = delete;
  ClosestPointQuery& operator=(const ClosestPointQuery&) = delete;

  // Closest point p of the surface to q and the unit normal n there.
  void Project(const Eigen::Vector3d& q, Eigen::Vector3d* p, Eigen::Vector3d* n) const;

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

// Closest points on a polyline (its segments in CGAL's AABB tree: a query costs O(log n)).
class PolylineClosestPoint {
 public:
  // Throws InputError for fewer than 2 points.
  explicit PolylineClosestPoint(const std::vector<Eigen::Vector3d>& points);
  ~PolylineClosestPoint();
  PolylineClosestPoint(const PolylineClosestPoint&) = delete;
  PolylineClosestPoint& operator=(const PolylineClosestPoint&) = delete;

  Eigen::Vector3d Closest(const Eigen::Vector3d& q) const;

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

}  // namespace gproj
