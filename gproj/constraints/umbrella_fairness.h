#pragma once
// Umbrella fairness at vertices that no mesh polyline passes through (the valence-3 vertices of
// hexagonal and hex-dominant meshes, where the second differences of 004 §3.2 have no
// polyline to run along): per vertex v with neighbours n_1 … n_k the row
//   (2 / k) Σ n_i − 2 v,
// one per coordinate (items {v, n_1, …, n_k}). At a valence-4 vertex it is the mean of the two
// polylines' second differences, so both kinds of rows weigh alike. Linear rows: the family is
// part of the P of ‖P x‖² (role kFairness).

#include "gproj/solver/constraint_family.h"

namespace gproj {

class UmbrellaFairness : public ConstraintFamily {
 public:
  // `dim` the dimension of the items (3 for vertices).
  explicit UmbrellaFairness(int dim = 3, double weight = 1.0,
                            std::string name = "fairness_umbrella");

  void EvaluateElement(int e, const double* x, double* phi, double* jac) const override;
  bool RowTouches(int e, int row, int local) const override { return local % dim_ == row; }

 private:
  int dim_;
};

}  // namespace gproj
