#include "gproj/problems/mesh/mesh_problem.h"

#include <algorithm>
#include <cmath>
#include <string>

#include "gproj/common/input_error.h"

namespace gproj {

MeshProblem::MeshProblem(const PolyMesh& mesh)
    : input_(mesh), current_(mesh), norm_(MeshNormalization::Of(mesh)) {
  vertex_block_ = problem_.layout().AddBlock("vertices", static_cast<int>(mesh.n_vertices()), 3);
}

void MeshProblem::LoadInputVertices() {
  problem_.ResizeToLayout();
  LoadVertices(input_, norm_, vertex_block_, &problem_);
}

void MeshProblem::AddBoundsAndControl(const PanelBoundsOptions& panels,
                                      const VertexControlOptions& vertices) {
  panels_ = panels;
  bounds_ = AddPanelBounds(input_, norm_, vertex_block_, panels, &problem_);
  control_ = ApplyVertexControl(input_, norm_, vertex_block_, vertices, &problem_);
}

RunReport MeshProblem::Resolve(const std::vector<int>& ids,
                               const std::vector<Eigen::Vector3d>& positions,
                               const RunCallback& callback) {
  if (ids.size() != positions.size())
    throw InputError("resolve: " + std::to_string(ids.size()) + " vertex ids but " +
                     std::to_string(positions.size()) + " positions");
  const int n = static_cast<int>(input_.n_vertices());
  std::vector<bool> seen(n, false);
  for (size_t k = 0; k < ids.size(); ++k) {
    const int v = ids[k];
    if (v < 0 || v >= n)
      throw InputError("resolve: vertex " + std::to_string(v) + " is out of range (the mesh has " +
                       std::to_string(n) + " vertices)");
    if (seen[v]) throw InputError("resolve: vertex " + std::to_string(v) + " is given twice");
    seen[v] = true;
    if (!positions[k].allFinite())
      throw InputError("resolve: the position of vertex " + std::to_string(v) + " is not finite");
  }
  const BlockItems vertex = vertices();
  const VariableLayout& layout = problem_.layout();
  for (size_t k = 0; k < ids.size(); ++k) {
    const int v = ids[k];
    problem_.x().segment<3>(layout.ItemOffset(vertex[v])) = norm_.ToProblem(positions[k]);
    problem_.SetConstant(vertex[v]);
    control_.moved[v] = PolyMesh::Point(positions[k][0], positions[k][1], positions[k][2]);
    control_.held.push_back(v);
  }
  std::sort(control_.held.begin(), control_.held.end());
  control_.held.erase(std::unique(control_.held.begin(), control_.held.end()), control_.held.end());
  SolverOptions options = solver_options();
  options.initial_soft_scale = 0.0;
  return RunWithOptions(options, callback);
}

void MeshProblem::AddEdgeRange(const PolyMesh& mesh, double tolerance, NamedValues* m) const {
  if (!(panels_.min_edge_length > 0.0 || panels_.max_edge_length > 0.0)) return;
  const double slack = tolerance * MeanEdgeLength(mesh);
  const double max = panels_.max_edge_length > 0.0 ? panels_.max_edge_length : INFINITY;
  int outside = 0;
  for (auto e : mesh.edges()) {
    const double length = mesh.calc_edge_length(e);
    outside += length > max + slack || length < panels_.min_edge_length - slack;
  }
  m->push_back({"out_of_range_edges", static_cast<double>(outside)});
}

PolyMesh MeshProblem::Result() const {
  PolyMesh out = input_;
  StoreVertices(problem_, vertex_block_, norm_, &out);
  control_.RestoreHeld(input_, &out);
  return out;
}

const PolyMesh& MeshProblem::MeshAt(const Eigen::VectorXd& x) const {
  StoreVertices(x, problem_.layout(), vertex_block_, norm_, &current_);
  control_.RestoreHeld(input_, &current_);
  return current_;
}

std::vector<int> MeshProblem::FacesAtAngleBound() const {
  StoreVertices(problem_, vertex_block_, norm_, &current_);
  return FacesAtCornerBound(current_, bounds_);
}

std::vector<std::array<int, 2>> MeshProblem::EdgesAtLengthBound() const {
  StoreVertices(problem_, vertex_block_, norm_, &current_);
  return gproj::EdgesAtLengthBound(input_, current_, bounds_);
}

SolverOptions MeshProblem::WithStartSoftScale(SolverOptions solver, double start_residual) {
  solver.fairness_weight *= std::sqrt(StartSoftScale(start_residual, solver.soft_weight_floor));
  return solver;
}

}  // namespace gproj
