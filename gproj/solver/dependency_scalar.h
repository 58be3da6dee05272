#pragma once
// A scalar that records which inputs a value depends on: the structural sparsity of a term's
// rows, derived by evaluating its residual function once (gproj::Term). Each value carries the
// set of local scalars it was computed from and its numeric value at the evaluation point, so
// that code branching on values takes the branch it would take there. Any operation of two
// operands depends on the union of their inputs (conservative: 0 · x still depends on x).

#include <Eigen/Core>
#include <bitset>
#include <cmath>

namespace gproj {

template <int N>
struct DependencyScalar {
  double value = 0.0;
  std::bitset<N> inputs;

  DependencyScalar() = default;
  // Constants depend on nothing.
  DependencyScalar(double v) : value(v) {}  // NOLINT(runtime/explicit): mixes like a double
  DependencyScalar(double v, const std::bitset<N>& in) : value(v), inputs(in) {}

  DependencyScalar& operator+=(const DependencyScalar& o) { return *this = *this + o; }
  DependencyScalar& operator-=(const DependencyScalar& o) { return *this = *this - o; }
  DependencyScalar& operator*=(const DependencyScalar& o) { return *this = *this * o; }
  DependencyScalar& operator/=(const DependencyScalar& o) { return *this = *this / o; }

  friend DependencyScalar operator+(const DependencyScalar& a) { return a; }
  friend DependencyScalar operator-(const DependencyScalar& a) { return {-a.value, a.inputs}; }
  friend DependencyScalar operator+(const DependencyScalar& a, const DependencyScalar& b) {
    return {a.value + b.value, a.inputs | b.inputs};
  }
  friend DependencyScalar operator-(const DependencyScalar& a, const DependencyScalar& b) {
    return {a.value - b.value, a.inputs | b.inputs};
  }
  friend DependencyScalar operator*(const DependencyScalar& a, const DependencyScalar& b) {
    return {a.value * b.value, a.inputs | b.inputs};
  }
  friend DependencyScalar operator/(const DependencyScalar& a, const DependencyScalar& b) {
    return {a.value / b.value, a.inputs | b.inputs};
  }
  friend bool operator<(const DependencyScalar& a, const DependencyScalar& b) {
    return a.value < b.value;
  }
  friend bool operator>(const DependencyScalar& a, const DependencyScalar& b) {
    return a.value > b.value;
  }
  friend bool operator<=(const DependencyScalar& a, const DependencyScalar& b) {
    return a.value <= b.value;
  }
  friend bool operator>=(const DependencyScalar& a, const DependencyScalar& b) {
    return a.value >= b.value;
  }
  friend bool operator==(const DependencyScalar& a, const DependencyScalar& b) {
    return a.value == b.value;
  }
  friend bool operator!=(const DependencyScalar& a, const DependencyScalar& b) {
    return a.value != b.value;
  }

  // Elementary functions: the result depends on what the arguments depend on.
#define GPROJ_DEPENDENCY_UNARY(fn) \
  friend DependencyScalar fn(const DependencyScalar& a) { return {std::fn(a.value), a.inputs}; }
  GPROJ_DEPENDENCY_UNARY(sqrt)
  GPROJ_DEPENDENCY_UNARY(cbrt)
  GPROJ_DEPENDENCY_UNARY(abs)
  GPROJ_DEPENDENCY_UNARY(fabs)
  GPROJ_DEPENDENCY_UNARY(exp)
  GPROJ_DEPENDENCY_UNARY(log)
  GPROJ_DEPENDENCY_UNARY(sin)
  GPROJ_DEPENDENCY_UNARY(cos)
  GPROJ_DEPENDENCY_UNARY(tan)
  GPROJ_DEPENDENCY_UNARY(asin)
  GPROJ_DEPENDENCY_UNARY(acos)
  GPROJ_DEPENDENCY_UNARY(atan)
  GPROJ_DEPENDENCY_UNARY(sinh)
  GPROJ_DEPENDENCY_UNARY(cosh)
  GPROJ_DEPENDENCY_UNARY(tanh)
#undef GPROJ_DEPENDENCY_UNARY
  friend DependencyScalar atan2(const DependencyScalar& y, const DependencyScalar& x) {
    return {std::atan2(y.value, x.value), y.inputs | x.inputs};
  }
  friend DependencyScalar hypot(const DependencyScalar& a, const DependencyScalar& b) {
    return {std::hypot(a.value, b.value), a.inputs | b.inputs};
  }
  friend DependencyScalar pow(const DependencyScalar& a, const DependencyScalar& b) {
    return {std::pow(a.value, b.value), a.inputs | b.inputs};
  }
  friend DependencyScalar fmin(const DependencyScalar& a, const DependencyScalar& b) {
    return {std::fmin(a.value, b.value), a.inputs | b.inputs};
  }
  friend DependencyScalar fmax(const DependencyScalar& a, const DependencyScalar& b) {
    return {std::fmax(a.value, b.value), a.inputs | b.inputs};
  }
  friend bool isfinite(const DependencyScalar& a) { return std::isfinite(a.value); }
  friend bool isnan(const DependencyScalar& a) { return std::isnan(a.value); }
};

}  // namespace gproj

namespace Eigen {

// Lets DependencyScalar sit inside Eigen matrices (Map, cross, dot, norm), as ceres::Jet does.
template <int N>
struct NumTraits<gproj::DependencyScalar<N>> : GenericNumTraits<double> {
  using Real = gproj::DependencyScalar<N>;
  using NonInteger = gproj::DependencyScalar<N>;
  using Nested = gproj::DependencyScalar<N>;
  using Literal = gproj::DependencyScalar<N>;
  enum {
    IsComplex = 0,
    IsInteger = 0,
    IsSigned = 1,
    RequireInitialization = 1,
    ReadCost = 1,
    AddCost = 1,
    MulCost = 1,
  };
  static Real epsilon() { return Real(std::numeric_limits<double>::epsilon()); }
  static Real dummy_precision() { return Real(1e-12); }
  static Real highest() { return Real(std::numeric_limits<double>::max()); }
  static Real lowest() { return Real(std::numeric_limits<double>::lowest()); }
  static int digits10() { return std::numeric_limits<double>::digits10; }
};

template <typename BinaryOp, int N>
struct ScalarBinaryOpTraits<gproj::DependencyScalar<N>, double, BinaryOp> {
  using ReturnType = gproj::DependencyScalar<N>;
};
template <typename BinaryOp, int N>
struct ScalarBinaryOpTraits<double, gproj::DependencyScalar<N>, BinaryOp> {
  using ReturnType = gproj::DependencyScalar<N>;
};

}  // namespace Eigen
