#include "local_global_planarizer.h"

#include <Eigen/Eigenvalues>
#include <Eigen/SparseCore>
#include <stdexcept>
#include <string>

#include "gproj/geometry/mesh/quad_shape.h"
#include "gproj/solver/sparse_cholesky.h"

namespace gproj {

struct LocalGlobalPlanarizer::Factor {
  std::unique_ptr<SparseCholesky> cholesky;
};

LocalGlobalPlanarizer::LocalGlobalPlanarizer(const PolyMesh& mesh, double closeness_weight)
    : closeness_weight_(closeness_weight), factor_(std::make_unique<Factor>()) {
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
}

LocalGlobalPlanarizer::~LocalGlobalPlanarizer() = default;

void LocalGlobalPlanarizer::Iterate() {
  rhs_ = closeness_weight_ * v0_;
  for (const auto& q : quads_) {
    Eigen::Matrix<double, 4, 3> p;
    for (int k = 0; k < 4; ++k) p.row(k) = v_.row(q[k]);
    p.rowwise() -= p.colwise().mean();
    const Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d> eig(p.transpose() * p);
    const Eigen::Vector3d normal = eig.eigenvectors().col(0);  // smallest eigenvalue
    p -= (p * normal) * normal.transpose();
    for (int k = 0; k < 4; ++k) rhs_.row(q[k]) += p.row(k);
  }
  std::string message;
  for (int c = 0; c < 3; ++c) {
    column_ = rhs_.col(c);
    if (!factor_->cholesky->Solve(column_.data(), solved_.data(), &message))
      throw std::runtime_error("LocalGlobalPlanarizer: " + message);
    v_.col(c) = solved_;
  }
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
