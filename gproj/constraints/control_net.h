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
#include <vector>

#include "gproj/solver/constraint_family.h"

namespace gproj {

class EdgeLengthPreservation : public ConstraintFamily {
 public:
  explicit EdgeLengthPreservation(double weight, std::string name = "shape preservation")
      : ConstraintFamily(std::move(name), 1, FamilyRole::kSoft, weight) {}
  int AddEdge(int a, int b, double reference_length);
  void EvaluateElement(int e, const double* x, double* phi, double* jac) const override;

 private:
  std::vector<double> lengths_;
};

class PolylineGliding : public ConstraintFamily {
 public:
  explicit PolylineGliding(double weight, std::string name = "boundary gliding")
      : ConstraintFamily(std::move(name), 2, FamilyRole::kConstraint, weight) {}
  // Adds a polyline (at least two points; a closed one repeats its first point at the end)
  // shared by the points that glide along it; returns its id.
  int AddPolyline(std::vector<Eigen::Vector3d> polyline);
  // The point `item` glides along polyline `polyline_id`.
  int AddPoint(int item, int polyline_id);
  // Adds `polyline` for this point alone.
  int AddPoint(int item, const std::vector<Eigen::Vector3d>& polyline) {
    return AddPoint(item, AddPolyline(polyline));
  }

  void EvaluateElement(int e, const double* x, double* phi, double* jac) const override;
  void Update(const VariableLayout& layout, const Eigen::VectorXd& x) override;
  // The rows' frame turns from segment to segment, so a shifted target would point elsewhere.
  bool ShiftsTargets() const override { return false; }

  // Distance from the point of element e (at x) to its polyline.
  double DistanceToPolyline(int e, const VariableLayout& layout, const Eigen::VectorXd& x) const;

  // Closest point of a polyline to p and the unit direction of its segment.
  static void ClosestPoint(const std::vector<Eigen::Vector3d>& polyline, const Eigen::Vector3d& p,
                           Eigen::Vector3d* foot, Eigen::Vector3d* direction);

 private:
  std::vector<std::vector<Eigen::Vector3d>> polylines_;
  std::vector<int> polyline_of_;  // per element
  std::vector<Eigen::Vector3d> foot_, e1_, e2_;
};

}  // namespace gproj
