#pragma once
// The weighted linearisation of all rows of a problem at x^k, in a fixed sparse pattern:
//   A = (S J)ᵀ  (n × m, CSC),  r = S φ  (m),  S = diag(√w).
// The pattern, scatter positions and buffers are built once; Assemble only writes values.

#include <Eigen/Core>
#include <string>
#include <vector>

#include "gproj/solver/problem.h"
#include "gproj/solver/sparse_cholesky.h"

namespace gproj {

class LinearizedSystem {
 public:
  // Builds the pattern of A from the families' elements and RowTouches.
  explicit LinearizedSystem(Problem* problem);

  // Updates frozen coefficients, evaluates every row at x and writes A and r. soft_scale
  // multiplies kSoft/kFairness weights; kFairness rows also get ω_f². Returns false (with a
  // message naming the family and element) if a value or gradient is non-finite.
  bool Assemble(const Eigen::VectorXd& x, double fairness_weight, double soft_scale,
                std::string* message);

  const CscMatrix& a() const { return a_; }        // n × m
  const Eigen::VectorXd& r() const { return r_; }  // m (weighted residuals)
  // Unweighted φ of the last Assemble, m.
  const Eigen::VectorXd& phi() const { return phi_; }
  int num_rows() const { return a_.num_cols; }
  int family_row_begin(int f) const { return family_row_begin_[f]; }
  // ½‖r‖² of the last Assemble.
  double Energy() const { return 0.5 * r_.squaredNorm(); }
  // Moves every kConstraint row's target against its residual at the last Assemble (v ← v − φ;
  // the row is then φ − v, see SolverOptions::shifted_constraints) and rewrites r to match.
  void ShiftConstraintTargets();
  // Variables held by the solve: every later Assemble writes their entries of A as 0, so a
  // step neither moves them nor counts on moving them (rhs and normal matrix of the others).
  void SetHeld(const std::vector<int>& variables);
  // Forgets every shift (the rows' own targets again).
  void ClearShifts() { shift_.resize(0); }
  // out = A r (n).
  void MultiplyAr(Eigen::VectorXd* out) const;
  // out = (A Aᵀ + β I) d (n), without forming A Aᵀ.
  void MultiplyNormal(const Eigen::VectorXd& d, double beta, Eigen::VectorXd* out);
  // out = Aᵀ d (m): the change of the weighted rows along d.
  void MultiplyAt(const Eigen::VectorXd& d, Eigen::VectorXd* out) const;
  // out = diag(A Aᵀ) (n).
  void NormalDiagonal(Eigen::VectorXd* out) const;

 private:
  Problem* problem_;
  CscMatrix a_;
  Eigen::VectorXd r_, phi_;
  Eigen::VectorXd shift_;              // per row: v of the shifted constraint rows (empty: none)
  std::vector<double> row_scale_;      // per family: √weight of the last Assemble
  std::vector<int> family_row_begin_;  // #families + 1
  // Per family, per element: global indices of the local scalars, and for every (row, local)
  // the position in a_.values (or −1).
  std::vector<std::vector<int>> local_begin_;  // per family: #elements + 1
  std::vector<std::vector<int>> local_index_;
  std::vector<std::vector<int>> scatter_;  // per family: Σ_e rows × L_e
  std::vector<double> x_local_, phi_local_, jac_local_;
  Eigen::VectorXd at_d_;           // m, scratch of MultiplyNormal
  std::vector<int> held_entries_;  // positions in a_.values of held variables
};

}  // namespace gproj
