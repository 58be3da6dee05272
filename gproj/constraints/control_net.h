#pragma once
// Constraints on a B-spline control net (003 §3.1.4).
//   EdgeLengthPreservation: (‖c_a − c_b‖² − l⁰²) / (2 l⁰) = 0, edges and face diagonals of the
//     control mesh (≈ ‖c_a − c_b‖ − l⁰ near the reference). Items {c_a, c_b}. Role kSoft.
//   PolylineGliding: a point glides along a fixed polyline β: with q the closest point of β to
//     the point at x^k and t the polyline's direction there, (c − q)·e1 = 0 and (c − q)·e2 = 0
//     with e1, e2 ⟂ t (frozen at x^k, refreshed by Update). Items {c}. Role kConstraint.
//     The rows are not followed by a closest-point retraction onto β: at a corner of β the
//     retraction moves a point across the rows' tangent to first order, and monotone steps
//     then stall; the rows alone bring the points onto β to the constraint tolerance.

#include <Eigen/Core>
#include <string>
#include <utility>
#include <vector>

#include "gproj/solver/term.h"

namespace gproj {

struct ReferenceLengthResidual {
  template <typename T>
  void operator()(const double& l0, const T* a, const T* b, T* r) const {
    T d2 = T(0.0);
    for (int c = 0; c < 3; ++c) d2 += (b[c] - a[c]) * (b[c] - a[c]);
    r[0] = (d2 - l0 * l0) / (2.0 * l0);
  }
};

class EdgeLengthPreservation : public Term<double, ReferenceLengthResidual, 1, 3, 3> {
 public:
  explicit EdgeLengthPreservation(double weight, std::string name = "shape preservation")
      : Term(std::move(name), ReferenceLengthResidual{}, FamilyRole::kSoft, weight) {}
  int AddEdge(int a, int b, double reference_length) { return Add({a, b}, reference_length); }
};

// The frame of a gliding point, frozen at x^k: the closest point q of its polyline and two unit
// vectors e1, e2 orthogonal to the polyline's direction there.
struct GlideFrame {
  int polyline = 0;
  Eigen::Vector3d foot = Eigen::Vector3d::Zero();
  Eigen::Vector3d e1 = Eigen::Vector3d::UnitX(), e2 = Eigen::Vector3d::UnitY();
};

struct GlideResidual {
  template <typename T>
  void operator()(const GlideFrame& frame, const T* c, T* r) const {
    const T d[3] = {c[0] - frame.foot[0], c[1] - frame.foot[1], c[2] - frame.foot[2]};
    r[0] = d[0] * frame.e1[0] + d[1] * frame.e1[1] + d[2] * frame.e1[2];
    r[1] = d[0] * frame.e2[0] + d[1] * frame.e2[1] + d[2] * frame.e2[2];
  }
};

class PolylineGliding : public Term<GlideFrame, GlideResidual, 2, 3> {
 public:
  explicit PolylineGliding(double weight, std::string name = "boundary gliding");
  // Adds a polyline (at least two points; a closed one repeats its first point at the end)
  // shared by the points that glide along it; returns its id.
  int AddPolyline(std::vector<Eigen::Vector3d> polyline);
  // The point `item` glides along polyline `polyline_id`.
  int AddPoint(int item, int polyline_id);
  // Adds `polyline` for this point alone.
  int AddPoint(int item, const std::vector<Eigen::Vector3d>& polyline) {
    return AddPoint(item, AddPolyline(polyline));
  }

  // The rows' frame turns from segment to segment, so a shifted target would point elsewhere.
  bool ShiftsTargets() const override { return false; }

  // Distance from the point of element e (at x) to its polyline.
  double DistanceToPolyline(int e, const VariableLayout& layout, const Eigen::VectorXd& x) const;

  // Closest point of a polyline to p and the unit direction of its segment.
  static void ClosestPoint(const std::vector<Eigen::Vector3d>& polyline, const Eigen::Vector3d& p,
                           Eigen::Vector3d* foot, Eigen::Vector3d* direction);

 private:
  std::vector<std::vector<Eigen::Vector3d>> polylines_;
};

}  // namespace gproj
