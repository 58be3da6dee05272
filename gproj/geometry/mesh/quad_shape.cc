#include "gproj/geometry/mesh/quad_shape.h"

#include <Eigen/Geometry>
#include <algorithm>
#include <cstdio>

#include "gproj/geometry/mesh/circle.h"
#include "gproj/geometry/mesh/polygon_shape.h"
#include "gproj/geometry/mesh/scale_free.h"

namespace gproj {
namespace {

double AngleDeg(const Eigen::Vector3d& a, const Eigen::Vector3d& b) {
  return std::atan2(a.cross(b).norm(), a.dot(b)) * 180.0 / M_PI;
}

Eigen::Vector3d Point(const PolyMesh& mesh, PolyMesh::VertexHandle v) {
  const auto& q = mesh.point(v);
  return {q[0], q[1], q[2]};
}

// The four corners of face f, or false when it is not a quad.
bool QuadPoints(const PolyMesh& mesh, PolyMesh::FaceHandle f, Eigen::Vector3d* p) {
  if (mesh.valence(f) != 4) return false;
  int k = 0;
  for (auto v : mesh.fv_range(f)) p[k++] = Point(mesh, v);
  return true;
}

// The mean edge length (1 for a mesh without edges): the unit of the relative measures.
double MeanEdge(const PolyMesh& mesh) { return mesh.n_edges() > 0 ? MeanEdgeLength(mesh) : 1.0; }

}  // namespace

namespace {

// Corner angles of a quad already at unit size (NormalizePolygon), from its corner sines.
std::array<double, 4> CornerAngles(const Eigen::Vector3d* v, const double* sines) {
  std::array<double, 4> angles{};
  for (int i = 0; i < 4; ++i) {
    const double angle = AngleDeg(v[(i + 1) % 4] - v[i], v[(i + 3) % 4] - v[i]);
    angles[i] = sines[i] > 0.0 ? angle : 360.0 - angle;
  }
  return angles;
}

// Distance between the diagonal lines of a quad at unit size.
double UnitDiagonalDistance(const Eigen::Vector3d* v) {
  const Eigen::Vector3d d0 = v[2] - v[0], d1 = v[3] - v[1];
  const Eigen::Vector3d n = d0.cross(d1);
  const double length = n.norm();
  if (length <= 1e-300)  // parallel diagonals: distance of v1 from the line through v0, v2
    return (v[1] - v[0]).cross(d0).norm() / std::max(d0.norm(), 1e-300);
  return std::abs((v[1] - v[0]).dot(n)) / length;
}

}  // namespace

std::array<double, 4> QuadCornerAngles(const Eigen::Vector3d& v0, const Eigen::Vector3d& v1,
                                       const Eigen::Vector3d& v2, const Eigen::Vector3d& v3) {
  Eigen::Vector3d v[4] = {v0, v1, v2, v3};
  NormalizePolygon(v, 4);
  double sines[4];
  QuadCornerSines(v[0].data(), v[1].data(), v[2].data(), v[3].data(), sines);
  return CornerAngles(v, sines);
}

double DiagonalDistance(const Eigen::Vector3d& v0, const Eigen::Vector3d& v1,
                        const Eigen::Vector3d& v2, const Eigen::Vector3d& v3) {
  Eigen::Vector3d v[4] = {v0, v1, v2, v3};
  const double extent = NormalizePolygon(v, 4);
  return extent * UnitDiagonalDistance(v);
}

QuadShape MeasureQuadShape(const Eigen::Vector3d& p0, const Eigen::Vector3d& p1,
                           const Eigen::Vector3d& p2, const Eigen::Vector3d& p3) {
  QuadShape s;
  Eigen::Vector3d v[4] = {p0, p1, p2, p3};
  const double extent = NormalizePolygon(v, 4);  // scale-free: measured at unit size
  double sines[4];
  QuadCornerSines(v[0].data(), v[1].data(), v[2].data(), v[3].data(), sines);
  const std::array<double, 4> angles = CornerAngles(v, sines);
  s.min_angle_deg = *std::min_element(angles.begin(), angles.end());
  for (double sine : sines) s.convex = s.convex && sine > 0.0;
  // Split along v0–v2: triangles (v0, v1, v2) and (v0, v2, v3); along v1–v3 likewise.
  const double kink02 =
      AngleDeg((v[1] - v[0]).cross(v[2] - v[0]), (v[2] - v[0]).cross(v[3] - v[0]));
  const double kink13 =
      AngleDeg((v[2] - v[1]).cross(v[3] - v[1]), (v[3] - v[1]).cross(v[0] - v[1]));
  s.kink_deg = std::max(kink02, kink13);
  s.diagonal_distance = extent * UnitDiagonalDistance(v);
  return s;
}

std::vector<QuadShape> MeasureQuadShapes(const PolyMesh& mesh) {
  std::vector<QuadShape> shapes(mesh.n_faces());
  Eigen::Vector3d p[4];
  for (auto f : mesh.faces())
    if (QuadPoints(mesh, f, p)) shapes[f.idx()] = MeasureQuadShape(p[0], p[1], p[2], p[3]);
  return shapes;
}

QuadShapeSummary Summarize(const std::vector<QuadShape>& shapes) {
  QuadShapeSummary s;
  for (const QuadShape& q : shapes) {
    s.non_convex += q.convex ? 0 : 1;
    s.min_angle_deg = std::min(s.min_angle_deg, q.min_angle_deg);
    s.max_kink_deg = std::max(s.max_kink_deg, q.kink_deg);
    s.max_diagonal_distance = std::max(s.max_diagonal_distance, q.diagonal_distance);
  }
  return s;
}

std::vector<double> RelativeFacePlanarity(const PolyMesh& mesh, bool circular) {
  const double mean_edge = MeanEdge(mesh);
  std::vector<double> values(mesh.n_faces(), 0.0);
  Eigen::Vector3d p[4];
  for (auto f : mesh.faces()) {
    if (mesh.valence(f) > 4) {
      values[f.idx()] = PolygonPlanarity(FacePoints(mesh, f)) / mean_edge;
      continue;
    }
    if (!QuadPoints(mesh, f, p)) continue;
    double v = MeasureQuadShape(p[0], p[1], p[2], p[3]).diagonal_distance / mean_edge;
    if (circular) v = std::max(v, QuadConcyclicity({p[0], p[1], p[2], p[3]}) / mean_edge);
    values[f.idx()] = v;
  }
  return values;
}

FaceValues MeasureFaceValues(const PolyMesh& mesh, bool circular) {
  const double mean_edge = MeanEdge(mesh);
  FaceValues values;
  Eigen::Vector3d p[4];
  for (auto f : mesh.faces()) {
    if (mesh.valence(f) > 4) {
      const std::vector<Eigen::Vector3d> q = FacePoints(mesh, f);
      const PolygonShape s = MeasurePolygonShape(q);
      values.face.push_back(f.idx());
      values.planarity.push_back(s.planarity / mean_edge);
      values.planarity_abs.push_back(s.planarity);
      values.kink_deg.push_back(PolygonKinkDeg(q));
      values.min_angle_deg.push_back(s.min_angle_deg);
      values.convex.push_back(s.convex);
      continue;
    }
    if (!QuadPoints(mesh, f, p)) continue;
    const QuadShape s = MeasureQuadShape(p[0], p[1], p[2], p[3]);
    values.face.push_back(f.idx());
    values.planarity.push_back(s.diagonal_distance / mean_edge);
    values.planarity_abs.push_back(s.diagonal_distance);
    values.kink_deg.push_back(s.kink_deg);
    values.min_angle_deg.push_back(s.min_angle_deg);
    values.convex.push_back(s.convex);
    if (circular)
      values.concyclicity.push_back(QuadConcyclicity({p[0], p[1], p[2], p[3]}) / mean_edge);
  }
  return values;
}

std::string QuadShapesCsv(const PolyMesh& mesh, bool circular) {
  const FaceValues values = MeasureFaceValues(mesh, circular);
  std::string csv = "face,planarity,planarity_abs,kink_deg,min_angle_deg";
  csv += circular ? ",concyclicity\n" : "\n";
  char line[192];
  for (std::size_t i = 0; i < values.face.size(); ++i) {
    std::snprintf(line, sizeof(line), "%d,%.6e,%.6e,%.6e,%.6f", values.face[i], values.planarity[i],
                  values.planarity_abs[i], values.kink_deg[i], values.min_angle_deg[i]);
    csv += line;
    if (circular) {
      std::snprintf(line, sizeof(line), ",%.6e", values.concyclicity[i]);
      csv += line;
    }
    csv += "\n";
  }
  return csv;
}

ShapeChange CompareCornerAngles(const PolyMesh& before, const PolyMesh& after,
                                double threshold_deg) {
  ShapeChange change;
  change.threshold_deg = threshold_deg;
  int quads = 0;
  Eigen::Vector3d p[4], q[4];
  for (auto f : before.faces()) {
    if (before.valence(f) > 4 && after.valence(f) == before.valence(f)) {
      const std::vector<double> a = PolygonCornerAngles(FacePoints(before, f));
      const std::vector<double> b = PolygonCornerAngles(FacePoints(after, f));
      double worst = 0.0;
      for (size_t i = 0; i < a.size(); ++i) worst = std::max(worst, std::abs(a[i] - b[i]));
      change.max_corner_change_deg = std::max(change.max_corner_change_deg, worst);
      change.quads_changed += worst > threshold_deg ? 1 : 0;
      ++change.polygons;
      ++quads;
      continue;
    }
    if (!QuadPoints(before, f, p) || !QuadPoints(after, f, q)) continue;
    ++quads;
    const std::array<double, 4> a = QuadCornerAngles(p[0], p[1], p[2], p[3]);
    const std::array<double, 4> b = QuadCornerAngles(q[0], q[1], q[2], q[3]);
    double worst = 0.0;
    for (int i = 0; i < 4; ++i) worst = std::max(worst, std::abs(a[i] - b[i]));
    change.max_corner_change_deg = std::max(change.max_corner_change_deg, worst);
    change.quads_changed += worst > threshold_deg ? 1 : 0;
  }
  change.share_changed = quads > 0 ? static_cast<double>(change.quads_changed) / quads : 0.0;
  return change;
}

}  // namespace gproj
