#include "gproj/constraints/control_net.h"

#include <Eigen/Geometry>
#include <algorithm>
#include <limits>
#include <utility>

namespace gproj {

PolylineGliding::PolylineGliding(double weight, std::string name)
    : Term(std::move(name), GlideResidual{}, FamilyRole::kConstraint, weight) {
  SetUpdate([this](GlideFrame& frame, const double* c) {
    Eigen::Vector3d direction;
    ClosestPoint(polylines_[frame.polyline], Eigen::Vector3d(c[0], c[1], c[2]), &frame.foot,
                 &direction);
    frame.e1 = direction.unitOrthogonal();
    frame.e2 = direction.cross(frame.e1);
  });
}

int PolylineGliding::AddPolyline(std::vector<Eigen::Vector3d> polyline) {
  polylines_.push_back(std::move(polyline));
  return static_cast<int>(polylines_.size()) - 1;
}

int PolylineGliding::AddPoint(int item, int polyline_id) {
  GlideFrame frame;
  frame.polyline = polyline_id;
  frame.foot = polylines_[polyline_id].front();
  return Add({item}, frame);
}

double PolylineGliding::DistanceToPolyline(int e, const VariableLayout& layout,
                                           const Eigen::VectorXd& x) const {
  const Eigen::Vector3d p = x.segment<3>(layout.ItemOffset(element_items(e)[0]));
  Eigen::Vector3d foot, direction;
  ClosestPoint(polylines_[data(e).polyline], p, &foot, &direction);
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
