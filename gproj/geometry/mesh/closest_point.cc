#include "gproj/geometry/mesh/closest_point.h"

#include <CGAL/AABB_segment_primitive.h>
#include <CGAL/AABB_traits.h>
#include <CGAL/AABB_tree.h>
#include <CGAL/AABB_triangle_primitive.h>
#include <CGAL/Simple_cartesian.h>

#include <Eigen/Geometry>
#include <array>
#include <vector>

namespace gproj {

using Kernel = CGAL::Simple_cartesian<double>;
using Triangle = Kernel::Triangle_3;
using TriangleIterator = std::vector<Triangle>::const_iterator;
using Primitive = CGAL::AABB_triangle_primitive<Kernel, TriangleIterator>;
using Tree = CGAL::AABB_tree<CGAL::AABB_traits<Kernel, Primitive>>;

struct ClosestPointQuery::Impl {
  std::vector<Triangle> triangles;
  std::vector<std::array<Eigen::Vector3d, 3>> corner_normals;  // per triangle
  std::vector<Eigen::Vector3d> face_normals;                   // per triangle
  Tree tree;
};

namespace {
Eigen::Vector3d ToEigen(const Kernel::Point_3& p) { return {p.x(), p.y(), p.z()}; }
}  // namespace

ClosestPointQuery::ClosestPointQuery(const PolyMesh& mesh) : impl_(std::make_unique<Impl>()) {
  std::vector<Eigen::Vector3d> vertex_normals(mesh.n_vertices(), Eigen::Vector3d::Zero());
  std::vector<std::array<int, 3>> corners;
  for (auto f : mesh.faces()) {
    std::vector<int> v;
    for (auto fv : mesh.fv_range(f)) v.push_back(fv.idx());
    for (size_t k = 1; k + 1 < v.size(); ++k) corners.push_back({v[0], v[k], v[k + 1]});
  }
  if (corners.empty()) throw InputError("the reference surface has no faces");
  auto point = [&mesh](int i) {
    const auto& p = mesh.point(PolyMesh::VertexHandle(i));
    return Eigen::Vector3d(p[0], p[1], p[2]);
  };
  for (const auto& c : corners) {
    const Eigen::Vector3d area = (point(c[1]) - point(c[0])).cross(point(c[2]) - point(c[0]));
    for (int i : c) vertex_normals[i] += area;
    impl_->face_normals.push_back(area.normalized());
    impl_->triangles.emplace_back(Kernel::Point_3(point(c[0])[0], point(c[0])[1], point(c[0])[2]),
                                  Kernel::Point_3(point(c[1])[0], point(c[1])[1], point(c[1])[2]),
                                  Kernel::Point_3(point(c[2])[0], point(c[2])[1], point(c[2])[2]));
  }
  for (auto& n : vertex_normals) n.normalize();
  for (const auto& c : corners)
    impl_->corner_normals.push_back(
        {vertex_normals[c[0]], vertex_normals[c[1]], vertex_normals[c[2]]});
  impl_->tree.insert(impl_->triangles.cbegin(), impl_->triangles.cend());
  impl_->tree.build();
  impl_->tree.accelerate_distance_queries();
}

ClosestPointQuery::~ClosestPointQuery() = default;

void ClosestPointQuery::Project(const Eigen::Vector3d& q, Eigen::Vector3d* p,
                                Eigen::Vector3d* n) const {
  const auto hit = impl_->tree.closest_point_and_primitive(Kernel::Point_3(q[0], q[1], q[2]));
  *p = ToEigen(hit.first);
  const size_t t = static_cast<size_t>(hit.second - impl_->triangles.cbegin());
  const Triangle& tri = impl_->triangles[t];
  const Eigen::Vector3d a = ToEigen(tri[0]), b = ToEigen(tri[1]), c = ToEigen(tri[2]);
  // Barycentric coordinates of p in the triangle.
  const Eigen::Vector3d normal = (b - a).cross(c - a);
  const double area2 = normal.squaredNorm();
  Eigen::Vector3d blended = impl_->face_normals[t];
  if (area2 > 0.0) {
    const double lb = (c - a).cross(*p - a).dot(-normal) / area2;
    const double lc = (b - a).cross(*p - a).dot(normal) / area2;
    const double la = 1.0 - lb - lc;
    const auto& cn = impl_->corner_normals[t];
    blended = la * cn[0] + lb * cn[1] + lc * cn[2];
    if (blended.norm() > 0.0) blended.normalize();
  }
  *n = blended;
}

using Segment = Kernel::Segment_3;
using SegmentIterator = std::vector<Segment>::const_iterator;
using SegmentTree = CGAL::AABB_tree<
    CGAL::AABB_traits<Kernel, CGAL::AABB_segment_primitive<Kernel, SegmentIterator>>>;

struct PolylineClosestPoint::Impl {
  std::vector<Segment> segments;
  SegmentTree tree;
  Kernel::Point_3 single;  // a polyline of coincident points
  bool degenerate = true;
};

PolylineClosestPoint::PolylineClosestPoint(const std::vector<Eigen::Vector3d>& points)
    : impl_(std::make_unique<Impl>()) {
  if (points.size() < 2) throw InputError("a polyline needs at least 2 points");
  impl_->single = Kernel::Point_3(points[0].x(), points[0].y(), points[0].z());
  for (size_t i = 0; i + 1 < points.size(); ++i) {
    if (points[i] == points[i + 1]) continue;  // CGAL refuses zero-length segments
    impl_->segments.emplace_back(
        Kernel::Point_3(points[i].x(), points[i].y(), points[i].z()),
        Kernel::Point_3(points[i + 1].x(), points[i + 1].y(), points[i + 1].z()));
  }
  impl_->degenerate = impl_->segments.empty();
  if (!impl_->degenerate) {
    impl_->tree.insert(impl_->segments.begin(), impl_->segments.end());
    impl_->tree.accelerate_distance_queries();
  }
}

PolylineClosestPoint::~PolylineClosestPoint() = default;

Eigen::Vector3d PolylineClosestPoint::Closest(const Eigen::Vector3d& q) const {
  if (impl_->degenerate) return ToEigen(impl_->single);
  return ToEigen(impl_->tree.closest_point(Kernel::Point_3(q.x(), q.y(), q.z())));
}

}  // namespace gproj
