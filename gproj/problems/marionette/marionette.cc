#include "gproj/problems/marionette/marionette.h"

#include <Eigen/Cholesky>
#include <Eigen/LU>
#include <algorithm>
#include <cmath>

#include "gproj/common/input_error.h"
#include "gproj/constraints/marionette_planarity.h"
#include "gproj/constraints/scalar_target.h"
#include "gproj/geometry/mesh/quad_grid.h"
#include "gproj/geometry/mesh/scale_free.h"
#include "gproj/problems/mesh/panel_bounds.h"

namespace gproj::marionette {

MarionettePlan MakeMarionettePlan(const PolyMesh& mesh, const std::string& path) {
  const std::string prefix = path.empty() ? "" : path + ": ";
  MarionettePlan plan;
  const GridShape shape = DetectGridShape(mesh, path);
  plan.rows = shape.rows;
  plan.cols = shape.cols;
  for (auto vh : mesh.vertices()) {
    const auto& p = mesh.point(vh);
    plan.xy.emplace_back(p[0], p[1]);
  }
  for (int i = 0; i < plan.rows; ++i)
    for (int j = 0; j < plan.cols; ++j) {
      double alpha = 0.0, beta = 0.0;
      if (!MarionettePlanarity::PlanCoefficients(
              plan.xy[plan.Vertex(i, j)], plan.xy[plan.Vertex(i + 1, j)],
              plan.xy[plan.Vertex(i + 1, j + 1)], plan.xy[plan.Vertex(i, j + 1)], &alpha, &beta))
        throw InputError(prefix + "face " + std::to_string(i * plan.cols + j) +
                         " has a degenerate plan view: its vertices " +
                         std::to_string(plan.Vertex(i, j)) + ", " +
                         std::to_string(plan.Vertex(i + 1, j)) + " and " +
                         std::to_string(plan.Vertex(i, j + 1)) +
                         " are collinear in x, y, so its height cannot be propagated");
      plan.alpha.push_back(alpha);
      plan.beta.push_back(beta);
    }
  return plan;
}

std::vector<int> FoldedPlanFaces(const PolyMesh& mesh) {
  // Per quad: the signs of its four corners' xy cross products.
  std::vector<int> orientation(mesh.n_faces(), 0);  // +1, −1, or 0 when mixed (not convex)
  int positive = 0, negative = 0;
  for (auto f : mesh.faces()) {
    if (mesh.valence(f) != 4) continue;
    Eigen::Vector3d q[4];  // the plan quad at unit extent (any finite scale)
    int k = 0;
    for (auto v : mesh.fv_range(f)) q[k++] = Eigen::Vector3d(mesh.point(v)[0], mesh.point(v)[1], 0);
    NormalizePolygon(q, 4);
    Eigen::Vector2d p[4];
    for (k = 0; k < 4; ++k) p[k] = q[k].head<2>();
    int plus = 0, minus = 0;
    bool degenerate = false;  // collinear corners: refused with their own message
    for (int i = 0; i < 4; ++i) {
      const Eigen::Vector2d a = p[(i + 1) % 4] - p[i], b = p[(i + 3) % 4] - p[i];
      const double cross = a.x() * b.y() - a.y() * b.x();
      degenerate = degenerate || std::abs(cross) <= 1e-12 * a.norm() * b.norm();
      plus += cross > 0.0 ? 1 : 0;
      minus += cross < 0.0 ? 1 : 0;
    }
    orientation[f.idx()] = degenerate ? 2 : (plus == 4 ? 1 : (minus == 4 ? -1 : 0));
    positive += plus == 4 ? 1 : 0;
    negative += minus == 4 ? 1 : 0;
  }
  const int majority = positive >= negative ? 1 : -1;
  std::vector<int> folded;
  for (auto f : mesh.faces())
    if (mesh.valence(f) == 4 && orientation[f.idx()] != majority && orientation[f.idx()] != 2)
      folded.push_back(f.idx());
  return folded;
}

std::string CheckPlanView(const PolyMesh& mesh, const std::string& path, bool allow) {
  const std::vector<int> folded = FoldedPlanFaces(mesh);
  if (folded.empty()) return "";
  const std::string what =
      std::to_string(folded.size()) +
      " quads of the plan view overlap or are not convex in x, y: " + FaceList(folded);
  if (!allow)
    throw InputError((path.empty() ? "" : path + ": ") + what +
                     " (a lift over them folds; `allow_folded_plan` lifts it anyway)");
  return "warning: " + what + "; the lift over them folds\n";
}

Eigen::VectorXd LiftMarionette(const MarionettePlan& plan, const Eigen::VectorXd& row,
                               const Eigen::VectorXd& column) {
  if (row.size() != plan.cols + 1 || column.size() != plan.rows + 1)
    throw InputError("guide curves need " + std::to_string(plan.cols + 1) + " row heights and " +
                     std::to_string(plan.rows + 1) + " column heights, got " +
                     std::to_string(row.size()) + " and " + std::to_string(column.size()));
  if (std::abs(row[0] - column[0]) > 1e-12 * (1.0 + std::abs(row[0])))
    throw InputError("incompatible guide curves: they share vertex 0 but give it heights " +
                     std::to_string(row[0]) + " and " + std::to_string(column[0]));
  Eigen::VectorXd z(plan.num_vertices());
  for (int j = 0; j <= plan.cols; ++j) z[plan.Vertex(0, j)] = row[j];
  for (int i = 0; i <= plan.rows; ++i) z[plan.Vertex(i, 0)] = column[i];
  for (int i = 0; i < plan.rows; ++i)
    for (int j = 0; j < plan.cols; ++j) {
      const int f = i * plan.cols + j;
      const double za = z[plan.Vertex(i, j)];
      z[plan.Vertex(i + 1, j + 1)] = za + plan.alpha[f] * (z[plan.Vertex(i + 1, j)] - za) +
                                     plan.beta[f] * (z[plan.Vertex(i, j + 1)] - za);
    }
  return z;
}

Eigen::MatrixXd MarionetteGuideMatrix(const MarionettePlan& plan) {
  const int guides = plan.rows + plan.cols + 1;
  Eigen::MatrixXd a(plan.num_vertices(), guides);
  for (int k = 0; k < guides; ++k) {
    Eigen::VectorXd row = Eigen::VectorXd::Zero(plan.cols + 1),
                    column = Eigen::VectorXd::Zero(plan.rows + 1);
    if (k <= plan.cols) {
      row[k] = 1.0;
      if (k == 0) column[0] = 1.0;
    } else {
      column[k - plan.cols] = 1.0;
    }
    a.col(k) = LiftMarionette(plan, row, column);
  }
  return a;
}

Eigen::MatrixXd MarionettePlanarityMatrix(const MarionettePlan& plan) {
  Eigen::MatrixXd p = Eigen::MatrixXd::Zero(plan.rows * plan.cols, plan.num_vertices());
  for (int i = 0; i < plan.rows; ++i)
    for (int j = 0; j < plan.cols; ++j) {
      const int f = i * plan.cols + j;
      p(f, plan.Vertex(i, j)) = -1.0 + plan.alpha[f] + plan.beta[f];
      p(f, plan.Vertex(i + 1, j)) = -plan.alpha[f];
      p(f, plan.Vertex(i + 1, j + 1)) = 1.0;
      p(f, plan.Vertex(i, j + 1)) = -plan.beta[f];
    }
  return p;
}

Problem MakeMarionetteProblem(const MarionettePlan& plan, const std::vector<MarionetteTarget>& hard,
                              const std::vector<MarionetteTarget>& soft, double hard_weight,
                              double soft_weight) {
  Problem problem;
  const int block = problem.layout().AddBlock("heights", plan.num_vertices(), 1);
  problem.ResizeToLayout();
  problem.x().setZero();
  const BlockItems height(problem.layout(), block);
  auto* planarity = problem.AddFamily<MarionettePlanarity>(1.0);
  for (int i = 0; i < plan.rows; ++i)
    for (int j = 0; j < plan.cols; ++j) {
      const int f = i * plan.cols + j;
      planarity->AddQuad(height[plan.Vertex(i, j)], height[plan.Vertex(i + 1, j)],
                         height[plan.Vertex(i + 1, j + 1)], height[plan.Vertex(i, j + 1)],
                         plan.alpha[f], plan.beta[f]);
    }
  if (!hard.empty()) {
    auto* guides =
        problem.AddFamily<ScalarTarget>("prescribed_heights", FamilyRole::kConstraint, hard_weight);
    for (const auto& t : hard) guides->AddTarget(height[t.vertex], t.height);
  }
  if (!soft.empty()) {
    auto* target =
        problem.AddFamily<ScalarTarget>("target_heights", FamilyRole::kSoft, soft_weight);
    for (const auto& t : soft) target->AddTarget(height[t.vertex], t.height);
  }
  return problem;
}

SolverOptions MarionetteSolverOptions() {
  SolverOptions options;
  options.max_iterations = 1;
  options.epsilon = 1e-9;
  options.residual_tolerance = 0.0;
  options.step_tolerance = 0.0;
  options.eliminate_auxiliaries = false;
  return options;
}

namespace {

// z_{i+1}* = α_i z_i* + (1 − α_i − β_i) Z_i + β_i Z_{i+1} for quad (A, B, C, D) = (P_i, Q_i,
// Q_{i+1}, P_{i+1}); returns z_N*.
double PropagateStrip(const std::vector<double>& alpha, const std::vector<double>& beta,
                      const Eigen::VectorXd& z, double outer0, Eigen::VectorXd* outer) {
  const int n = static_cast<int>(alpha.size());
  double q = outer0;
  for (int i = 0; i < n; ++i) {
    if (outer != nullptr) (*outer)[i] = q;
    q = alpha[i] * q + (1.0 - alpha[i] - beta[i]) * z[i] + beta[i] * z[(i + 1) % n];
  }
  return q;
}

// α_i, β_i of every quad (P_i, Q_i, Q_{i+1}, P_{i+1}); returns the first degenerate quad or −1.
int StripCoefficients(const ClosedStrip& strip, std::vector<double>* alpha,
                      std::vector<double>* beta) {
  const int n = static_cast<int>(strip.inner.size());
  alpha->assign(n, 0.0);
  beta->assign(n, 0.0);
  for (int i = 0; i < n; ++i)
    if (!MarionettePlanarity::PlanCoefficients(strip.inner[i], strip.outer[i],
                                               strip.outer[(i + 1) % n], strip.inner[(i + 1) % n],
                                               &(*alpha)[i], &(*beta)[i]))
      return i;
  return -1;
}

}  // namespace

int DegenerateClosedStripQuad(const ClosedStrip& strip) {
  std::vector<double> alpha, beta;
  return StripCoefficients(strip, &alpha, &beta);
}

ClosedStripLift LiftClosedStrip(const ClosedStrip& strip, const Eigen::VectorXd& inner_heights,
                                double outer0_when_free, double tolerance) {
  const int n = static_cast<int>(strip.inner.size());
  if (n < 3 || static_cast<int>(strip.outer.size()) != n || inner_heights.size() != n)
    throw InputError(
        "a closed strip needs inner and outer curves of the same length (≥ 3) and one "
        "height per inner vertex");
  std::vector<double> alpha, beta;
  const int i = StripCoefficients(strip, &alpha, &beta);
  if (i >= 0)
    throw InputError("quad " + std::to_string(i) +
                     " of the closed strip has a degenerate plan view (inner " + std::to_string(i) +
                     ", outer " + std::to_string(i) + " and inner " + std::to_string((i + 1) % n) +
                     " are collinear)");
  ClosedStripLift out;
  // z_N* is linear in (Z, z_0*): a from (0, 1), V_k from (e_k, 0).
  out.a = PropagateStrip(alpha, beta, Eigen::VectorXd::Zero(n), 1.0, nullptr);
  out.v.resize(n);
  for (int k = 0; k < n; ++k)
    out.v[k] = PropagateStrip(alpha, beta, Eigen::VectorXd::Unit(n, k), 0.0, nullptr);
  out.a_is_one = std::abs(out.a - 1.0) <= tolerance;
  out.inner_heights = inner_heights;
  double outer0 = outer0_when_free;
  if (out.a_is_one) {
    // V = 0 (e.g. concentric circles) leaves every inner curve free.
    if (out.v.norm() > tolerance)
      out.inner_heights -= (out.v.dot(inner_heights) / out.v.squaredNorm()) * out.v;
  } else {
    outer0 = out.v.dot(inner_heights) / (1.0 - out.a);
  }
  out.outer_heights.resize(n);
  PropagateStrip(alpha, beta, out.inner_heights, outer0, &out.outer_heights);
  return out;
}

PolyMesh ClosedStripMesh(const ClosedStrip& strip, const ClosedStripLift& lift) {
  const int n = static_cast<int>(strip.inner.size());
  PolyMesh out;
  std::vector<PolyMesh::VertexHandle> inner, outer;
  for (int i = 0; i < n; ++i)
    inner.push_back(
        out.add_vertex({strip.inner[i].x(), strip.inner[i].y(), lift.inner_heights[i]}));
  for (int i = 0; i < n; ++i)
    outer.push_back(
        out.add_vertex({strip.outer[i].x(), strip.outer[i].y(), lift.outer_heights[i]}));
  for (int i = 0; i < n; ++i) {
    const int k = (i + 1) % n;
    out.add_face({inner[i], outer[i], outer[k], inner[k]});
  }
  return out;
}

Eigen::VectorXd FitMarionette(const MarionettePlan& plan, const Eigen::VectorXd& z0) {
  const Eigen::MatrixXd a = MarionetteGuideMatrix(plan);  // 002 eq. 14
  return a * (a.transpose() * a).ldlt().solve(a.transpose() * z0);
}

Eigen::RowVectorXd MarionetteVolumeRow(const MarionettePlan& plan) {
  Eigen::RowVectorXd row = Eigen::RowVectorXd::Zero(plan.num_vertices());
  double total = 0.0;
  auto triangle = [&](int a, int b, int c) {
    const Eigen::Vector2d ab = plan.xy[b] - plan.xy[a], ac = plan.xy[c] - plan.xy[a];
    const double area = 0.5 * (ab.x() * ac.y() - ab.y() * ac.x());
    total += area;
    for (int v : {a, b, c}) row[v] += area / 3.0;
  };
  for (int i = 0; i < plan.rows; ++i)
    for (int j = 0; j < plan.cols; ++j) {
      const int a = plan.Vertex(i, j), b = plan.Vertex(i + 1, j), c = plan.Vertex(i + 1, j + 1),
                d = plan.Vertex(i, j + 1);
      triangle(a, b, c);
      triangle(a, c, d);
    }
  return total < 0.0 ? Eigen::RowVectorXd(-row) : row;
}

namespace {

// The KKT system of the fit min ½ gᵀ H g − bᵀ g with the equality rows `rows` = `values` and
// the heights of the `active` vertices (rows of A) at max_height: the guide heights g, then
// the multipliers. Throws InputError when the system is singular or its constraints
// contradict each other.
Eigen::VectorXd SolveFitKkt(const Eigen::MatrixXd& h, const Eigen::VectorXd& b,
                            const Eigen::MatrixXd& a, const std::vector<Eigen::RowVectorXd>& rows,
                            const std::vector<double>& values, const std::vector<int>& active,
                            double max_height, bool first_round) {
  const int g = static_cast<int>(a.cols());
  const int fixed = static_cast<int>(rows.size());
  const int m = fixed + static_cast<int>(active.size());
  Eigen::MatrixXd kkt = Eigen::MatrixXd::Zero(g + m, g + m);
  Eigen::VectorXd rhs(g + m);
  kkt.topLeftCorner(g, g) = h;
  rhs.head(g) = b;
  for (int r = 0; r < m; ++r) {
    const Eigen::RowVectorXd row =
        r < fixed ? rows[r] : Eigen::RowVectorXd(a.row(active[r - fixed]));
    kkt.block(g + r, 0, 1, g) = row;
    kkt.block(0, g + r, g, 1) = row.transpose();
    rhs[g + r] = r < fixed ? values[r] : max_height;
  }
  const Eigen::FullPivLU<Eigen::MatrixXd> lu(kkt);
  if (lu.rank() < g + m) {
    if (first_round || active.empty())
      throw InputError(
          "the fit's targets and hard constraints do not determine the lift: " +
          std::to_string(g + m - lu.rank()) + " of its " + std::to_string(g) +
          " guide heights stay free, or constraints repeat each other (give targets at more "
          "vertices or fewer constraints)");
    throw InputError("the max height contradicts the prescribed heights or volume");
  }
  const Eigen::VectorXd solution = lu.solve(rhs);
  if ((kkt * solution - rhs).norm() > 1e-8 * (rhs.norm() + 1.0))
    throw InputError("the hard constraints contradict each other");
  return solution;
}

}  // namespace

Eigen::VectorXd FitMarionette(const MarionettePlan& plan, const Eigen::VectorXd& z0,
                              const Eigen::VectorXd& weights,
                              const MarionetteConstraints& constraints) {
  const int n = plan.num_vertices();
  if (z0.size() != n || weights.size() != n)
    throw InputError("the fit needs one target height and one weight per vertex (" +
                     std::to_string(n) + ")");
  for (const auto& [v, z] : constraints.heights)
    if (v < 0 || v >= n || !std::isfinite(z))
      throw InputError("prescribed height at vertex " + std::to_string(v) +
                       ": no such vertex or not finite (the plan has " + std::to_string(n) +
                       " vertices)");
  const Eigen::MatrixXd a = MarionetteGuideMatrix(plan);
  const int g = static_cast<int>(a.cols());
  const Eigen::MatrixXd h = a.transpose() * weights.asDiagonal() * a;
  const Eigen::VectorXd b = a.transpose() * (weights.array() * z0.array()).matrix();
  // Equality rows over z: the prescribed heights, the volume; then the active bounds.
  std::vector<Eigen::RowVectorXd> rows;
  std::vector<double> values;
  for (const auto& [v, z] : constraints.heights) {
    rows.push_back(a.row(v));
    values.push_back(z);
  }
  if (constraints.with_volume) {
    rows.push_back(MarionetteVolumeRow(plan) * a);
    values.push_back(constraints.volume);
  }
  const int fixed = static_cast<int>(rows.size());
  std::vector<int> active;  // vertices held at the max height
  const double scale = 1.0 + z0.cwiseAbs().maxCoeff() + std::abs(constraints.max_height);
  for (int round = 0; round <= 2 * n + 2; ++round) {
    const Eigen::VectorXd solution =
        SolveFitKkt(h, b, a, rows, values, active, constraints.max_height, round == 0);
    const Eigen::VectorXd z = a * solution.head(g);
    if (!constraints.with_max_height) return z;
    // Release the active bound with the most negative multiplier, else add the worst violation.
    int leave = -1;
    double most_negative = -1e-12 * scale;
    for (size_t k = 0; k < active.size(); ++k)
      if (solution[g + fixed + k] < most_negative) {
        most_negative = solution[g + fixed + k];
        leave = static_cast<int>(k);
      }
    if (leave >= 0) {
      active.erase(active.begin() + leave);
      continue;
    }
    int worst = -1;
    double excess = 1e-12 * scale;
    for (int v = 0; v < n; ++v)
      if (z[v] - constraints.max_height > excess &&
          std::find(active.begin(), active.end(), v) == active.end()) {
        excess = z[v] - constraints.max_height;
        worst = v;
      }
    if (worst < 0) return z;
    active.push_back(worst);
  }
  throw InputError("the max height could not be met (the active set did not settle)");
}

}  // namespace gproj::marionette
