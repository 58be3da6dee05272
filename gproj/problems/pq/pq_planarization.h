#pragma once
// PQ planarisation: every face of a quad mesh planar, the shape kept by closeness to the
// input and fairness along the mesh polylines (docs/method.md; 004 §3.2). The mesh is centred and
// scaled to mean edge length 1 inside the problem, so weights do not depend on units.

#include <functional>
#include <memory>
#include <string>

#include "gproj/geometry/io/mesh_io.h"
#include "gproj/geometry/render/face_colours.h"
#include "gproj/problems/mesh/mesh_problem.h"
#include "gproj/problems/mesh/mesh_variables.h"
#include "gproj/problems/mesh/panel_bounds.h"
#include "gproj/problems/mesh/planarity_measures.h"
#include "gproj/problems/mesh/vertex_control.h"
#include "gproj/problems/run/guided_problem.h"
#include "gproj/problems/run/report_json.h"
#include "gproj/solver/ceres_adapter.h"
#include "gproj/solver/guided_projection.h"
#include "gproj/solver/problem.h"

namespace gproj::pq {

// Guided projection's defaults for planarisation: 30 iterations, ω_f = 1, soft weights fading
// by 0.1 per iteration down to 1e-12, monotone steps (an under-determined Gauss–Newton step
// would otherwise jump once the soft weights have faded); the planarity measure (not a row
// residual) decides convergence.
SolverOptions PQPlanarizationSolverDefaults();

struct PQPlanarizationOptions {
  // Guided projection (ω_f = solver.fairness_weight weighs the second-difference fairness).
  SolverOptions solver = PQPlanarizationSolverDefaults();
  double planarity_weight = 1.0;  // weight of the planarity rows
  // Closeness to the input vertices (scaled mesh units). Strong at the start, it fades with the
  // soft schedule; the planar mesh then moves no more than a closeness-dominated solve needs.
  double closeness_weight = 100.0;
  int fairness_order = 2;  // 2: second differences, 3: third differences
  // Circular quads instead of planar ones (000 §2): every face planar and concyclic, with an
  // auxiliary (normal, centre, squared radius) per face; the tolerance then also bounds the
  // concyclicity measure.
  bool circular = false;
  // Valid panels: corner-angle and edge-length bounds (on by default).
  PanelBoundsOptions panels;
  // Held and gliding vertices.
  VertexControlOptions vertices;
  // With a reference surface (constructor): weight of its tangent-plane closeness, which then
  // replaces the closeness to the input vertices (× closeness_weight), and of the weaker point
  // term (× closeness_weight).
  double reference_tangent_weight = 1.0;
  double reference_point_weight = 0.1;
  // Stop when the max planarity measure (diagonal distance / mean edge) is ≤ this.
  double tolerance = 1e-9;
  // Ceres path: one fixed-weight problem, closeness and fairness × this scale (0: tolerance /
  // 100, whose optimum meets the tolerance on typical inputs since the planarity left at the
  // optimum is roughly proportional to the soft weights).
  double ceres_soft_scale = 0.0;

  bool IsValid(std::string* why) const;
};

// The options as the report's "options" object (tolerance, max_iterations, weights, schedule,
// circular, ceres_soft_scale).
nlohmann::json OptionsJson(const PQPlanarizationOptions& o);

// The colour scale of the per-face pictures (--heatmap, --picture): RelativeFacePlanarity of
// `result` on a log scale.
ColourScale PlanarityColourScale(const PolyMesh& result, bool circular);

// The report's facts about a run besides the solver's: linear_solver, vertices, faces, options,
// shape_change (input against result) and colour_scale.
nlohmann::json PlanarizationFacts(const PolyMesh& input, const PolyMesh& result,
                                  const PQPlanarizationOptions& options);

// Run() is guided projection to the tolerance; RunCeres() minimises the same rows with fixed
// weights (closeness and fairness × ceres_soft_scale) by Ceres LM.
class PQPlanarization : public MeshProblem {
 public:
  // `mesh` must be a valid quad mesh (ReadMesh with quads_only). Throws InputError otherwise.
  // With `reference` (a triangle or polygon mesh), vertices keep close to that surface through
  // its tangent planes instead of to their start.
  // With `kept` (faces on the same vertices, e.g. the quads whose diagonal meshes `mesh` holds),
  // those faces get the panel bounds too, so they stay valid while `mesh`'s faces are made
  // planar.
  PQPlanarization(const PolyMesh& mesh, const PQPlanarizationOptions& options,
                  const PolyMesh* reference = nullptr, const PolyMesh* kept = nullptr);

  // The faces of `kept` whose corners sit on their bound (empty without `kept`).
  std::vector<int> KeptFacesAtAngleBound() const;

  // The options with ω_f² scaled by StartSoftScale of the start's planarity.
  SolverOptions solver_options() const override;
  CeresOptions ceres_options(int max_iterations) const override;
  NamedValues MeasureAt(const Eigen::VectorXd& x) const override {
    NamedValues m = ToNamedValues(MeasuresAt(x));
    AddEdgeRange(MeshAt(x), options_.tolerance, &m);
    return m;
  }
  // Planarity, and concyclicity when circular, within the tolerance.
  bool MeetsTolerance(const NamedValues& m) const override;

  PlanarityMeasures Measures() const { return MeasuresAt(problem_.x()); }
  const PQPlanarizationOptions& options() const { return options_; }
  // The faces whose planarity measure exceeds the tolerance, worst first.
  std::vector<int> FacesAboveTolerance() const;

 private:
  PlanarityMeasures MeasuresAt(const Eigen::VectorXd& x) const;

  PQPlanarizationOptions options_;
  int normal_block_ = -1;
  const PolyMesh* kept_ = nullptr;
  PanelBounds kept_bounds_;
  double start_planarity_ = 0.0;
};

}  // namespace gproj::pq
