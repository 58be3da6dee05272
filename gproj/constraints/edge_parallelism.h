#pragma once
// Edge parallelism between two meshes of one connectivity (000 eq. 3, §2.4: Combescure
// transformations): for every edge, e × (b − a) = 0, with e the unit direction of the edge in
// the fixed reference mesh and a, b the edge's vertices in the unknown mesh. Three rows per
// edge (rank two), linear in the unknowns.
//
// EdgeVector prescribes a whole edge vector, b − a − d = 0 (three rows): the lengths given along
// two crossing polylines in the Combescure construction (000 §2.5).
// Element items for both: {a, b}, dimension 3 each.

#include <Eigen/Geometry>
#include <vector>

#include "gproj/solver/constraint_family.h"

namespace gproj {

class EdgeParallelism : public ConstraintFamily {
 public:
  explicit EdgeParallelism(double weight = 1.0, std::string name = "edge parallelism")
      : ConstraintFamily(std::move(name), 3, FamilyRole::kConstraint, weight) {}

  // `direction` need not be unit; it is normalised (and must be non-zero).
  int AddEdge(int a, int b, const Eigen::Vector3d& direction);

  void EvaluateElement(int e, const double* x, double* phi, double* jac) const override;
  bool RowTouches(int e, int row, int local) const override { return local % 3 != row; }

 private:
  std::vector<Eigen::Vector3d> directions_;
};

class EdgeVector : public ConstraintFamily {
 public:
  explicit EdgeVector(double weight = 1.0, std::string name = "edge vector")
      : ConstraintFamily(std::move(name), 3, FamilyRole::kConstraint, weight) {}

  int AddEdge(int a, int b, const Eigen::Vector3d& vector);

  void EvaluateElement(int e, const double* x, double* phi, double* jac) const override;
  bool RowTouches(int e, int row, int local) const override { return local % 3 == row; }

 private:
  std::vector<Eigen::Vector3d> vectors_;
};

}  // namespace gproj
