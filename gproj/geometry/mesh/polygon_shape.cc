#include "gproj/geometry/mesh/polygon_shape.h"

#include <Eigen/Eigenvalues>
#include <Eigen/Geometry>
#include <algorithm>
#include <cmath>

#include "gproj/geometry/mesh/quad_shape.h"
#include "gproj/geometry/mesh/scale_free.h"

namespace gproj {

namespace {

// The direction of the polygon's vector area Σ p_i × p_{i+1}: the normal its corners' signs are
// read against, as the corner bounds read them (panel_validity.h), so that a polygon the bounds
// keep convex measures convex while it is not yet planar.
Eigen::Vector3d VectorAreaNormal(const std::vector<Eigen::Vector3d>& p) {
  const int n = static_cast<int>(p.size());
  Eigen::Vector3d area = Eigen::Vector3d::Zero();
  for (int i = 0; i < n; ++i) area += p[i].cross(p[(i + 1) % n]);
  return area.norm() > 0.0 ? Eigen::Vector3d(area.normalized()) : Eigen::Vector3d::UnitZ();
}

}  // namespace

Eigen::Vector3d PolygonNormal(const std::vector<Eigen::Vector3d>& p) {
  const int n = static_cast<int>(p.size());
  if (n < 3) return Eigen::Vector3d::UnitZ();
  Eigen::Vector3d centroid = Eigen::Vector3d::Zero(), area = Eigen::Vector3d::Zero();
  for (int i = 0; i < n; ++i) {
    centroid += p[i];
    area += p[i].cross(p[(i + 1) % n]);
  }
  centroid /= n;
  Eigen::Matrix3d spread = Eigen::Matrix3d::Zero();
  for (const Eigen::Vector3d& q : p) spread += (q - centroid) * (q - centroid).transpose();
  const Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d> eigen(spread);
  Eigen::Vector3d normal = eigen.eigenvectors().col(0);  // the least spread
  if (!(eigen.eigenvalues()(1) > 1e-24 * eigen.eigenvalues()(2))) return Eigen::Vector3d::UnitZ();
  if (normal.dot(area) < 0.0) normal = -normal;
  return normal;
}

double PolygonPlanarity(const std::vector<Eigen::Vector3d>& p) {
  const int n = static_cast<int>(p.size());
  if (n < 4) return 0.0;
  if (n == 4) return DiagonalDistance(p[0], p[1], p[2], p[3]);
  Eigen::Vector3d centroid = Eigen::Vector3d::Zero();
  for (const Eigen::Vector3d& q : p) centroid += q;
  centroid /= n;
  const Eigen::Vector3d normal = PolygonNormal(p);
  double worst = 0.0;
  for (const Eigen::Vector3d& q : p) worst = std::max(worst, std::abs((q - centroid).dot(normal)));
  return 2.0 * worst;
}

std::vector<double> PolygonCornerAngles(const std::vector<Eigen::Vector3d>& p) {
  const int n = static_cast<int>(p.size());
  const Eigen::Vector3d normal = VectorAreaNormal(p);
  std::vector<double> angles(n);
  for (int i = 0; i < n; ++i) {
    const Eigen::Vector3d a = p[(i + 1) % n] - p[i], b = p[(i + n - 1) % n] - p[i];
    const Eigen::Vector3d cross = a.cross(b);
    const double angle = std::atan2(cross.norm(), a.dot(b)) * 180.0 / M_PI;
    angles[i] = cross.dot(normal) > 0.0 ? angle : 360.0 - angle;
  }
  return angles;
}

PolygonShape MeasurePolygonShape(const std::vector<Eigen::Vector3d>& p) {
  PolygonShape s;
  const int n = static_cast<int>(p.size());
  s.corners = n;
  if (n == 4) {
    const QuadShape q = MeasureQuadShape(p[0], p[1], p[2], p[3]);
    s.convex = q.convex;
    s.min_angle_deg = q.min_angle_deg;
    s.planarity = q.diagonal_distance;
    return s;
  }
  s.planarity = PolygonPlanarity(p);
  const Eigen::Vector3d normal = VectorAreaNormal(p);
  s.min_angle_deg = 360.0;
  for (int i = 0; i < n; ++i) {
    const Eigen::Vector3d a = p[(i + 1) % n] - p[i], b = p[(i + n - 1) % n] - p[i];
    const Eigen::Vector3d cross = a.cross(b);
    const double angle = std::atan2(cross.norm(), a.dot(b)) * 180.0 / M_PI;
    const bool salient = cross.dot(normal) > 0.0;
    s.convex = s.convex && salient;
    s.min_angle_deg = std::min(s.min_angle_deg, salient ? angle : 360.0 - angle);
  }
  return s;
}

double PolygonKinkDeg(const std::vector<Eigen::Vector3d>& p) {
  const int n = static_cast<int>(p.size());
  if (n < 4) return 0.0;
  auto corner_normal = [&](int i) {
    return Eigen::Vector3d((p[(i + 1) % n] - p[i]).cross(p[(i + n - 1) % n] - p[i]));
  };
  double worst = 0.0;
  for (int i = 0; i < n; ++i) {
    const Eigen::Vector3d a = corner_normal(i), b = corner_normal((i + 1) % n);
    if (!(a.norm() > 0.0 && b.norm() > 0.0)) continue;
    worst = std::max(worst, std::atan2(a.cross(b).norm(), a.dot(b)) * 180.0 / M_PI);
  }
  return worst;
}

std::vector<Eigen::Vector3d> FacePoints(const PolyMesh& mesh, PolyMesh::FaceHandle f) {
  std::vector<Eigen::Vector3d> p;
  for (auto v : mesh.fv_range(f)) {
    const auto& q = mesh.point(v);
    p.emplace_back(q[0], q[1], q[2]);
  }
  return p;
}

std::vector<PolygonShape> MeasurePolygonShapes(const PolyMesh& mesh) {
  std::vector<PolygonShape> shapes(mesh.n_faces());
  for (auto f : mesh.faces()) shapes[f.idx()] = MeasurePolygonShape(FacePoints(mesh, f));
  return shapes;
}

PolygonMeshSummary SummarizePolygons(const PolyMesh& mesh) {
  PolygonMeshSummary s;
  const double mean_edge = mesh.n_edges() > 0 ? MeanEdgeLength(mesh) : 1.0;
  double sum = 0.0;
  int polygons = 0;
  for (const PolygonShape& shape : MeasurePolygonShapes(mesh)) {
    if (shape.corners >= static_cast<int>(s.faces_by_corners.size()))
      s.faces_by_corners.resize(shape.corners + 1, 0);
    ++s.faces_by_corners[shape.corners];
    if (shape.corners < 4) continue;
    ++polygons;
    const double planarity = shape.planarity / mean_edge;
    s.max_planarity = std::max(s.max_planarity, planarity);
    sum += planarity;
    s.non_convex += shape.convex ? 0 : 1;
    s.min_angle_deg = std::min(s.min_angle_deg, shape.min_angle_deg);
  }
  s.mean_planarity = polygons > 0 ? sum / polygons : 0.0;
  return s;
}

std::string FaceCountsText(const std::vector<int>& faces_by_corners) {
  static const char* const kNames[] = {"",         "",        "",         "triangle", "quad",
                                       "pentagon", "hexagon", "heptagon", "octagon"};
  std::string text;
  for (int n = static_cast<int>(faces_by_corners.size()) - 1; n >= 0; --n) {
    const int count = faces_by_corners[n];
    if (count == 0) continue;
    if (!text.empty()) text += ", ";
    text += std::to_string(count) + " ";
    text += n <= 8 ? std::string(kNames[n]) + (count == 1 ? "" : "s")
                   : std::to_string(n) + "-gon" + (count == 1 ? "" : "s");
  }
  return text.empty() ? "no faces" : text;
}

}  // namespace gproj
