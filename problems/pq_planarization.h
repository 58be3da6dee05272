#pragma once
// PQ planarisation: every face of a quad mesh planar, the shape kept by closeness to the
// input and fairness along the mesh polylines (SPEC §3; 004 §3.2). The mesh is centred and
// scaled to mean edge length 1 inside the problem, so weights do not depend on units.

#include <functional>
#include <string>

#include "geometry/mesh_io.h"
#include "problems/mesh_variables.h"
#include "solver/ceres_adapter.h"
#include "solver/guided_projection.h"
#include "solver/problem.h"

namespace gproj {

struct PQPlanarizationOptions {
  double planarity_weight = 1.0;  // weight of the planarity rows
  double closeness_weight = 1.0;  // closeness to the input vertices (scaled mesh units)
  double fairness_weight = 1.0;   // ω_f of the second-difference fairness
  int fairness_order = 2;         // 2: second differences, 3: third differences
  // Circular quads instead of planar ones (000 §2): every face planar and concyclic, with an
  // auxiliary (normal, centre, squared radius) per face; the tolerance then also bounds the
  // concyclicity measure.
  bool circular = false;
  // Stop when the max planarity measure (diagonal distance / mean edge) is ≤ this.
  double tolerance = 1e-9;
  int max_iterations = 30;
  // Soft schedule: closeness and fairness weights × max(decay^k, floor) at iteration k.
  double soft_weight_decay = 0.1;
  double soft_weight_floor = 1e-12;
  double epsilon = 1e-3;
  // Ceres path: one fixed-weight problem, closeness and fairness × this scale (0: tolerance /
  // 100, whose optimum meets the tolerance on typical inputs since the planarity left at the
  // optimum is roughly proportional to the soft weights).
  double ceres_soft_scale = 0.0;
  LinearSolverType linear_solver = LinearSolverType::kCholmod;
  int num_threads = 0;

  bool IsValid(std::string* why) const;
  SolverOptions ToSolverOptions() const;
};

struct PlanarityMeasures {
  double max_planarity = 0.0;     // max over faces of (diagonal distance) / (mean edge length)
  double mean_planarity = 0.0;    // mean of the same
  double max_displacement = 0.0;  // max vertex displacement / bbox diagonal of the input
  double mean_edge_length = 0.0;  // of the measured mesh, in input units
  // Max over faces of the vertices' distance to their fitted circle / mean edge length; only
  // measured for circular problems (−1 otherwise).
  double max_concyclicity = -1.0;
};

// Distance between the two diagonal lines of a quad.
double DiagonalDistance(const Eigen::Vector3d& v0, const Eigen::Vector3d& v1,
                        const Eigen::Vector3d& v2, const Eigen::Vector3d& v3);

// Planarity of `mesh` (quads), displacement against `reference` (same connectivity; may be
// the mesh itself).
PlanarityMeasures MeasurePlanarity(const PolyMesh& mesh, const PolyMesh& reference);

class PQPlanarization {
 public:
  // `mesh` must be a valid quad mesh (ReadMesh with quads_only). Throws InputError otherwise.
  PQPlanarization(const PolyMesh& mesh, const PQPlanarizationOptions& options);

  // Guided projection. `callback` sees every iteration with the current measures; its return
  // value can stop the run. The run stops on its own when the tolerance is met.
  using Callback = std::function<CallbackResult(const IterationRecord&, const PlanarityMeasures&)>;
  SolverSummary Solve(const Callback& callback = nullptr);

  // The same problem (rows, weights at the final soft scale) minimised by Ceres LM.
  // Stops when the tolerance is met, or Ceres converges.
  using CeresCallback = std::function<bool(const CeresIterationRecord&, const PlanarityMeasures&)>;
  CeresSummary SolveWithCeres(int max_iterations, const CeresCallback& callback = nullptr);

  // Current vertices, in input units.
  PolyMesh Result() const;
  PlanarityMeasures Measures() const;
  // Whether the measures meet the tolerance (planarity, and concyclicity when circular).
  bool MeetsTolerance(const PlanarityMeasures& m) const;
  Problem& problem() { return problem_; }
  const PQPlanarizationOptions& options() const { return options_; }

 private:
  PlanarityMeasures MeasuresAt(const Eigen::VectorXd& x) const;

  PQPlanarizationOptions options_;
  PolyMesh input_;
  mutable PolyMesh current_;  // the iterate as a mesh, rewritten in place by MeasuresAt
  MeshNormalization norm_;
  Problem problem_;
  int vertex_block_ = -1;
  int normal_block_ = -1;
};

}  // namespace gproj
