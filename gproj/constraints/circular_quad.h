#pragma once
// Circular quad (000 §2): the four vertices are coplanar and concyclic. One auxiliary
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

#include "gproj/solver/term.h"

namespace gproj {

// The definition: the ten rows of one quad from its auxiliary (n, m, ρ) and vertices.
struct CircularQuadResidual {
  template <typename T>
  void operator()(const T* c, const T* v0, const T* v1, const T* v2, const T* v3, T* r) const {
    const T *n = c, *m = c + 3;
    const T* v[4] = {v0, v1, v2, v3};
    for (int j = 0; j < 4; ++j) {
      const int k = (j + 1) % 4;
      r[j] = n[0] * (v[k][0] - v[j][0]) + n[1] * (v[k][1] - v[j][1]) + n[2] * (v[k][2] - v[j][2]);
    }
    r[4] = n[0] * n[0] + n[1] * n[1] + n[2] * n[2] - 1.0;
    for (int j = 0; j < 4; ++j) {
      const T d[3] = {v[j][0] - m[0], v[j][1] - m[1], v[j][2] - m[2]};
      r[5 + j] = d[0] * d[0] + d[1] * d[1] + d[2] * d[2] - c[6];
    }
    r[9] = n[0] * (m[0] - v0[0]) + n[1] * (m[1] - v0[1]) + n[2] * (m[2] - v0[2]);
  }
};
using CircularQuadTerm = Term<NoData, CircularQuadResidual, 10, 7, 3, 3, 3, 3>;

// The term, declared quadratic.
class CircularQuad : public CircularQuadTerm {
 public:
  static constexpr int kAuxiliaryDim = 7;

  explicit CircularQuad(double weight = 1.0, std::string name = "circularity")
      : CircularQuadTerm(std::move(name), CircularQuadResidual{}, FamilyRole::kConstraint, weight) {
    DeclareQuadratic();
  }

  int AddQuad(int circle, int v0, int v1, int v2, int v3) { return Add({circle, v0, v1, v2, v3}); }

  // (n, m, ρ) for a quad: n from the diagonals, m the circumcentre of v0 v1 v2, ρ the mean
  // squared distance of the four vertices to m. Exact for a circular quad.
  static Eigen::Matrix<double, 7, 1> InitialAuxiliary(const std::array<Eigen::Vector3d, 4>& quad);
};

}  // namespace gproj
