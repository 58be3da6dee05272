#pragma once
// Shared plumbing of mesh problems: the similarity that centres a mesh and scales it to mean
// edge length 1 (weights then do not depend on units), copying vertices in and out of x, and
// the fairness polylines of a quad mesh.

#include <Eigen/Core>

#include "gproj/geometry/io/mesh_io.h"
#include "gproj/geometry/mesh/scale_free.h"
#include "gproj/solver/guided_projection.h"
#include "gproj/solver/problem.h"

namespace gproj {

struct MeshNormalization {
  Eigen::Vector3d center = Eigen::Vector3d::Zero();
  double scale = 1.0;  // problem = (input − center) * scale

  static MeshNormalization Of(const PolyMesh& mesh);
  Eigen::Vector3d ToProblem(const Eigen::Vector3d& p) const { return (p - center) * scale; }
  Eigen::Vector3d FromProblem(const Eigen::Vector3d& q) const { return q / scale + center; }
};

inline Eigen::Vector3d ToEigen(const PolyMesh::Point& p) { return {p[0], p[1], p[2]}; }

// Max vertex displacement between two meshes of one connectivity / bbox diagonal of `reference`.
double MaxDisplacement(const PolyMesh& mesh, const PolyMesh& reference);

// x[vertex block] = normalised mesh vertices.
void LoadVertices(const PolyMesh& mesh, const MeshNormalization& norm, int vertex_block,
                  Problem* problem);
// mesh vertices = x[vertex block] in input units.
void StoreVertices(const Eigen::VectorXd& x, const VariableLayout& layout, int vertex_block,
                   const MeshNormalization& norm, PolyMesh* mesh);
inline void StoreVertices(const Problem& problem, int vertex_block, const MeshNormalization& norm,
                          PolyMesh* mesh) {
  StoreVertices(problem.x(), problem.layout(), vertex_block, norm, mesh);
}

// Calls visit(a, b, c) for every triple of consecutive vertices on a mesh polyline through a
// regular vertex b: at an inner valence-4 vertex the two pairs of opposite neighbours, at a
// boundary vertex of valence 3 its two boundary neighbours.
template <typename Visit>
void ForEachPolylineTriple(const PolyMesh& mesh, Visit visit) {
  for (auto v : mesh.vertices()) {
    if (mesh.is_boundary(v)) {
      if (mesh.valence(v) != 3) continue;
      const auto out = mesh.halfedge_handle(v);
      const auto next = mesh.to_vertex_handle(out);
      const auto prev = mesh.from_vertex_handle(mesh.prev_halfedge_handle(out));
      visit(prev.idx(), v.idx(), next.idx());
    } else if (mesh.valence(v) == 4) {
      int ring[4], k = 0;
      for (auto w : mesh.vv_range(v)) ring[k++] = w.idx();
      visit(ring[0], v.idx(), ring[2]);
      visit(ring[1], v.idx(), ring[3]);
    }
  }
}

// Adds a PolylineFairness family of the given order (2 or 3) over the mesh polylines, and
// AddUmbrellaFairness; returns their number of elements.
int AddMeshFairness(const PolyMesh& mesh, int order, int vertex_block, Problem* problem);

// Umbrella rows (constraints/umbrella_fairness.h) at the inner vertices that no mesh polyline
// passes through and that touch a face other than a quad: the valence-3 vertices of hexagonal
// meshes, which have no polyline to be fair along. Quad meshes get none (their singular vertices
// stay free as before). Adds the family only when there are such vertices; returns their count.
int AddUmbrellaFairness(const PolyMesh& mesh, int vertex_block, Problem* problem);

}  // namespace gproj
