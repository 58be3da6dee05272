#pragma once
// Planarity of a quad whose vertices move on fixed lines p_j = o_j + t_j d_j (002 §4.1,
// Fig. 14: general projections), with an auxiliary unit normal per face as in 004 §3.2:
//   n_f · (p_{j+1} − p_j) = 0  (j = 0..3, indices mod 4),   n_f · n_f − 1 = 0.
// Bilinear in (n_f, t). Element items: {n_f (3), t_0, t_1, t_2, t_3 (1 each)}; five rows.

#include <Eigen/Core>
#include <array>
#include <vector>

#include "gproj/solver/constraint_family.h"

namespace gproj {

class LineQuadPlanarity : public ConstraintFamily {
 public:
  explicit LineQuadPlanarity(double weight = 1.0, std::string name = "planarity")
      : ConstraintFamily(std::move(name), 5, FamilyRole::kConstraint, weight) {}

  // Adds one face: its normal item, the parameter items of its four vertices in cyclic order,
  // and their lines (origins o_j and directions d_j).
  int AddQuad(int normal, const std::array<int, 4>& t, const std::array<Eigen::Vector3d, 4>& o,
              const std::array<Eigen::Vector3d, 4>& d);

  void EvaluateElement(int e, const double* x, double* phi, double* jac) const override;
  bool RowTouches(int e, int row, int local) const override;

 private:
  std::vector<std::array<Eigen::Vector3d, 4>> origins_, directions_;
};

}  // namespace gproj
