#pragma once
// Elimination of per-element auxiliaries before the sparse factorisation (as Ceres' Schur
// solvers do for bundle adjustment). With x split into kept variables k and eliminated items
// e, whose rows never touch two different eliminated items,
//   N = A Aᵀ + β I = [N_kk  B; Bᵀ  D],  D block diagonal (one small block per item),
// the step solves  S d_k = g_k − B D⁻¹ g_e,  S = N_kk − B D⁻¹ Bᵀ,  then d_e = D⁻¹ (g_e − Bᵀ d_k).
// The pattern of S and every scatter position are computed once; Form only writes values.

#include <Eigen/Core>
#include <cstdint>
#include <string>
#include <vector>

#include "gproj/solver/sparse_cholesky.h"
#include "gproj/solver/variable_layout.h"

namespace gproj {

class SchurComplement {
 public:
  // Largest eliminated item dimension supported (small dense blocks live on the stack).
  static constexpr int kMaxItemDim = 24;

  // `a` is the pattern of A (n × m). Items of eliminable blocks are eliminated. Returns false
  // from Init (with a message) when some row touches two eliminated items or an item is larger
  // than kMaxItemDim; the caller then factors A Aᵀ directly.
  bool Init(const VariableLayout& layout, const CscMatrix& a, std::string* message);

  int num_kept() const { return s_.num_rows; }
  // Global variable of each kept index (increasing).
  const std::vector<int>& kept_variables() const { return kept_var_; }
  int num_eliminated() const { return num_eliminated_; }
  // Upper triangle of S without the β I term (the factorisation adds it): n_k × n_k.
  const CscMatrix& s() const { return s_; }

  // Writes S for the current values of A; false if a block D_e is not positive definite.
  bool Form(const CscMatrix& a, double beta, std::string* message);
  // g (n) → reduced right-hand side (n_k); `a` the matrix S was formed from.
  void ReduceRhs(const CscMatrix& a, const Eigen::VectorXd& g, Eigen::VectorXd* reduced) const;
  // d_k (n_k) and g (n) → the full step d (n); `a` the matrix S was formed from.
  void BackSubstitute(const CscMatrix& a, const Eigen::VectorXd& d_kept, const Eigen::VectorXd& g,
                      Eigen::VectorXd* d) const;

 private:
  // The steps of Init.
  bool CollectItems(const VariableLayout& layout, int n, std::vector<int>* item_of_var,
                    std::string* message);
  bool SplitColumns(const CscMatrix& a, const std::vector<int>& item_of_var, std::string* message);
  void GroupColumnsByItem(int m);
  void BuildPattern(int m);

  struct Item {
    int first_var = 0;  // global index of component 0
    int dim = 0;
    int kept_begin = 0;  // into kept_vars_: K_e, sorted kept indices touched with the item
    int kept_end = 0;
    int clique_begin = 0;            // into clique_pos_: S positions of the pairs a ≤ b of K_e
    int64_t v_offset = 0;            // into v_: V = A_eᵀ D⁻¹, cols × dim
    int dinv_offset = 0;             // into dinv_: dim × dim
    int col_begin = 0, col_end = 0;  // into item_cols_: columns of A touching the item
  };

  int num_eliminated_ = 0;
  CscMatrix s_;
  std::vector<int> kept_of_var_;  // n: kept index or −1
  std::vector<int> kept_var_;     // n_k: global variable of each kept index
  // Per column of A: its kept entries (positions in A, kept indices, local index in its
  // item's K_e or −1), its eliminated entries (positions in A, component) and, for a column
  // that touches no item, the S positions of its kept pairs p ≤ q (an item's columns add to its
  // clique instead).
  std::vector<int> col_kept_begin_, kept_pos_, kept_idx_, kept_local_;
  std::vector<int> col_elim_begin_, elim_pos_, elim_comp_;
  std::vector<int> col_item_;   // item touched by the column or −1
  std::vector<int> free_cols_;  // the columns that touch no item
  std::vector<int> col_pair_begin_, pair_pos_;
  std::vector<Item> items_;
  std::vector<int> kept_vars_, clique_pos_, item_cols_;
  std::vector<double> v_, dinv_;
  // Form's workspace, sized by Init for the largest item: A_K, A_e (then T), P, A_K P, the
  // clique.
  Eigen::MatrixXd ak_, ae_, p_, w_, clique_;
};

}  // namespace gproj
