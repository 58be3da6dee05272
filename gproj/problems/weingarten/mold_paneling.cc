#include "gproj/problems/weingarten/mold_paneling.h"

#include <ceres/jet.h>
#include <ceres/rotation.h>

#include <Eigen/Dense>
#include <Eigen/SparseCholesky>
#include <algorithm>
#include <array>
#include <cmath>
#include <map>
#include <string>
#include <utility>

#include "gproj/common/input_error.h"
#include "gproj/common/run_stopped.h"
#include "gproj/problems/weingarten/curvature_diagram.h"

namespace gproj::weingarten {
namespace {

constexpr double kPi = 3.14159265358979323846;

// The ten monomials at (x, y) and their x and y derivatives.
template <typename T>
void Monomials(const T& x, const T& y, T* m, T* mx, T* my) {
  const T xx = x * x, yy = y * y;
  const T values[10] = {T(1), x, y, xx, x * y, yy, xx * x, xx * y, x * yy, yy * y};
  const T dx[10] = {T(0), T(1), T(0), 2.0 * x, y, T(0), 3.0 * xx, 2.0 * x * y, yy, T(0)};
  const T dy[10] = {T(0), T(0), T(1), T(0), x, 2.0 * y, T(0), xx, 2.0 * x * y, 3.0 * yy};
  for (int i = 0; i < 10; ++i) {
    m[i] = values[i];
    if (mx) mx[i] = dx[i];
    if (my) my[i] = dy[i];
  }
}

// The mold's height f and slopes f_x, f_y at (x, y); T a scalar or a Jet.
template <typename T>
void CubicAt(const MoldShape& mold, const T& x, const T& y, T* f, T* fx, T* fy) {
  T m[10], mx[10], my[10];
  Monomials<T>(x / mold.scale, y / mold.scale, m, mx, my);
  *f = *fx = *fy = T(0);
  for (int i = 0; i < 10; ++i) {
    if (mold.coefficients[i] == 0.0) continue;
    *f += mold.coefficients[i] * m[i];
    *fx += mold.coefficients[i] * mx[i] / mold.scale;
    *fy += mold.coefficients[i] * my[i] / mold.scale;
  }
}

Eigen::Matrix3d Cross(const Eigen::Vector3d& a) {
  Eigen::Matrix3d m;
  m << 0, -a.z(), a.y(), a.z(), 0, -a.x(), -a.y(), a.x(), 0;
  return m;
}

// A panel of the design surface: its sample points (points_per_side² of them, row-major over
// (u, v)), its centre's curvatures and principal frame.
struct DesignPanel {
  std::vector<Eigen::Vector3d> points;
  double h = 0.0, k = 0.0;
  Eigen::Isometry3d frame = Eigen::Isometry3d::Identity();  // principal frame → world
  double size = 0.0;                                        // half its diagonal
};

DesignPanel MakePanel(const BSplineSurface& s, double u0, double u1, double v0, double v1, int m) {
  DesignPanel p;
  for (int a = 0; a < m; ++a)
    for (int b = 0; b < m; ++b)
      p.points.push_back(s.Point(u0 + (u1 - u0) * a / (m - 1), v0 + (v1 - v0) * b / (m - 1)));
  const auto d = s.Derivatives(0.5 * (u0 + u1), 0.5 * (v0 + v1));
  const Eigen::Vector3d cross = d[1].cross(d[2]);
  if (!(cross.norm() > 0.0) || !cross.allFinite())
    throw InputError(
        "the surface is degenerate (s_u × s_v = 0) at the centre of the panel over "
        "u ∈ [" +
        std::to_string(u0) + ", " + std::to_string(u1) + "], v ∈ [" + std::to_string(v0) + ", " +
        std::to_string(v1) + "]");
  const Eigen::Vector3d n = cross.normalized();
  Eigen::Matrix2d first, second;
  first << d[1].dot(d[1]), d[1].dot(d[2]), d[1].dot(d[2]), d[2].dot(d[2]);
  second << d[3].dot(n), d[4].dot(n), d[4].dot(n), d[5].dot(n);
  p.k = second.determinant() / first.determinant();
  p.h = 0.5 * (first.inverse() * second).trace();
  // Principal directions: second w = κ first w; the larger κ first.
  const Eigen::GeneralizedSelfAdjointEigenSolver<Eigen::Matrix2d> eig(second, first);
  const Eigen::Vector2d w = eig.eigenvectors().col(1);
  Eigen::Vector3d d1 = w.x() * d[1] + w.y() * d[2];
  d1 = (d1 - d1.dot(n) * n).normalized();
  if (!d1.allFinite()) d1 = (d[1] - d[1].dot(n) * n).normalized();
  Eigen::Matrix3d r;
  r.col(0) = d1;
  r.col(1) = n.cross(d1);
  r.col(2) = n;
  p.frame.linear() = r;
  p.frame.translation() = d[0];
  p.size = 0.5 * (p.points.front() - p.points.back()).norm();
  return p;
}

// The mold point above design point x for a panel placed by `placement` on `mold`, and the
// mold's unit normal there (world).
void MoldPoint(const MoldShape& mold, const Eigen::Isometry3d& placement, const Eigen::Vector3d& x,
               Eigen::Vector3d* point, Eigen::Vector3d* normal) {
  const Eigen::Vector3d q = placement.inverse() * x;
  const Eigen::Vector3d f = mold.HeightAndSlope(q.x(), q.y());
  *point = placement * Eigen::Vector3d(q.x(), q.y(), f[0]);
  *normal = placement.linear() * Eigen::Vector3d(-f[1], -f[2], 1.0).normalized();
}

// Least-squares cubic through the points of every panel in its placement's frame. The mold
// passes through the frame's origin with the xy-plane as its tangent plane (no constant or
// linear term): otherwise a tilt or shift of all placements, absorbed by the linear terms, would
// leave the fit unchanged and the placements free to drift.
MoldShape FitMold(const std::vector<const DesignPanel*>& panels,
                  const std::vector<Eigen::Isometry3d*>& placements, double scale) {
  int rows = 0;
  for (const DesignPanel* p : panels) rows += static_cast<int>(p->points.size());
  Eigen::MatrixXd a(rows, 7);
  Eigen::VectorXd z(rows);
  int r = 0;
  for (size_t i = 0; i < panels.size(); ++i) {
    const Eigen::Isometry3d inverse = placements[i]->inverse();
    for (const Eigen::Vector3d& x : panels[i]->points) {
      const Eigen::Vector3d q = inverse * x;
      double m[10];
      Monomials<double>(q.x() / scale, q.y() / scale, m, nullptr, nullptr);
      for (int c = 0; c < 7; ++c) a(r, c) = m[c + 3];
      z[r++] = q.z();
    }
  }
  MoldShape mold;
  mold.scale = scale;
  mold.coefficients.tail<7>() = a.colPivHouseholderQr().solve(z);
  return mold;
}

// Sum of squared vertical residuals q_z − f(q_x, q_y) of the panel's points q in the mold frame.
double PlacementError(const DesignPanel& panel, const MoldShape& mold,
                      const Eigen::Isometry3d& placement) {
  const Eigen::Isometry3d inverse = placement.inverse();
  double sum = 0.0;
  for (const Eigen::Vector3d& x : panel.points) {
    const Eigen::Vector3d q = inverse * x;
    const double r = q.z() - mold.Height(q.x(), q.y());
    sum += r * r;
  }
  return sum;
}

// Levenberg–Marquardt on the rigid motion placing `panel` on `mold`: the vertical residuals
// q_z − f(q_x, q_y), q the panel's points in the mold frame, with a small rotation ω and
// translation τ of the frame. A step is kept only if it lowers the error; the damping keeps the
// motions a nearly symmetric mold hardly determines (sliding, turning about the normal) small.
// Returns the RMS residual.
double PlacePanel(const DesignPanel& panel, const MoldShape& mold, Eigen::Isometry3d* placement,
                  int steps) {
  double error = PlacementError(panel, mold, *placement), lambda = 1e-3;
  for (int step = 0; step < steps; ++step) {
    Eigen::Matrix<double, 6, 6> normal = Eigen::Matrix<double, 6, 6>::Zero();
    Eigen::Matrix<double, 6, 1> rhs = Eigen::Matrix<double, 6, 1>::Zero();
    const Eigen::Isometry3d inverse = placement->inverse();
    for (const Eigen::Vector3d& x : panel.points) {
      const Eigen::Vector3d q = inverse * x;
      const Eigen::Vector3d f = mold.HeightAndSlope(q.x(), q.y());
      const Eigen::RowVector3d g(-f[1], -f[2], 1.0);  // ∂residual / ∂q
      // q(ω, τ) = exp(−[ω]×) (q − τ): ∂q/∂ω = [q]×, ∂q/∂τ = −I.
      Eigen::Matrix<double, 1, 6> j;
      j << g * Cross(q), -g;
      normal += j.transpose() * j;
      rhs -= j.transpose() * (q.z() - f[0]);
    }
    // Rotations in radians and translations in panel sizes weigh alike in the damping.
    Eigen::Matrix<double, 6, 1> unit;
    unit << 1, 1, 1, 1 / panel.size, 1 / panel.size, 1 / panel.size;
    const double level = normal.diagonal().maxCoeff() + 1e-300;
    bool improved = false;
    for (int attempt = 0; attempt < 8 && !improved; ++attempt, lambda *= 10.0) {
      Eigen::Matrix<double, 6, 6> damped = normal;
      damped.diagonal() += lambda * level * unit.cwiseAbs2();
      const Eigen::Matrix<double, 6, 1> delta = damped.ldlt().solve(rhs);
      if (!delta.allFinite()) break;
      const Eigen::Vector3d omega = delta.head<3>(), tau = delta.tail<3>();
      Eigen::Isometry3d motion = Eigen::Isometry3d::Identity();
      if (omega.norm() > 0.0)
        motion.linear() = Eigen::AngleAxisd(omega.norm(), omega.normalized()).toRotationMatrix();
      motion.translation() = tau;
      const Eigen::Isometry3d trial = *placement * motion;
      const double trial_error = PlacementError(panel, mold, trial);
      if (trial_error < error) {
        *placement = trial;
        error = trial_error;
        improved = true;
        lambda = std::max(lambda / 100.0, 1e-9);
      }
    }
    if (!improved) break;
  }
  return std::sqrt(error / panel.points.size());
}

// A seam sample: the same design point as point ia of panel a and point ib of panel b.
struct SeamSample {
  int a, b, ia, ib;
};

// Every seam sample of the panel grid: m per side shared by two panels.
std::vector<SeamSample> SeamSamples(int nu, int nv, int m) {
  std::vector<SeamSample> samples;
  for (int i = 0; i < nu; ++i)
    for (int j = 0; j < nv; ++j) {
      const int a = i * nv + j;
      for (int t = 0; t < m; ++t) {
        // The side u = u_{i+1} of panel (i, j) is the side u = u_{i+1} of panel (i + 1, j).
        if (i + 1 < nu) samples.push_back({a, a + nv, (m - 1) * m + t, t});
        if (j + 1 < nv) samples.push_back({a, a + 1, t * m + m - 1, t * m});
      }
    }
  return samples;
}

SeamMeasures MeasureSeams(const std::vector<DesignPanel>& panels, const Paneling& p,
                          const std::vector<SeamSample>& samples) {
  SeamMeasures s;
  for (const SeamSample& q : samples) {
    Eigen::Vector3d pa, na, pb, nb;
    MoldPoint(p.molds[p.mold_of_panel[q.a]], p.placement[q.a], panels[q.a].points[q.ia], &pa, &na);
    MoldPoint(p.molds[p.mold_of_panel[q.b]], p.placement[q.b], panels[q.b].points[q.ib], &pb, &nb);
    s.gaps.push_back((pa - pb).norm());
    s.kinks_deg.push_back(std::atan2(na.cross(nb).norm(), na.dot(nb)) * 180.0 / kPi);
  }
  for (double g : s.gaps) s.mean_gap += g / s.gaps.size(), s.max_gap = std::max(s.max_gap, g);
  for (double k : s.kinks_deg)
    s.mean_kink_deg += k / s.kinks_deg.size(), s.max_kink_deg = std::max(s.max_kink_deg, k);
  return s;
}

// The mold point above a design point and the mold's unit normal there (world), for a panel
// placed by base ∘ M(θ), M(θ) the rotation by the angle-axis θ[0..2] and then the translation
// θ[3..5]; q0 = base⁻¹ x is the design point in the base frame. T a scalar or a Jet over θ.
template <typename T>
void MovedMoldPoint(const MoldShape& mold, const Eigen::Isometry3d& base, const T* theta,
                    const Eigen::Vector3d& q0, Eigen::Matrix<T, 3, 1>* point,
                    Eigen::Matrix<T, 3, 1>* normal) {
  const T minus[3] = {-theta[0], -theta[1], -theta[2]};
  const T shifted[3] = {T(q0.x()) - theta[3], T(q0.y()) - theta[4], T(q0.z()) - theta[5]};
  T q[3];
  ceres::AngleAxisRotatePoint(minus, shifted, q);  // M⁻¹ q0
  T f, fx, fy;
  CubicAt(mold, q[0], q[1], &f, &fx, &fy);
  const T on_mold[3] = {q[0], q[1], f};
  T moved[3];
  ceres::AngleAxisRotatePoint(theta, on_mold, moved);
  const T length = sqrt(fx * fx + fy * fy + T(1));
  const T slope[3] = {-fx / length, -fy / length, T(1) / length};
  T turned[3];
  ceres::AngleAxisRotatePoint(theta, slope, turned);
  const Eigen::Matrix3d r = base.linear();
  for (int k = 0; k < 3; ++k) {
    (*point)[k] = T(base.translation()[k]);
    (*normal)[k] = T(0);
    for (int l = 0; l < 3; ++l) {
      (*point)[k] += r(k, l) * (moved[l] + theta[3 + l]);
      (*normal)[k] += r(k, l) * turned[l];
    }
  }
}

// Seam positioning: every panel's placement corrected by a rigid motion so that the gaps and
// kinks (normal differences) at the seam samples are small, each panel held to its design panel
// by its fit residuals at nine points (weight `hold`). Gaps and fit residuals are measured in
// units of the mean gap before positioning, kinks in units of the mean kink, so that neither
// is traded for the other whatever the surface's size. Levenberg–Marquardt on the 6 parameters
// per panel; the normal equations have one 6 × 6 block per panel and per pair of panels sharing
// a seam, accumulated in place (the pattern is built once).
class SeamPositioning {
 public:
  SeamPositioning(const std::vector<DesignPanel>& panels, const std::vector<SeamSample>& seams,
                  const SeamMeasures& fitted, double hold, Paneling* p)
      : panels_(panels),
        seams_(seams),
        hold_weight_(hold),
        p_(p),
        n_(static_cast<int>(panels.size())) {
    double size = 0.0;
    for (const DesignPanel& d : panels) size += d.size / n_;
    const double gap = fitted.mean_gap > 1e-9 * size ? fitted.mean_gap : 1e-3 * size;
    const double kink = std::max(fitted.mean_kink_deg * kPi / 180.0, 1e-6);
    inv_gap_ = gap > 0.0 ? 1.0 / gap : 1.0;
    inv_kink_ = 1.0 / kink;
    // Blocks: (a, a) for every panel, then (a, b), a < b, for every pair sharing a seam.
    for (int a = 0; a < n_; ++a) block_of_[{a, a}] = a;
    for (const SeamSample& s : seams) {
      const auto key = std::minmax(s.a, s.b);
      if (!block_of_.count(key)) block_of_.emplace(key, static_cast<int>(block_of_.size()));
    }
    blocks_.resize(block_of_.size());
    seam_block_.reserve(seams.size());
    for (const SeamSample& s : seams) {
      seam_block_.push_back(block_of_.at(std::minmax(s.a, s.b)));
      seam_q0_.push_back({p->placement[s.a].inverse() * panels[s.a].points[s.ia],
                          p->placement[s.b].inverse() * panels[s.b].points[s.ib]});
    }
    // Held at a 3 × 3 subset of its points (corners, side midpoints, centre).
    hold_begin_.push_back(0);
    for (int a = 0; a < n_; ++a) {
      const int m = static_cast<int>(std::lround(std::sqrt(panels[a].points.size())));
      const Eigen::Isometry3d inverse = p->placement[a].inverse();
      for (int i : {0, (m - 1) / 2, m - 1})
        for (int j : {0, (m - 1) / 2, m - 1}) {
          const Eigen::Vector3d& x = panels[a].points[i * m + j];
          hold_.push_back({x, inverse * x});
        }
      hold_begin_.push_back(static_cast<int>(hold_.size()));
    }
  }

  // Runs at most `iterations` LM steps and applies the motions to the placements.
  void Run(int iterations, const std::function<bool()>& stop) {
    Eigen::VectorXd theta = Eigen::VectorXd::Zero(6 * n_), gradient(6 * n_);
    double energy = Energy(theta), lambda = 1e-4;
    Eigen::SparseMatrix<double> normal(6 * n_, 6 * n_);
    std::vector<Eigen::Triplet<double>> triplets;
    // The blocks' pattern is the same at every step: ordered and analysed once; each damping
    // is a shift of the diagonal in the numeric factorisation.
    Eigen::SimplicialLDLT<Eigen::SparseMatrix<double>> ldlt;
    bool analysed = false;
    for (int it = 0; it < iterations; ++it) {
      PollStop(stop, "the paneling");
      Linearize(theta, &gradient);
      triplets.clear();
      for (const auto& [key, index] : block_of_)
        for (int i = 0; i < 6; ++i)
          for (int j = 0; j < 6; ++j) {
            triplets.emplace_back(6 * key.first + i, 6 * key.second + j, blocks_[index](i, j));
            if (key.first != key.second)
              triplets.emplace_back(6 * key.second + j, 6 * key.first + i, blocks_[index](i, j));
          }
      normal.setFromTriplets(triplets.begin(), triplets.end());
      if (!analysed) ldlt.analyzePattern(normal), analysed = true;
      const double level = normal.diagonal().maxCoeff() + 1e-300;
      bool improved = false;
      for (int attempt = 0; attempt < 8 && !improved; ++attempt, lambda *= 10.0) {
        ldlt.setShift(lambda * level);
        ldlt.factorize(normal);
        if (ldlt.info() != Eigen::Success) continue;
        const Eigen::VectorXd trial = theta - ldlt.solve(gradient);
        const double trial_energy = trial.allFinite() ? Energy(trial) : HUGE_VAL;
        if (trial_energy < energy) {
          improved = true;
          theta = trial;
          lambda = std::max(lambda / 100.0, 1e-12);
          const bool converged = energy - trial_energy < 1e-10 * energy;
          energy = trial_energy;
          if (converged) it = iterations;
        }
      }
      if (!improved) break;
    }
    for (int a = 0; a < n_; ++a) {
      const Eigen::Vector3d omega = theta.segment<3>(6 * a);
      Eigen::Isometry3d motion = Eigen::Isometry3d::Identity();
      if (omega.norm() > 0.0)
        motion.linear() = Eigen::AngleAxisd(omega.norm(), omega.normalized()).toRotationMatrix();
      motion.translation() = theta.segment<3>(6 * a + 3);
      p_->placement[a] = p_->placement[a] * motion;
    }
  }

 private:
  using Jet = ceres::Jet<double, 12>;  // both panels of a seam sample
  using HoldJet = ceres::Jet<double, 6>;

  // The 6 residuals of seam sample k (gap over L, normal difference) for motions ta, tb.
  template <typename T>
  void SeamResiduals(int k, const T* ta, const T* tb, T* r) const {
    const SeamSample& s = seams_[k];
    Eigen::Matrix<T, 3, 1> pa, na, pb, nb;
    MovedMoldPoint(p_->molds[p_->mold_of_panel[s.a]], p_->placement[s.a], ta, seam_q0_[k][0], &pa,
                   &na);
    MovedMoldPoint(p_->molds[p_->mold_of_panel[s.b]], p_->placement[s.b], tb, seam_q0_[k][1], &pb,
                   &nb);
    for (int k = 0; k < 3; ++k) {
      r[k] = (pa[k] - pb[k]) * inv_gap_;
      r[3 + k] = (na[k] - nb[k]) * inv_kink_;
    }
  }
  // The hold residual of hold point h of panel a: the design point's distance from the mold
  // along the mold's normal (the fit residual), weighted.
  template <typename T>
  T HoldResidual(int a, int h, const T* ta) const {
    const Eigen::Vector3d& x = hold_[h][0];
    Eigen::Matrix<T, 3, 1> point, normal;
    MovedMoldPoint(p_->molds[p_->mold_of_panel[a]], p_->placement[a], ta, hold_[h][1], &point,
                   &normal);
    T r(0.0);
    for (int k = 0; k < 3; ++k) r += (point[k] - x[k]) * normal[k];
    return r * (hold_weight_ * inv_gap_);
  }

  double Energy(const Eigen::VectorXd& t) const {
    double energy = 0.0, r[6];
    for (size_t k = 0; k < seams_.size(); ++k) {
      SeamResiduals(k, t.data() + 6 * seams_[k].a, t.data() + 6 * seams_[k].b, r);
      for (double v : r) energy += v * v;
    }
    for (int a = 0; a < n_; ++a)
      for (int h = hold_begin_[a]; h < hold_begin_[a + 1]; ++h) {
        const double v = HoldResidual(a, h, t.data() + 6 * a);
        energy += v * v;
      }
    return energy;
  }

  // Fills the blocks of JᵀJ and the gradient Jᵀr at t.
  void Linearize(const Eigen::VectorXd& t, Eigen::VectorXd* gradient) {
    for (auto& b : blocks_) b.setZero();
    gradient->setZero();
    Jet ta[6], tb[6];
    for (size_t k = 0; k < seams_.size(); ++k) {
      const SeamSample& s = seams_[k];
      for (int c = 0; c < 6; ++c) {
        ta[c] = Jet(t[6 * s.a + c], c);
        tb[c] = Jet(t[6 * s.b + c], 6 + c);
      }
      Jet r[6];
      SeamResiduals(static_cast<int>(k), ta, tb, r);
      const bool a_first = s.a < s.b;
      for (const Jet& v : r) {
        const Eigen::Matrix<double, 6, 1> ja = v.v.head<6>(), jb = v.v.tail<6>();
        gradient->segment<6>(6 * s.a) += ja * v.a;
        gradient->segment<6>(6 * s.b) += jb * v.a;
        blocks_[s.a] += ja * ja.transpose();
        blocks_[s.b] += jb * jb.transpose();
        blocks_[seam_block_[k]] += a_first ? Eigen::Matrix<double, 6, 6>(ja * jb.transpose())
                                           : Eigen::Matrix<double, 6, 6>(jb * ja.transpose());
      }
    }
    HoldJet th[6];
    for (int a = 0; a < n_; ++a) {
      for (int c = 0; c < 6; ++c) th[c] = HoldJet(t[6 * a + c], c);
      for (int h = hold_begin_[a]; h < hold_begin_[a + 1]; ++h) {
        const HoldJet v = HoldResidual(a, h, th);
        gradient->segment<6>(6 * a) += v.v * v.a;
        blocks_[a] += v.v * v.v.transpose();
      }
    }
  }

  const std::vector<DesignPanel>& panels_;
  const std::vector<SeamSample>& seams_;
  double hold_weight_;
  Paneling* p_;
  int n_;
  double inv_gap_ = 1.0, inv_kink_ = 1.0;
  std::map<std::pair<int, int>, int> block_of_;
  std::vector<Eigen::Matrix<double, 6, 6>> blocks_;
  std::vector<int> seam_block_;
  std::vector<std::array<Eigen::Vector3d, 2>> seam_q0_;  // per seam sample, in a's and b's base
  std::vector<std::array<Eigen::Vector3d, 2>> hold_;     // design point x and its base-frame q0
  std::vector<int> hold_begin_;                          // per panel, into hold_
};

}  // namespace

double MoldShape::Height(double x, double y) const { return HeightAndSlope(x, y)[0]; }

Eigen::Vector3d MoldShape::HeightAndSlope(double x, double y) const {
  Eigen::Vector3d f;
  CubicAt(*this, x, y, &f[0], &f[1], &f[2]);
  return f;
}

void PanelingOptions::Validate() const {
  if (panels_u < 1 || panels_v < 1)
    throw InputError("`panels`: at least 1 x 1 panels (got " + std::to_string(panels_u) + " x " +
                     std::to_string(panels_v) + ")");
  if (static_cast<int64_t>(panels_u) * panels_v > 1000000)
    throw InputError("`panels`: at most 1000000 panels (got " + std::to_string(panels_u) + " x " +
                     std::to_string(panels_v) + ")");
  if (molds < 1)
    throw InputError("paneling: at least one mold (got " + std::to_string(molds) + ")");
  if (points_per_side < 3 || points_per_side > 50)
    throw InputError("paneling: 3 to 50 points per panel side (got " +
                     std::to_string(points_per_side) + ")");
  if (fit_rounds < 1)
    throw InputError("paneling: at least one fit round (got " + std::to_string(fit_rounds) + ")");
  if (!(hold_weight >= 0.0) || !std::isfinite(hold_weight) || positioning_iterations < 0)
    throw InputError(
        "paneling: the hold weight must be finite and >= 0 and the positioning "
        "iterations >= 0");
}

Paneling PanelSurface(const BSplineSurface& surface, const PanelingOptions& options) {
  options.Validate();
  const int nu = options.panels_u, nv = options.panels_v, m = options.points_per_side;
  Paneling p;
  p.panels_u = nu;
  p.panels_v = nv;
  std::vector<DesignPanel> panels;
  panels.reserve(static_cast<size_t>(nu) * nv);
  const double du = (surface.u_max() - surface.u_min()) / nu;
  const double dv = (surface.v_max() - surface.v_min()) / nv;
  for (int i = 0; i < nu; ++i)
    for (int j = 0; j < nv; ++j) {
      const double u0 = surface.u_min() + i * du, v0 = surface.v_min() + j * dv;
      panels.push_back(MakePanel(surface, u0, u0 + du, v0, v0 + dv, m));
      p.h.push_back(panels.back().h);
      p.k.push_back(panels.back().k);
    }
  const MoldClustering clusters = ClusterMolds(p.h, p.k, options.molds);
  p.num_molds = clusters.num_clusters;
  p.cells_per_axis = clusters.cells_per_axis;
  p.mold_of_panel = clusters.cluster;
  p.placement.resize(panels.size());
  for (size_t i = 0; i < panels.size(); ++i) p.placement[i] = panels[i].frame;
  p.molds.resize(p.num_molds);
  for (int c = 0; c < p.num_molds; ++c) {
    PollStop(options.stop, "the paneling");
    std::vector<const DesignPanel*> members;
    std::vector<Eigen::Isometry3d*> placements;
    double scale = 0.0;
    for (size_t i = 0; i < panels.size(); ++i)
      if (p.mold_of_panel[i] == c) {
        members.push_back(&panels[i]);
        placements.push_back(&p.placement[i]);
        scale += panels[i].size;
      }
    scale = scale > 0.0 ? scale / members.size() : 1.0;
    for (int round = 0; round < options.fit_rounds; ++round) {
      p.molds[c] = FitMold(members, placements, scale);
      for (size_t i = 0; i < members.size(); ++i) {
        // A panel may also sit on the mold turned by a half turn about its normal (the
        // principal frame's sign is arbitrary): keep whichever fits better.
        Eigen::Isometry3d turned = *placements[i];
        turned.linear().col(0) *= -1.0;
        turned.linear().col(1) *= -1.0;
        const double plain = PlacePanel(*members[i], p.molds[c], placements[i], 3);
        if (round == 0 && PlacePanel(*members[i], p.molds[c], &turned, 3) < plain)
          *placements[i] = turned;
      }
    }
    p.molds[c] = FitMold(members, placements, scale);
    for (size_t i = 0; i < members.size(); ++i)
      PlacePanel(*members[i], p.molds[c], placements[i], 3);
  }
  const std::vector<SeamSample> seams = SeamSamples(nu, nv, m);
  p.fitted_seams = MeasureSeams(panels, p, seams);
  if (options.seam_positioning && panels.size() > 1)
    SeamPositioning(panels, seams, p.fitted_seams, options.hold_weight, &p)
        .Run(options.positioning_iterations, options.stop);
  p.seams = MeasureSeams(panels, p, seams);
  int points = 0;
  for (size_t i = 0; i < panels.size(); ++i)
    for (const Eigen::Vector3d& x : panels[i].points) {
      Eigen::Vector3d point, normal;
      MoldPoint(p.molds[p.mold_of_panel[i]], p.placement[i], x, &point, &normal);
      const double d = (point - x).norm();
      p.mean_deviation += d;
      p.max_deviation = std::max(p.max_deviation, d);
      ++points;
    }
  p.mean_deviation /= std::max(points, 1);
  return p;
}

int MoldsForTolerance(const BSplineSurface& surface, PanelingOptions options, double max_gap,
                      double max_kink_deg, Paneling* result) {
  auto meets = [&](const Paneling& p) {
    return p.seams.max_gap <= max_gap && p.seams.max_kink_deg <= max_kink_deg;
  };
  const int panels = options.panels_u * options.panels_v;
  options.molds = panels;
  Paneling best = PanelSurface(surface, options);
  if (!meets(best)) {
    if (result) *result = best;
    return -1;
  }
  // Down from one mold per panel to the first count that fails. Counts whose clustering is the
  // previous count's give its paneling again and are not recomputed.
  const std::vector<double> h = best.h, k = best.k;
  std::vector<int> previous = best.mold_of_panel;
  for (int molds = panels - 1; molds >= 1; --molds) {
    const MoldClustering clusters = ClusterMolds(h, k, molds);
    if (clusters.cluster == previous) continue;
    previous = clusters.cluster;
    options.molds = molds;
    Paneling trial = PanelSurface(surface, options);
    if (!meets(trial)) break;
    best = std::move(trial);
  }
  if (result) *result = best;
  return best.num_molds;
}

PolyMesh PanelMesh(const BSplineSurface& surface, const Paneling& paneling, int n,
                   std::vector<int>* panel_of_face) {
  PolyMesh mesh;
  if (panel_of_face) panel_of_face->clear();
  const double du = (surface.u_max() - surface.u_min()) / paneling.panels_u;
  const double dv = (surface.v_max() - surface.v_min()) / paneling.panels_v;
  for (int i = 0; i < paneling.panels_u; ++i)
    for (int j = 0; j < paneling.panels_v; ++j) {
      const int panel = i * paneling.panels_v + j;
      const MoldShape& mold = paneling.molds[paneling.mold_of_panel[panel]];
      std::vector<PolyMesh::VertexHandle> v;
      for (int a = 0; a <= n; ++a)
        for (int b = 0; b <= n; ++b) {
          const Eigen::Vector3d x = surface.Point(surface.u_min() + (i + double(a) / n) * du,
                                                  surface.v_min() + (j + double(b) / n) * dv);
          Eigen::Vector3d point, normal;
          MoldPoint(mold, paneling.placement[panel], x, &point, &normal);
          v.push_back(mesh.add_vertex(PolyMesh::Point(point.x(), point.y(), point.z())));
        }
      for (int a = 0; a < n; ++a)
        for (int b = 0; b < n; ++b) {
          mesh.add_face({v[a * (n + 1) + b], v[(a + 1) * (n + 1) + b], v[(a + 1) * (n + 1) + b + 1],
                         v[a * (n + 1) + b + 1]});
          if (panel_of_face) panel_of_face->push_back(panel);
        }
    }
  return mesh;
}

}  // namespace gproj::weingarten
