#pragma once
// Quad planarity with an auxiliary unit normal per face (004 §3.2; Tang et al. 2014):
//   n_f · (v_{j+1} − v_j) = 0  (j = 0..3, indices mod 4),   n_f · n_f − 1 = 0.
// Element items: {n_f, v0, v1, v2, v3}, each of dimension 3. Five rows per element.

#include <Eigen/Geometry>
#include <string>

#include "gproj/solver/term.h"

namespace gproj {

// The definition: the five rows of one quad from its normal and vertices.
struct QuadPlanarityResidual {
  template <typename T>
  void operator()(const T* n, const T* v0, const T* v1, const T* v2, const T* v3, T* r) const {
    const T* v[5] = {v0, v1, v2, v3, v0};
    for (int j = 0; j < 4; ++j)
      r[j] = n[0] * (v[j + 1][0] - v[j][0]) + n[1] * (v[j + 1][1] - v[j][1]) +
             n[2] * (v[j + 1][2] - v[j][2]);
    r[4] = n[0] * n[0] + n[1] * n[1] + n[2] * n[2] - 1.0;
  }
};

using QuadPlanarityTerm = Term<NoData, QuadPlanarityResidual, 5, 3, 3, 3, 3, 3>;

// The term, declared quadratic: derivatives and sparsity automatic, evaluated from its
// coefficients (bench/term_benchmark.cc compares it with a hand-written Jacobian).
class QuadPlanarity : public QuadPlanarityTerm {
 public:
  explicit QuadPlanarity(double weight = 1.0, std::string name = "planarity")
      : QuadPlanarityTerm(std::move(name), QuadPlanarityResidual{}, FamilyRole::kConstraint,
                          weight) {
    DeclareQuadratic();
  }

  // Adds one face: its normal item and its four vertex items in cyclic order.
  int AddQuad(int normal, int v0, int v1, int v2, int v3) { return Add({normal, v0, v1, v2, v3}); }

  // The unit normal of a quad from its diagonals: (v2 − v0) × (v3 − v1), normalised.
  static Eigen::Vector3d InitialNormal(const Eigen::Vector3d& v0, const Eigen::Vector3d& v1,
                                       const Eigen::Vector3d& v2, const Eigen::Vector3d& v3);
};

}  // namespace gproj
