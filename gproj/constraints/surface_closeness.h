#pragma once
// Closeness to a reference surface (004 §3.2, 003 §3.1.4): with p the closest point of the
// surface to v at x^k and n_p its unit normal there (both frozen, refreshed by Update),
//   SurfaceTangentCloseness:  n_p · (v − p) = 0      (one row; lets points slide along S)
//   SurfacePointCloseness:    v − p = 0              (three rows; weaker, keeps them near p)
// Items {v}. Both are soft regularisers. The surface is reached through a projector, so this
// file knows nothing about how closest points are found.

#include <Eigen/Core>
#include <functional>
#include <memory>
#include <vector>

#include "gproj/solver/constraint_family.h"

namespace gproj {

// Closest point of the reference surface to q, and the unit surface normal there.
using SurfaceProjector =
    std::function<void(const Eigen::Vector3d& q, Eigen::Vector3d* p, Eigen::Vector3d* n)>;

class SurfaceTangentCloseness : public ConstraintFamily {
 public:
  SurfaceTangentCloseness(SurfaceProjector projector, double weight,
                          std::string name = "surface_tangent")
      : ConstraintFamily(std::move(name), 1, FamilyRole::kSoft, weight),
        projector_(std::move(projector)) {}
  void Update(const VariableLayout& layout, const Eigen::VectorXd& x) override;
  void EvaluateElement(int e, const double* x, double* phi, double* jac) const override;

 private:
  SurfaceProjector projector_;
  std::vector<Eigen::Vector3d> points_, normals_;
};

class SurfacePointCloseness : public ConstraintFamily {
 public:
  SurfacePointCloseness(SurfaceProjector projector, double weight,
                        std::string name = "surface_point")
      : ConstraintFamily(std::move(name), 3, FamilyRole::kSoft, weight),
        projector_(std::move(projector)) {}
  void Update(const VariableLayout& layout, const Eigen::VectorXd& x) override;
  void EvaluateElement(int e, const double* x, double* phi, double* jac) const override;
  bool RowTouches(int, int row, int local) const override { return row == local; }

 private:
  SurfaceProjector projector_;
  std::vector<Eigen::Vector3d> points_;
};

}  // namespace gproj
