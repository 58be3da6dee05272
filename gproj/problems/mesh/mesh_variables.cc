#include "gproj/problems/mesh/mesh_variables.h"

#include <Eigen/Geometry>
#include <algorithm>
#include <cassert>
#include <utility>
#include <vector>

#include "gproj/constraints/polyline_fairness.h"
#include "gproj/constraints/umbrella_fairness.h"

namespace gproj {

MeshNormalization MeshNormalization::Of(const PolyMesh& mesh) {
  MeshNormalization n;
  for (auto v : mesh.vertices()) n.center += ToEigen(mesh.point(v));
  if (mesh.n_vertices() > 0) n.center /= static_cast<double>(mesh.n_vertices());
  const double mean = MeanEdgeLength(mesh);
  n.scale = mean > 0.0 ? 1.0 / mean : 1.0;
  return n;
}

double MaxDisplacement(const PolyMesh& mesh, const PolyMesh& reference) {
  assert(mesh.n_vertices() == reference.n_vertices() && "vertex-by-vertex displacement");
  Eigen::AlignedBox3d box;
  for (auto v : reference.vertices()) box.extend(ToEigen(reference.point(v)));
  const double diagonal = box.diagonal().stableNorm();
  double worst = 0.0;
  for (auto v : mesh.vertices())
    worst = std::max(worst, (ToEigen(mesh.point(v)) - ToEigen(reference.point(v))).stableNorm());
  return diagonal > 0.0 ? worst / diagonal : worst;
}

void LoadVertices(const PolyMesh& mesh, const MeshNormalization& norm, int vertex_block,
                  Problem* problem) {
  const VariableLayout& layout = problem->layout();
  for (auto v : mesh.vertices())
    problem->x().segment<3>(layout.Index(vertex_block, v.idx(), 0)) =
        norm.ToProblem(ToEigen(mesh.point(v)));
}

void StoreVertices(const Eigen::VectorXd& x, const VariableLayout& layout, int vertex_block,
                   const MeshNormalization& norm, PolyMesh* mesh) {
  for (auto v : mesh->vertices()) {
    const Eigen::Vector3d p =
        norm.FromProblem(x.segment<3>(layout.Index(vertex_block, v.idx(), 0)));
    mesh->set_point(v, PolyMesh::Point(p[0], p[1], p[2]));
  }
}

int AddMeshFairness(const PolyMesh& mesh, int order, int vertex_block, Problem* problem) {
  const VariableLayout& layout = problem->layout();
  auto* fairness = problem->AddFamily<PolylineFairness>(order, 3);
  const BlockItems vertex(layout, vertex_block);
  const int umbrellas = AddUmbrellaFairness(mesh, vertex_block, problem);
  if (order == 2) {
    ForEachPolylineTriple(mesh, [&](int a, int b, int c) {
      fairness->AddElement({vertex[a], vertex[b], vertex[c]});
    });
    return fairness->num_elements() + umbrellas;
  }
  // Third differences: extend each triple (a, b, c) by the vertex d beyond c when the
  // polyline continues through c.
  std::vector<std::vector<std::pair<int, int>>> through(mesh.n_vertices());
  ForEachPolylineTriple(mesh, [&](int a, int b, int c) { through[b].emplace_back(a, c); });
  for (size_t b = 0; b < through.size(); ++b) {
    for (const auto& [a, c] : through[b]) {
      for (const auto& [p, q] : through[c]) {
        if (p != static_cast<int>(b) && q != static_cast<int>(b)) continue;
        const int d = p == static_cast<int>(b) ? q : p;
        fairness->AddElement({vertex[a], vertex[static_cast<int>(b)], vertex[c], vertex[d]});
      }
    }
  }
  return fairness->num_elements() + umbrellas;
}

int AddUmbrellaFairness(const PolyMesh& mesh, int vertex_block, Problem* problem) {
  std::vector<char> on_polyline(mesh.n_vertices(), 0);
  ForEachPolylineTriple(mesh, [&](int, int b, int) { on_polyline[b] = 1; });
  std::vector<std::vector<int>> elements;
  const BlockItems vertex(problem->layout(), vertex_block);
  for (auto v : mesh.vertices()) {
    if (mesh.is_boundary(v) || on_polyline[v.idx()] || mesh.valence(v) < 3) continue;
    bool polygon = false;
    for (auto f : mesh.vf_range(v)) polygon = polygon || mesh.valence(f) != 4;
    if (!polygon) continue;
    std::vector<int> items = {vertex[v.idx()]};
    for (auto w : mesh.vv_range(v)) items.push_back(vertex[w.idx()]);
    elements.push_back(std::move(items));
  }
  if (elements.empty()) return 0;
  auto* umbrella = problem->AddFamily<UmbrellaFairness>(3);
  for (const std::vector<int>& items : elements) umbrella->AddElement(items);
  return umbrella->num_elements();
}

}  // namespace gproj
