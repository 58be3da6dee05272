#include "local_global_planarizer.h"

#include <Eigen/Eigenvalues>
#include <Eigen/SparseCore>
#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <string>

#include "gproj/geometry/mesh/quad_shape.h"
#include "gproj/solver/sparse_cholesky.h"

namespace gproj {

struct LocalGlobalPlanarizer::Factor {
  std::unique_ptr<SparseCholesky> cholesky;
};

LocalGlobalPlanarizer::LocalGlobalPlanarizer(const PolyMesh& mesh, double closeness_weight,
                                             int anderson_depth)
    : closeness_weight_(closeness_weight),
      factor_(std::make_unique<Factor>()),
      depth_(anderson_depth) {
  const int n = static_cast<int>(mesh.n_vertices());
  v0_.resize(n, 3);
  for (const auto vh : mesh.vertices()) {
    const auto& p = mesh.point(vh);
    v0_.row(vh.idx()) << p[0], p[1], p[2];
  }
  v_ = v0_;
  rhs_.resize(n, 3);
  column_.resize(n);
  solved_.resize(n);
  for (const auto eh : mesh.edges()) {
    const auto heh = mesh.halfedge_handle(eh, 0);
    edges_.emplace_back(mesh.from_vertex_handle(heh).idx(), mesh.to_vertex_handle(heh).idx());
  }
  std::vector<Eigen::Triplet<double>> triplets;
  for (const auto fh : mesh.faces()) {
    std::array<int, 4> q{};
    int k = 0;
    for (const auto vh : mesh.fv_range(fh)) {
      if (k == 4) throw std::invalid_argument("LocalGlobalPlanarizer: a face is not a quad");
      q[k++] = vh.idx();
    }
    if (k != 4) throw std::invalid_argument("LocalGlobalPlanarizer: a face is not a quad");
    quads_.push_back(q);
    for (int a = 0; a < 4; ++a)
      for (int b = 0; b < 4; ++b)
        if (q[a] <= q[b]) triplets.emplace_back(q[a], q[b], (a == b ? 1.0 : 0.0) - 0.25);
  }
  Eigen::SparseMatrix<double> upper(n, n);  // Σ_f S_fᵀ (I − ¼ 11ᵀ) S_f, upper triangle
  upper.setFromTriplets(triplets.begin(), triplets.end());
  upper.makeCompressed();
  const CscMatrix m = ToCsc(upper);
  factor_->cholesky = CreateSparseCholesky(LinearSolverType::kCholmod, 0);
  std::string message;
  if (!factor_->cholesky->Analyze(m, MatrixForm::kSymmetric, &message) ||
      !factor_->cholesky->Factorize(m, closeness_weight_, &message))
    throw std::runtime_error("LocalGlobalPlanarizer: " + message);
  energy_ = LocalStep(v_);
  if (depth_ > 0) {  // every buffer of an Anderson step, allocated once
    image_.resize(n, 3);
    candidate_.resize(n, 3);
    residual_.resize(3 * n);
    last_image_.resize(3 * n);
    last_residual_.resize(3 * n);
    image_changes_.resize(3 * n, depth_);
    residual_changes_.resize(3 * n, depth_);
  }
}

LocalGlobalPlanarizer::~LocalGlobalPlanarizer() = default;

double LocalGlobalPlanarizer::LocalStep(const Eigen::MatrixX3d& x) {
  rhs_ = closeness_weight_ * v0_;
  double energy = closeness_weight_ * (x - v0_).squaredNorm();
  for (const auto& q : quads_) {
    Eigen::Matrix<double, 4, 3> p;
    for (int k = 0; k < 4; ++k) p.row(k) = x.row(q[k]);
    p.rowwise() -= p.colwise().mean();
    Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d> eig;
    eig.computeDirect(p.transpose() * p);
    const Eigen::Vector3d normal = eig.eigenvectors().col(0);  // smallest eigenvalue
    const Eigen::Vector4d off = p * normal;  // distances to the plane (accurate near planarity,
    energy += off.squaredNorm();             // unlike the eigenvalue itself)
    p -= off * normal.transpose();
    for (int k = 0; k < 4; ++k) rhs_.row(q[k]) += p.row(k);
  }
  return energy;
}

void LocalGlobalPlanarizer::GlobalStep(Eigen::MatrixX3d* x) {
  std::string message;
  for (int c = 0; c < 3; ++c) {
    column_ = rhs_.col(c);
    if (!factor_->cholesky->Solve(column_.data(), solved_.data(), &message))
      throw std::runtime_error("LocalGlobalPlanarizer: " + message);
    x->col(c) = solved_;
  }
}

void LocalGlobalPlanarizer::Iterate() {
  if (depth_ > 0) return IterateAnderson();
  GlobalStep(&v_);
  if (!v_.allFinite()) throw std::runtime_error("LocalGlobalPlanarizer: a step is not finite");
  energy_ = LocalStep(v_);
}

void LocalGlobalPlanarizer::IterateAnderson() {
  GlobalStep(&image_);  // G(v_): rhs_ holds v_'s local step
  if (!image_.allFinite()) throw std::runtime_error("LocalGlobalPlanarizer: a step is not finite");
  const Eigen::Map<const Eigen::VectorXd> g(image_.data(), image_.size());
  const Eigen::Map<const Eigen::VectorXd> x(v_.data(), v_.size());
  residual_ = g - x;
  if (has_last_) {
    image_changes_.col(next_column_) = g - last_image_;
    residual_changes_.col(next_column_) = residual_ - last_residual_;
    next_column_ = (next_column_ + 1) % depth_;
    history_ = std::min(history_ + 1, depth_);
  }
  last_image_ = g;
  last_residual_ = residual_;
  has_last_ = true;
  candidate_ = image_;
  if (history_ > 0) {
    // θ = argmin ‖f − ΔF θ‖ by the normal equations (m ≤ a few columns), lightly regularised.
    const auto df = residual_changes_.leftCols(history_);
    Eigen::MatrixXd normal = df.transpose() * df;
    normal.diagonal().array() += 1e-10 * normal.diagonal().maxCoeff() + 1e-300;
    const Eigen::VectorXd theta = normal.ldlt().solve(df.transpose() * residual_);
    Eigen::Map<Eigen::VectorXd>(candidate_.data(), candidate_.size()).noalias() -=
        image_changes_.leftCols(history_) * theta;
  }
  const double energy = candidate_.allFinite() ? LocalStep(candidate_) : HUGE_VAL;
  if (history_ == 0 || energy < energy_) {
    v_.swap(candidate_);
    energy_ = energy;
    accepted_ += history_ > 0;
    return;
  }
  ++rejected_;
  v_.swap(image_);  // the plain step: its energy is not above the last accepted one
  energy_ = LocalStep(v_);
  history_ = 0;
  next_column_ = 0;
  has_last_ = false;
}

double LocalGlobalPlanarizer::MaxPlanarity() const {
  double worst = 0.0, edges = 0.0;
  for (const auto& q : quads_) {
    const Eigen::Vector3d a = v_.row(q[0]), b = v_.row(q[1]), c = v_.row(q[2]), d = v_.row(q[3]);
    worst = std::max(worst, DiagonalDistance(a, b, c, d));
  }
  for (const auto& [i, j] : edges_) edges += (v_.row(i) - v_.row(j)).norm();
  return edges_.empty() ? 0.0 : worst / (edges / edges_.size());
}

}  // namespace gproj
