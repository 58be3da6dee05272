#pragma once
// Rows that tie an auxiliary normal to the edges it must be orthogonal to (004 §3.2, option
// (i); Deng et al. 2011):
//   EdgeNormalOrthogonality:  n · (b − a) = 0,  items {n, a, b}, one row per element
//   UnitNormal:               n · n − 1 = 0,    items {n},       one row per element
// Vertex-star planarity is one UnitNormal per inner vertex v plus one orthogonality row per
// edge (v, v_j) of its star. Both rows are quadratic but are not declared so: their automatic
// derivatives equal the former hand-written ones bit for bit, while the quadratic model sums in
// another order, which moves the shipped H-net demo (several rounds of A-net solves) by 2e-7°.

#include <string>
#include <utility>

#include "gproj/solver/term.h"

namespace gproj {

struct EdgeNormalOrthogonalityResidual {
  template <typename T>
  void operator()(const T* n, const T* a, const T* b, T* r) const {
    r[0] = n[0] * (b[0] - a[0]) + n[1] * (b[1] - a[1]) + n[2] * (b[2] - a[2]);
  }
};

struct UnitNormalResidual {
  template <typename T>
  void operator()(const T* n, T* r) const {
    r[0] = n[0] * n[0] + n[1] * n[1] + n[2] * n[2] - 1.0;
  }
};

class EdgeNormalOrthogonality : public Term<NoData, EdgeNormalOrthogonalityResidual, 1, 3, 3, 3> {
 public:
  explicit EdgeNormalOrthogonality(std::string name = "star_planarity", double weight = 1.0)
      : Term(std::move(name), EdgeNormalOrthogonalityResidual{}, FamilyRole::kConstraint, weight) {}
};

class UnitNormal : public Term<NoData, UnitNormalResidual, 1, 3> {
 public:
  explicit UnitNormal(std::string name = "unit_normal", double weight = 1.0)
      : Term(std::move(name), UnitNormalResidual{}, FamilyRole::kConstraint, weight) {}
};

}  // namespace gproj
