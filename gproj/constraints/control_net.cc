#include "gproj/constraints/control_net.h"

#include <Eigen/Geometry>
#include <algorithm>
#include <limits>
#include <utility>

namespace gproj {

int EdgeLengthPreservation::AddEdge(int a, int b, double reference_length) {
  lengths_.push_back(reference_length);
  return AddElement({a, b});
}

void EdgeLengthPreservation::EvaluateElement(int e, const double* x, double* phi,
                                             double* jac) const {
  const double l0 = lengths_[e];
  double d2 = 0.0;
  for (int c = 0; c < 3; ++c) {
    const double d = x[3 + c] - x[c];
    d2 += d * d;
    jac[c] = -d / l0;
    jac[3 + c] = d / l0;
  }
  phi[0] = (d2 - l0 * l0) / (2.0 * l0);
}

int PolylineGliding::AddPolyline(std::vector<Eigen::Vector3d> polyline) {
  polylines_.push_back(std::move(polyline));
  return static_cast<int>(polylines_.size()) - 1;
}

int PolylineGliding::AddPoint(int item, int polyline_id) {
  polyline_of_.push_back(polyline_id);
  foot_.push_back(polylines_[polyline_id].front());
  e1_.emplace_back(1, 0, 0);
  e2_.emplace_back(0, 1, 0);
  return AddElement({item});
}

void PolylineGliding::EvaluateElement(int e, const double* x, double* phi, double* jac) const {
  const Eigen::Vector3d d = Eigen::Vector3d(x[0], x[1], x[2]) - foot_[e];
  phi[0] = d.dot(e1_[e]);
  phi[1] = d.dot(e2_[e]);
  for (int c = 0; c < 3; ++c) {
    jac[c] = e1_[e][c];
    jac[3 + c] = e2_[e][c];
  }
}

void PolylineGliding::Update(const VariableLayout& layout, const Eigen::VectorXd& x) {
  for (int e = 0; e < num_elements(); ++e) {
    const Eigen::Vector3d p = x.segment<3>(layout.ItemOffset(element_items(e)[0]));
    Eigen::Vector3d direction;
    const std::vector<Eigen::Vector3d>& polyline = polylines_[polyline_of_[e]];
    ClosestPoint(polyline, p, &foot_[e], &direction);
    e1_[e] = direction.unitOrthogonal();
    e2_[e] = direction.cross(e1_[e]);
  }
}

double PolylineGliding::DistanceToPolyline(int e, const VariableLayout& layout,
                                           const Eigen::VectorXd& x) const {
  const Eigen::Vector3d p = x.segment<3>(layout.ItemOffset(element_items(e)[0]));
  Eigen::Vector3d foot, direction;
  ClosestPoint(polylines_[polyline_of_[e]], p, &foot, &direction);
  return (p - foot).norm();
}

void PolylineGliding::ClosestPoint(const std::vector<Eigen::Vector3d>& polyline,
                                   const Eigen::Vector3d& p, Eigen::Vector3d* foot,
                                   Eigen::Vector3d* direction) {
  double best = std::numeric_limits<double>::infinity();
  for (size_t i = 0; i + 1 < polyline.size(); ++i) {
    const Eigen::Vector3d a = polyline[i], ab = polyline[i + 1] - a;
    const double s = std::clamp((p - a).dot(ab) / std::max(ab.squaredNorm(), 1e-300), 0.0, 1.0);
    const Eigen::Vector3d q = a + s * ab;
    const double d = (q - p).squaredNorm();
    if (d < best) {
      best = d;
      *foot = q;
      *direction = ab.normalized();
    }
  }
}

}  // namespace gproj
