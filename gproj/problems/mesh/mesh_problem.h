#pragma once
// The skeleton every mesh problem shares (PQ planarisation, A-nets): the input mesh and its
// normalisation (mean edge 1, centred), a vertex block first in the layout and loaded from the
// input, the panel bounds and vertex control, the iterate as a mesh, and the result in input
// units with held vertices restored exactly. A problem adds its own blocks and families between
// the constructor and AddBoundsAndControl:
//
//   MyProblem(const PolyMesh& mesh, const MyOptions& o) : MeshProblem(mesh) {
//     const int normals = problem_.layout().AddBlock("face_normals", n, 3, true);
//     LoadInputVertices();
//     auto* planarity = problem_.AddFamily<QuadPlanarity>();
//     for (auto f : mesh.faces()) planarity->Add({... vertices()[v] ...});
//     AddBoundsAndControl(o.panels, o.vertices);
//   }

#include <array>
#include <vector>

#include "gproj/geometry/io/mesh_io.h"
#include "gproj/problems/mesh/mesh_variables.h"
#include "gproj/problems/mesh/panel_bounds.h"
#include "gproj/problems/mesh/vertex_control.h"
#include "gproj/problems/run/guided_problem.h"
#include "gproj/solver/problem.h"
#include "gproj/solver/variable_layout.h"

namespace gproj {

class MeshProblem : public GuidedProblem {
 public:
  Problem& problem() override { return problem_; }
  using GuidedProblem::problem;
  // The panel bounds' rows and their bounds (after the set-up).
  const PanelBounds& panel_bounds() const { return bounds_; }

  // The current vertices in input units, held vertices exactly as given.
  PolyMesh Result() const;
  // The iterate last measured (MeasureAt, which every mesh problem computes on MeshAt) as a mesh
  // in input units: inside a RunCallback, the record's iterate.
  const PolyMesh& MeasuredMesh() const { return current_; }
  const PolyMesh& input() const { return input_; }
  // The faces whose corners sit on their angle bound in the current iterate.
  std::vector<int> FacesAtAngleBound() const;
  // The edges of the current iterate on their length bound (vertex pairs).
  std::vector<std::array<int, 2>> EdgesAtLengthBound() const;
  // Whether `m` has no edge outside the asked edge_length range (true when none was asked).
  static bool EdgesInRange(const NamedValues& m) {
    return !(ValueOf(m, "out_of_range_edges") > 0.0);
  }

  // A warm re-solve after an edit (a designer dragging or pinning vertices): holds the vertices
  // `ids` at `positions` (input units; a held vertex may move again), then runs guided
  // projection from the current iterate with the soft and fairness weights off: the iterate
  // moves to the nearest one (in the proximal sense) that meets the constraints with the edit,
  // and the first run's set-up and symbolic analysis are reused. Throws InputError (nothing
  // changed) for an id out of range, a repeated id, a non-finite position or sizes that differ.
  RunReport Resolve(const std::vector<int>& ids, const std::vector<Eigen::Vector3d>& positions,
                    const RunCallback& callback = nullptr);
  // The vertices held now (input ids, sorted).
  const std::vector<int>& held_vertices() const { return control_.held; }

 protected:
  // Normalises `mesh` and adds the vertex block (#V × 3), the layout's first. The derived
  // problem checks the mesh and its options first (a base that throws would name neither).
  explicit MeshProblem(const PolyMesh& mesh);

  // Sizes x to the layout (after the problem's own blocks) and loads the normalised vertices.
  void LoadInputVertices();
  // The panel bounds and the vertex control, after the problem's own families.
  void AddBoundsAndControl(const PanelBoundsOptions& panels, const VertexControlOptions& vertices);
  // The vertices' items: vertices()[v] for a vertex index or handle.
  BlockItems vertices() const { return BlockItems(problem_.layout(), vertex_block_); }
  // x as a mesh in input units with held vertices restored (current_, rewritten in place).
  const PolyMesh& MeshAt(const Eigen::VectorXd& x) const;
  // With an edge_length range asked, adds out_of_range_edges to `m`: the edges of `mesh` (input
  // units) longer than its maximum or shorter than its minimum by more than `tolerance` mean
  // edge lengths (the problem's tolerance, on the scale of its planarity measures).
  void AddEdgeRange(const PolyMesh& mesh, double tolerance, NamedValues* m) const;
  // `solver` with the fairness weight ω_f² scaled by StartSoftScale(start_residual): fairness
  // guides a start far from the target and stays out of the way of one already near it.
  static SolverOptions WithStartSoftScale(SolverOptions solver, double start_residual);

  PolyMesh input_;
  mutable PolyMesh current_;  // the iterate as a mesh (MeshAt)
  MeshNormalization norm_;
  Problem problem_;
  int vertex_block_ = -1;
  PanelBounds bounds_;
  PanelBoundsOptions panels_;
  VertexControl control_;
};

}  // namespace gproj
