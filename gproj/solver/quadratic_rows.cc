#include "gproj/solver/quadratic_rows.h"

#include <algorithm>
#include <cmath>

namespace gproj {

void QuadraticRowsTable::Clear() {
  constants_.clear();
  entries_.clear();
  row_begin_.assign(1, 0);
}

bool QuadraticRowsTable::Append(const Evaluator& evaluate, std::string* why) {
  const size_t rd = static_cast<size_t>(rows_) * dim_;
  std::vector<double> x(dim_, 0.0), phi0(rows_), jac0(rd), phi(rows_), jac(rd);
  evaluate(x.data(), phi0.data(), jac0.data());
  // hessian[l]: rows × dim, the gradients' change along e_l.
  std::vector<double> hessian(rd * dim_);
  for (int l = 0; l < dim_; ++l) {
    x[l] = 1.0;
    evaluate(x.data(), phi.data(), jac.data());
    x[l] = 0.0;
    for (size_t k = 0; k < rd; ++k) hessian[l * rd + k] = jac[k] - jac0[k];
  }
  const size_t first_entry = entries_.size();
  for (int r = 0; r < rows_; ++r) {
    constants_.push_back(phi0[r]);
    for (int i = 0; i < dim_; ++i)
      if (jac0[r * dim_ + i] != 0.0) entries_.push_back({i, i, jac0[r * dim_ + i]});
    row_begin_.push_back(static_cast<int>(entries_.size()));
    for (int i = 0; i < dim_; ++i) {
      const double h = hessian[i * rd + r * dim_ + i];
      if (h != 0.0) entries_.push_back({i, i, h});
    }
    row_begin_.push_back(static_cast<int>(entries_.size()));
    for (int i = 0; i < dim_; ++i)
      for (int j = i + 1; j < dim_; ++j) {
        const double h = hessian[j * rd + r * dim_ + i];
        if (h != 0.0) entries_.push_back({i, j, h});
      }
    row_begin_.push_back(static_cast<int>(entries_.size()));
  }
  // Check the model at a point away from the ones it was read off.
  for (int l = 0; l < dim_; ++l) x[l] = 0.5 + 0.75 * std::sin(1.7 * l + 0.3);
  evaluate(x.data(), phi0.data(), jac0.data());
  Evaluate(num_models() - 1, x.data(), phi.data(), jac.data());
  for (int r = 0; r < rows_; ++r) {
    double scale = 1.0 + std::abs(phi0[r]);
    for (int i = 0; i < dim_; ++i) scale = std::max(scale, std::abs(jac0[r * dim_ + i]));
    double error = std::abs(phi[r] - phi0[r]);
    for (int i = 0; i < dim_; ++i)
      error = std::max(error, std::abs(jac[r * dim_ + i] - jac0[r * dim_ + i]));
    if (!(error <= 1e-9 * scale)) {
      *why = "row " + std::to_string(r) + " is not a polynomial of degree ≤ 2 (its quadratic " +
             "model is off by " + std::to_string(error) + ")";
      entries_.resize(first_entry);
      constants_.resize(constants_.size() - rows_);
      row_begin_.resize(row_begin_.size() - 3 * rows_);
      return false;
    }
  }
  return true;
}

void QuadraticRowsTable::Evaluate(int m, const double* x, double* phi, double* jac) const {
  std::fill(jac, jac + static_cast<size_t>(rows_) * dim_, 0.0);
  const int* begin = row_begin_.data() + 3 * m * rows_;
  const Entry* entries = entries_.data();
  for (int r = 0; r < rows_; ++r, begin += 3) {
    double value = constants_[m * rows_ + r];
    double* g = jac + r * dim_;
    for (int k = begin[0]; k < begin[1]; ++k) {
      value += entries[k].value * x[entries[k].i];
      g[entries[k].i] += entries[k].value;
    }
    for (int k = begin[1]; k < begin[2]; ++k) {
      const double hx = entries[k].value * x[entries[k].i];
      value += 0.5 * hx * x[entries[k].i];
      g[entries[k].i] += hx;
    }
    for (int k = begin[2]; k < begin[3]; ++k) {
      const Entry& e = entries[k];
      value += e.value * x[e.i] * x[e.j];
      g[e.i] += e.value * x[e.j];
      g[e.j] += e.value * x[e.i];
    }
    phi[r] = value;
  }
}

}  // namespace gproj
