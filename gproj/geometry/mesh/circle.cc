#include "gproj/geometry/mesh/circle.h"

#include <Eigen/Dense>
#include <algorithm>

#include "gproj/geometry/mesh/scale_free.h"

namespace gproj {

double DistanceToCircle(const Eigen::Vector3d& p, const Circle& circle) {
  const Eigen::Vector3d d = p - circle.centre;
  const double height = d.dot(circle.normal);
  const double in_plane = (d - height * circle.normal).norm();
  return std::hypot(in_plane - circle.radius, height);
}

Circle FitCircle(const Eigen::Vector3d* points, int count) {
  Eigen::Vector3d mean = Eigen::Vector3d::Zero();
  for (int i = 0; i < count; ++i) mean += points[i];
  mean /= count;
  Eigen::Matrix3d cov = Eigen::Matrix3d::Zero();
  for (int i = 0; i < count; ++i) cov += (points[i] - mean) * (points[i] - mean).transpose();
  const Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d> eig(cov);
  const Eigen::Vector3d normal = eig.eigenvectors().col(0);
  const Eigen::Vector3d e1 = eig.eigenvectors().col(2), e2 = normal.cross(e1);
  // Kåsa: x² + y² + D x + E y + F = 0 in the plane frame, least squares.
  Eigen::MatrixXd a(count, 3);
  Eigen::VectorXd b(count);
  for (int i = 0; i < count; ++i) {
    const double x = (points[i] - mean).dot(e1), y = (points[i] - mean).dot(e2);
    a.row(i) << x, y, 1.0;
    b[i] = -(x * x + y * y);
  }
  const Eigen::Vector3d s = a.colPivHouseholderQr().solve(b);
  const double cx = -s[0] / 2, cy = -s[1] / 2;
  Circle circle;
  circle.centre = mean + cx * e1 + cy * e2;
  circle.normal = normal;
  circle.radius = std::sqrt(std::max(0.0, cx * cx + cy * cy - s[2]));
  return circle;
}

double QuadConcyclicity(const std::array<Eigen::Vector3d, 4>& quad) {
  std::array<Eigen::Vector3d, 4> scaled = quad;
  const double extent = NormalizePolygon(scaled.data(), 4);
  if (extent == 0.0) return 0.0;
  const Circle circle = FitCircle(scaled.data(), 4);
  double worst = 0.0;
  for (const auto& p : scaled) worst = std::max(worst, DistanceToCircle(p, circle));
  return worst * extent;
}

bool IsConvexQuad(const std::array<Eigen::Vector3d, 4>& v) {
  const Eigen::Vector3d n = (v[2] - v[0]).cross(v[3] - v[1]);
  for (int i = 0; i < 4; ++i) {
    const Eigen::Vector3d turn = (v[(i + 1) % 4] - v[i]).cross(v[(i + 2) % 4] - v[(i + 1) % 4]);
    if (!(turn.dot(n) > 0.0)) return false;
  }
  return true;
}

CircularityMeasures MeasureCircularity(const PolyMesh& mesh) {
  CircularityMeasures m;
  const double mean_edge = mesh.n_edges() > 0 ? MeanEdgeLength(mesh) : 1.0;
  int quads = 0;
  for (auto f : mesh.faces()) {
    if (mesh.valence(f) != 4) continue;
    std::array<Eigen::Vector3d, 4> quad;
    int k = 0;
    for (auto v : mesh.fv_range(f)) {
      const auto& p = mesh.point(v);
      quad[k++] = Eigen::Vector3d(p[0], p[1], p[2]);
    }
    const double c = QuadConcyclicity(quad) / mean_edge;
    if (!IsConvexQuad(quad)) ++m.folded_quads;
    if (c > m.max_concyclicity || m.worst_face < 0) {
      m.max_concyclicity = c;
      m.worst_face = f.idx();
    }
    m.mean_concyclicity += c;
    ++quads;
  }
  if (quads > 0) m.mean_concyclicity /= quads;
  return m;
}

}  // namespace gproj
