#include "geometry/mold_paneling.h"

#include <Eigen/Dense>
#include <algorithm>
#include <cmath>
#include <string>

#include "geometry/curvature_diagram.h"
#include "geometry/input_error.h"

namespace gproj {
namespace {

constexpr double kPi = 3.14159265358979323846;

// The ten monomials at (x, y) and their x and y derivatives.
void Monomials(double x, double y, double* m, double* mx, double* my) {
  const double xx = x * x, yy = y * y;
  const double values[10] = {1, x, y, xx, x * y, yy, xx * x, xx * y, x * yy, yy * y};
  const double dx[10] = {0, 1, 0, 2 * x, y, 0, 3 * xx, 2 * x * y, yy, 0};
  const double dy[10] = {0, 0, 1, 0, x, 2 * y, 0, xx, 2 * x * y, 3 * yy};
  for (int i = 0; i < 10; ++i) {
    m[i] = values[i];
    if (mx) mx[i] = dx[i];
    if (my) my[i] = dy[i];
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
      Monomials(q.x() / scale, q.y() / scale, m, nullptr, nullptr);
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

SeamMeasures MeasureSeams(const std::vector<DesignPanel>& panels, const Paneling& p, int m) {
  SeamMeasures s;
  auto seam = [&](int a, int b, auto point_index) {
    for (int t = 0; t < m; ++t) {
      const Eigen::Vector3d& x = panels[a].points[point_index(t, true)];
      Eigen::Vector3d pa, na, pb, nb;
      MoldPoint(p.molds[p.mold_of_panel[a]], p.placement[a], x, &pa, &na);
      MoldPoint(p.molds[p.mold_of_panel[b]], p.placement[b],
                panels[b].points[point_index(t, false)], &pb, &nb);
      s.gaps.push_back((pa - pb).norm());
      s.kinks_deg.push_back(std::atan2(na.cross(nb).norm(), na.dot(nb)) * 180.0 / kPi);
    }
  };
  for (int i = 0; i < p.panels_u; ++i)
    for (int j = 0; j < p.panels_v; ++j) {
      const int a = i * p.panels_v + j;
      // The side u = u_{i+1} of panel (i, j) is the side u = u_{i+1} of panel (i + 1, j).
      if (i + 1 < p.panels_u)
        seam(a, a + p.panels_v, [m](int t, bool first) { return first ? (m - 1) * m + t : t; });
      if (j + 1 < p.panels_v)
        seam(a, a + 1, [m](int t, bool first) { return first ? t * m + m - 1 : t * m; });
    }
  for (double g : s.gaps) s.mean_gap += g / s.gaps.size(), s.max_gap = std::max(s.max_gap, g);
  for (double k : s.kinks_deg)
    s.mean_kink_deg += k / s.kinks_deg.size(), s.max_kink_deg = std::max(s.max_kink_deg, k);
  return s;
}

}  // namespace

double MoldShape::Height(double x, double y) const { return HeightAndSlope(x, y)[0]; }

Eigen::Vector3d MoldShape::HeightAndSlope(double x, double y) const {
  double m[10], mx[10], my[10];
  Monomials(x / scale, y / scale, m, mx, my);
  Eigen::Vector3d f = Eigen::Vector3d::Zero();
  for (int i = 0; i < 10; ++i) {
    f[0] += coefficients[i] * m[i];
    f[1] += coefficients[i] * mx[i] / scale;
    f[2] += coefficients[i] * my[i] / scale;
  }
  return f;
}

void PanelingOptions::Validate() const {
  if (panels_u < 1 || panels_v < 1)
    throw InputError("--panels: at least 1 x 1 panels (got " + std::to_string(panels_u) + " x " +
                     std::to_string(panels_v) + ")");
  if (static_cast<int64_t>(panels_u) * panels_v > 1000000)
    throw InputError("--panels: at most 1000000 panels (got " + std::to_string(panels_u) + " x " +
                     std::to_string(panels_v) + ")");
  if (molds < 1)
    throw InputError("paneling: at least one mold (got " + std::to_string(molds) + ")");
  if (points_per_side < 3 || points_per_side > 50)
    throw InputError("paneling: 3 to 50 points per panel side (got " +
                     std::to_string(points_per_side) + ")");
  if (fit_rounds < 1)
    throw InputError("paneling: at least one fit round (got " + std::to_string(fit_rounds) + ")");
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
  p.seams = MeasureSeams(panels, p, m);
  return p;
}

int MoldsForTolerance(const BSplineSurface& surface, PanelingOptions options, double max_gap,
                      double max_kink_deg, Paneling* result) {
  auto meets = [&](int molds, Paneling* out) {
    options.molds = molds;
    *out = PanelSurface(surface, options);
    return out->seams.max_gap <= max_gap && out->seams.max_kink_deg <= max_kink_deg;
  };
  const int panels = options.panels_u * options.panels_v;
  Paneling best;
  if (!meets(panels, &best)) {
    if (result) *result = best;
    return -1;
  }
  int lo = 0, hi = panels;  // lo fails (or is 0), hi meets
  while (hi - lo > 1) {
    const int mid = lo + (hi - lo) / 2;
    Paneling trial;
    if (meets(mid, &trial)) {
      hi = mid;
      best = std::move(trial);
    } else {
      lo = mid;
    }
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

}  // namespace gproj
