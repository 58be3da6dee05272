#include "gproj/constraints/normal_orthogonality.h"

namespace gproj {

void EdgeNormalOrthogonality::EvaluateElement(int, const double* x, double* phi,
                                              double* jac) const {
  const double* n = x;
  const double* a = x + 3;
  const double* b = x + 6;
  phi[0] = 0.0;
  for (int c = 0; c < 3; ++c) {
    phi[0] += n[c] * (b[c] - a[c]);
    jac[c] = b[c] - a[c];
    jac[3 + c] = -n[c];
    jac[6 + c] = n[c];
  }
}

void UnitNormal::EvaluateElement(int, const double* n, double* phi, double* jac) const {
  phi[0] = n[0] * n[0] + n[1] * n[1] + n[2] * n[2] - 1.0;
  for (int c = 0; c < 3; ++c) jac[c] = 2.0 * n[c];
}

}  // namespace gproj
