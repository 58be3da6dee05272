#pragma once
// Closeness to a reference surface (004 §3.2, 003 §3.1.4): with p the closest point of the
// surface to v at x^k and n_p its unit normal there (both frozen, refreshed by the update step),
//   SurfaceTangentCloseness:  n_p · (v − p) = 0      (one row; lets points slide along S)
//   SurfacePointCloseness:    v − p = 0              (three rows; weaker, keeps them near p)
// Items {v}. Both are soft regularisers. The surface is reached through a projector, so this
// file knows nothing about how closest points are found.

#include <Eigen/Core>
#include <functional>
#include <string>
#include <utility>

#include "gproj/solver/term.h"

namespace gproj {

// Closest point of the reference surface to q, and the unit surface normal there.
using SurfaceProjector =
    std::function<void(const Eigen::Vector3d& q, Eigen::Vector3d* p, Eigen::Vector3d* n)>;

// The foot of a point on the surface, frozen at x^k.
struct SurfaceFoot {
  Eigen::Vector3d point = Eigen::Vector3d::Zero();
  Eigen::Vector3d normal = Eigen::Vector3d::Zero();
};

struct SurfaceTangentResidual {
  template <typename T>
  void operator()(const SurfaceFoot& foot, const T* v, T* r) const {
    const Eigen::Vector3d& n = foot.normal;
    const Eigen::Vector3d& p = foot.point;
    r[0] = n[0] * (v[0] - p[0]) + n[1] * (v[1] - p[1]) + n[2] * (v[2] - p[2]);
  }
};

struct SurfacePointResidual {
  template <typename T>
  void operator()(const SurfaceFoot& foot, const T* v, T* r) const {
    for (int c = 0; c < 3; ++c) r[c] = v[c] - foot.point[c];
  }
};

// A term on single points whose foot on the surface is refreshed from x^k by the projector.
template <typename Residual, int kRows>
class SurfaceCloseness : public Term<SurfaceFoot, Residual, kRows, 3> {
  using Base = Term<SurfaceFoot, Residual, kRows, 3>;

 public:
  SurfaceCloseness(SurfaceProjector projector, double weight, std::string name)
      : Base(std::move(name), Residual{}, FamilyRole::kSoft, weight) {
    Base::SetUpdate([projector = std::move(projector)](SurfaceFoot& foot, const double* v) {
      projector(Eigen::Vector3d(v[0], v[1], v[2]), &foot.point, &foot.normal);
    });
  }
  // The point `item` is held close to the surface; returns the element index.
  int AddPoint(int item) { return Base::Add({item}); }
};

class SurfaceTangentCloseness : public SurfaceCloseness<SurfaceTangentResidual, 1> {
 public:
  SurfaceTangentCloseness(SurfaceProjector projector, double weight,
                          std::string name = "surface_tangent")
      : SurfaceCloseness(std::move(projector), weight, std::move(name)) {}
};

class SurfacePointCloseness : public SurfaceCloseness<SurfacePointResidual, 3> {
 public:
  SurfacePointCloseness(SurfaceProjector projector, double weight,
                        std::string name = "surface_point")
      : SurfaceCloseness(std::move(projector), weight, std::move(name)) {}
};

}  // namespace gproj
