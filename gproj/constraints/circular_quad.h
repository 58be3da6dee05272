#pragma once
// Circular quad (000 §2; SPEC §2): the four vertices are coplanar and concyclic. One auxiliary
// item c = (n, m, ρ) per face (dimension 7: unit normal n, centre m, squared radius ρ):
//   n · (v_{j+1} − v_j) = 0   (j = 0..3, indices mod 4)      planarity
//   n · n − 1 = 0
//   ‖v_j − m‖² − ρ = 0        (j = 0..3)                      co-spherical
//   n · (m − v_0) = 0                                         centre in the plane
// A planar quad on a sphere lies on a circle; the last row pins m to the circle's centre.
// Element items: {c, v0, v1, v2, v3}. Ten rows per element. The auxiliary is per face, so the
// solver eliminates it when its block is eliminable.

#include <Eigen/Geometry>
#include <array>

#include "gproj/solver/constraint_family.h"

namespace gproj {

class CircularQuad : public ConstraintFamily {
 public:
  static constexpr int kAuxiliaryDim = 7;

  explicit CircularQuad(double weight = 1.0, std::string name = "circularity")
      : ConstraintFamily(std::move(name), 10, FamilyRole::kConstraint, weight) {}

  int AddQuad(int circle, int v0, int v1, int v2, int v3) {
    return AddElement({circle, v0, v1, v2, v3});
  }

  void EvaluateElement(int e, const double* x, double* phi, double* jac) const override;
  bool RowTouches(int e, int row, int local) const override;

  // (n, m, ρ) for a quad: n from the diagonals, m the circumcentre of v0 v1 v2, ρ the mean
  // squared distance of the four vertices to m. Exact for a circular quad.
  static Eigen::Matrix<double, 7, 1> InitialAuxiliary(const std::array<Eigen::Vector3d, 4>& quad);
};

}  // namespace gproj
