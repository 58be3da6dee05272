#include "gproj/problems/weingarten/helical_fit.h"

#include <Eigen/Dense>
#include <algorithm>
#include <cmath>
#include <string>

#include "gproj/common/input_error.h"

namespace gproj::weingarten {

HelicalMotion FitHelicalMotion(const Eigen::MatrixX3d& points, const Eigen::MatrixX3d& normals) {
  const Eigen::Index count = points.rows();
  if (normals.rows() != count)
    throw InputError("a helical fit needs one normal per point (" + std::to_string(count) +
                     " points, " + std::to_string(normals.rows()) + " normals)");
  if (count < 6)
    throw InputError("a helical fit needs at least 6 points (got " + std::to_string(count) + ")");
  // Centred coordinates keep the 6 × 6 system well scaled; v(x) = c × (x − o) + c̄'.
  const Eigen::RowVector3d origin = points.colwise().mean();
  Eigen::Matrix<double, 6, 6> m = Eigen::Matrix<double, 6, 6>::Zero();
  for (Eigen::Index i = 0; i < count; ++i) {
    const Eigen::Vector3d x = (points.row(i) - origin).transpose();
    const Eigen::Vector3d n = normals.row(i).transpose();
    Eigen::Matrix<double, 6, 1> w;
    w << x.cross(n), n;
    m.selfadjointView<Eigen::Lower>().rankUpdate(w);
  }
  m.triangularView<Eigen::Upper>() = m.transpose();
  const Eigen::Matrix3d a = m.topLeftCorner<3, 3>(), b = m.topRightCorner<3, 3>(),
                        c = m.bottomRightCorner<3, 3>();
  // c̄' = −C⁺ Bᵀ c minimises over c̄' for a given c; C = Σ n nᵀ is singular only when the
  // normals span less than 3D (a cylinder or a plane), hence the pseudo-inverse.
  const Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d> ce(c);
  Eigen::Matrix3d c_pinv = Eigen::Matrix3d::Zero();
  const double floor = 1e-12 * std::max(ce.eigenvalues().maxCoeff(), 1e-300);
  for (int k = 0; k < 3; ++k)
    if (ce.eigenvalues()[k] > floor)
      c_pinv +=
          ce.eigenvectors().col(k) * ce.eigenvectors().col(k).transpose() / ce.eigenvalues()[k];
  const Eigen::Matrix3d reduced = a - b * c_pinv * b.transpose();
  const Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d> se(0.5 * (reduced + reduced.transpose()));
  const Eigen::Vector3d axis = se.eigenvectors().col(0);  // |c| = 1, smallest eigenvalue
  const Eigen::Vector3d bar_local = -c_pinv * b.transpose() * axis;
  // Back to world coordinates: c × (x − o) + c̄' = c × x + (c̄' − c × o).
  const Eigen::Vector3d bar = bar_local - axis.cross(origin.transpose());
  HelicalMotion motion;
  motion.axis = axis;
  motion.pitch = axis.dot(bar);
  motion.axis_point = axis.cross(bar);
  motion.residual = std::sqrt(std::max(se.eigenvalues()[0], 0.0) / static_cast<double>(count));
  return motion;
}

namespace {

// Max and mean |h − f(s)| of the least-squares polynomial f of `degree` through the points
// (s, h) in the cloud's principal frame.
std::pair<double, double> ProfileSpread(const std::vector<Eigen::Vector2d>& p, int degree) {
  Eigen::Vector2d mean = Eigen::Vector2d::Zero();
  for (const Eigen::Vector2d& q : p) mean += q;
  mean /= static_cast<double>(p.size());
  Eigen::Matrix2d cov = Eigen::Matrix2d::Zero();
  for (const Eigen::Vector2d& q : p) cov += (q - mean) * (q - mean).transpose();
  const Eigen::SelfAdjointEigenSolver<Eigen::Matrix2d> pca(cov);
  const Eigen::Vector2d along = pca.eigenvectors().col(1), across = pca.eigenvectors().col(0);
  const Eigen::Index count = static_cast<Eigen::Index>(p.size());
  Eigen::VectorXd s(count), h(count);
  for (Eigen::Index i = 0; i < count; ++i) {
    s[i] = (p[i] - mean).dot(along);
    h[i] = (p[i] - mean).dot(across);
  }
  const double half = std::max(s.cwiseAbs().maxCoeff(), 1e-300);
  // Legendre polynomials of s / half: well conditioned on [−1, 1].
  Eigen::MatrixXd basis(count, degree + 1);
  for (Eigen::Index i = 0; i < count; ++i) {
    const double t = s[i] / half;
    basis(i, 0) = 1.0;
    if (degree >= 1) basis(i, 1) = t;
    for (int k = 2; k <= degree; ++k)
      basis(i, k) = ((2 * k - 1) * t * basis(i, k - 1) - (k - 1) * basis(i, k - 2)) / k;
  }
  const Eigen::VectorXd coefficients = basis.colPivHouseholderQr().solve(h);
  const Eigen::VectorXd residual = (h - basis * coefficients).cwiseAbs();
  return {residual.maxCoeff(), residual.mean()};
}

}  // namespace

HelicalDeviation MeasureHelicalDeviation(const BSplineSurface& surface, int m, int n,
                                         int profile_degree) {
  if (m < 2 || n < 2 || profile_degree < 1)
    throw InputError(
        "a helical deviation needs a grid of at least 2 x 2 cells and a profile "
        "degree >= 1");
  const int count = (m + 1) * (n + 1);
  Eigen::MatrixX3d points(count, 3), normals(count, 3);
  int k = 0;
  for (int a = 0; a <= m; ++a)
    for (int b = 0; b <= n; ++b, ++k) {
      const double u = surface.u_min() + (surface.u_max() - surface.u_min()) * a / m;
      const double v = surface.v_min() + (surface.v_max() - surface.v_min()) * b / n;
      const auto d = surface.Derivatives(u, v);
      points.row(k) = d[0].transpose();
      normals.row(k) = d[1].cross(d[2]).normalized().transpose();
    }
  HelicalDeviation out;
  out.motion = FitHelicalMotion(points, normals);
  const Eigen::Vector3d axis = out.motion.axis;
  // Angles are measured from the mean radial direction, so a patch turning less than a full
  // circle gets continuous angles.
  Eigen::Vector3d mean_radial = Eigen::Vector3d::Zero();
  for (int i = 0; i < count; ++i) {
    const Eigen::Vector3d d = points.row(i).transpose() - out.motion.axis_point;
    mean_radial += d - d.dot(axis) * axis;
  }
  Eigen::Vector3d e1 = mean_radial.norm() > 0.0 ? mean_radial.normalized() : axis.unitOrthogonal();
  const Eigen::Vector3d e2 = axis.cross(e1);
  out.profile_points.reserve(count);
  for (int i = 0; i < count; ++i) {
    const Eigen::Vector3d d = points.row(i).transpose() - out.motion.axis_point;
    const double z = d.dot(axis);
    const Eigen::Vector3d radial = d - z * axis;
    const double phi = std::atan2(radial.dot(e2), radial.dot(e1));
    out.profile_points.emplace_back(radial.norm(), z - out.motion.pitch * phi);
    out.mean_radius += radial.norm() / count;
  }
  const auto [max_spread, mean_spread] = ProfileSpread(out.profile_points, profile_degree);
  const double radius = std::max(out.mean_radius, 1e-300);
  out.max_percent = 100.0 * max_spread / radius;
  out.mean_percent = 100.0 * mean_spread / radius;
  return out;
}

BSplineSurface MakeHelicalBSpline(int nu, int nv, int degree, const HelicalTestSurface& spec) {
  return FitBSpline(
      [&spec](double u, double v) {
        const double r = 1.0 + u, theta = M_PI * v;
        const double z =
            0.3 * (r - 1.5) * (r - 1.5) + spec.pitch * theta +
            spec.bump * std::exp(-20.0 * ((u - 0.5) * (u - 0.5) + (v - 0.4) * (v - 0.4))) +
            spec.pitch_drift * theta * theta + spec.profile_drift * (r - 1.5) * (r - 1.5) * v;
        return Eigen::Vector3d(r * std::cos(theta), r * std::sin(theta), z);
      },
      degree, degree, nu, nv);
}

}  // namespace gproj::weingarten
