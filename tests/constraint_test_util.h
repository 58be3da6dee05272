#pragma once
// Shared checks for constraint families: gradients against central finite differences.

#include <gtest/gtest.h>

#include <vector>

#include "gproj/solver/constraint_family.h"

namespace gproj {

// Compares every row's gradient of element e at x_local (local_dim values) with central
// differences (step h); max abs difference must be ≤ tol.
inline void ExpectGradientMatchesFiniteDifferences(const ConstraintFamily& family, int e,
                                                   std::vector<double> x_local, double h = 1e-6,
                                                   double tol = 1e-7) {
  const int rows = family.rows_per_element();
  const int n = static_cast<int>(x_local.size());
  std::vector<double> phi(rows), jac(rows * n), plus(rows), minus(rows), scratch(rows * n);
  family.EvaluateElement(e, x_local.data(), phi.data(), jac.data());
  for (int l = 0; l < n; ++l) {
    const double saved = x_local[l];
    x_local[l] = saved + h;
    family.EvaluateElement(e, x_local.data(), plus.data(), scratch.data());
    x_local[l] = saved - h;
    family.EvaluateElement(e, x_local.data(), minus.data(), scratch.data());
    x_local[l] = saved;
    for (int r = 0; r < rows; ++r) {
      const double fd = (plus[r] - minus[r]) / (2 * h);
      EXPECT_NEAR(jac[r * n + l], fd, tol) << family.name() << " row " << r << " local " << l;
      if (!family.RowTouches(e, r, l)) {
        EXPECT_EQ(jac[r * n + l], 0.0) << "row " << r << " declared not to touch local " << l;
      }
    }
  }
}

}  // namespace gproj
