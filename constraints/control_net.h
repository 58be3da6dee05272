#pragma once
// Constraints on a B-spline control net (003 §3.1.4).
//   EdgeLengthPreservation: (‖c_a − c_b‖² − l⁰²) / (2 l⁰) = 0, edges and face diagonals of the
//     control mesh (≈ ‖c_a − c_b‖ − l⁰ near the reference). Items {c_a, c_b}. Role kSoft.
//   PolylineGliding: a point glides along a fixed polyline β: with q the closest point of β to
//     the point at x^k and t the polyline's direction there, (c − q)·e1 = 0 and (c − q)·e2 = 0
//     with e1, e2 ⟂ t (frozen at x^k, refreshed by Update). Items {c}. Role kConstraint.

#include <Eigen/Core>
#include <vector>

#include "solver/constraint_family.h"

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
  // `polyline`: at least two points; the point `item` glides along it.
  int AddPoint(int item, const std::vector<Eigen::Vector3d>& polyline);
  void EvaluateElement(int e, const double* x, double* phi, double* jac) const override;
  void Update(const VariableLayout& layout, const Eigen::VectorXd& x) override;

  // Closest point of a polyline to p and the unit direction of its segment.
  static void Project(const std::vector<Eigen::Vector3d>& polyline, const Eigen::Vector3d& p,
                      Eigen::Vector3d* foot, Eigen::Vector3d* direction);

 private:
  std::vector<std::vector<Eigen::Vector3d>> polylines_;
  std::vector<Eigen::Vector3d> foot_, e1_, e2_;
};

}  // namespace gproj
