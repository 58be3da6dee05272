#pragma once
// A-nets (004 §3.2, eq. 10): a quad mesh roughly along the asymptotic directions of a
// negatively curved surface becomes a mesh with planar vertex stars, staying close to a
// reference surface (a triangle mesh, or the input itself) and fair.

#include <functional>
#include <memory>
#include <string>
#include <vector>

#include "geometry/closest_point.h"
#include "geometry/mesh_io.h"
#include "problems/mesh_variables.h"
#include "solver/ceres_adapter.h"
#include "solver/guided_projection.h"
#include "solver/problem.h"

namespace gproj {

enum class StarPlanarityForm {
  kNormals,  // an auxiliary unit normal per inner vertex, orthogonal to its star's edges
  kQuads,    // planarity of n − 2 quads of the star (diagonal-distance approximation)
};

struct ANetOptions {
  StarPlanarityForm star_form = StarPlanarityForm::kNormals;
  double planarity_weight = 1.0;
  double tangent_weight = 1.0;   // distance to the reference's tangent plane at the closest point
  double point_weight = 0.1;     // distance to the closest point itself (weaker)
  double anchor_weight = 0.0;    // distance to the input positions (fixed points; 0: off)
  double fairness_weight = 0.5;  // ω_f
  int fairness_order = 2;
  // Stop when the max star planarity (neighbour distance from the star plane / mean edge) is
  // ≤ this.
  double tolerance = 1e-9;
  int max_iterations = 50;
  double soft_weight_decay = 0.3;
  double soft_weight_floor = 1e-10;
  double epsilon = 1e-3;
  LinearSolverType linear_solver = LinearSolverType::kCholmod;
  int num_threads = 0;

  bool IsValid(std::string* why) const;
  SolverOptions ToSolverOptions() const;
};

struct StarPlanarityMeasures {
  double max_star_planarity = 0.0;   // max over star vertices and their neighbours
  double mean_star_planarity = 0.0;  // mean over star vertices of their max
  int worst_vertex = -1;
  double max_displacement = 0.0;  // / bbox diagonal of the reference positions
};

// Star planarity of every vertex with at least three neighbours: the largest distance of a
// neighbour from the least-squares plane through the vertex, divided by the mean edge length.
StarPlanarityMeasures MeasureStarPlanarity(const PolyMesh& mesh, const PolyMesh& reference);

// Refuses (InputError naming the vertex/face) what an A-net cannot be: non-quad faces, and
// inner vertices of odd valence. `path` goes into the message.
void CheckANetTopology(const PolyMesh& mesh, const std::string& path);

// Adds the A-net families to `problem`: star planarity (in the chosen form; star normals are
// added as an eliminable block), closeness to `reference` via tangent planes and points,
// fairness. Vertices must already be a block of the problem; the star-normal block is created
// here, so call it before ResizeToLayout and LoadANetNormals after.
struct ANetFamilies {
  int normal_block = -1;  // −1 for the quad form
  // Vertices whose star must be planar: inner vertices and boundary vertices of valence ≥ 3
  // (their star plane is the tangent plane of the patches meeting there), in block order.
  std::vector<int> star_vertices;
};
ANetFamilies AddANetLayout(const PolyMesh& mesh, const ANetOptions& options, Problem* problem);
void AddANetFamilies(const PolyMesh& mesh, const ANetOptions& options, int vertex_block,
                     const ANetFamilies& layout, const ClosestPointQuery* reference,
                     const MeshNormalization& norm, Problem* problem);
// Initialises star normals from the least-squares planes of the stars at x.
void LoadANetNormals(const PolyMesh& mesh, int vertex_block, const ANetFamilies& layout,
                     Problem* problem);

class ANet {
 public:
  // `reference` may be null: the input itself is the reference surface.
  ANet(const PolyMesh& mesh, const PolyMesh* reference, const ANetOptions& options);

  using Callback =
      std::function<CallbackResult(const IterationRecord&, const StarPlanarityMeasures&)>;
  SolverSummary Solve(const Callback& callback = nullptr);
  // Ceres LM on the same rows with fixed weights (soft scale `soft_scale`).
  CeresSummary SolveWithCeres(int max_iterations, double soft_scale);

  PolyMesh Result() const;
  StarPlanarityMeasures Measures() const;
  Problem& problem() { return problem_; }

 private:
  StarPlanarityMeasures MeasuresAt(const Eigen::VectorXd& x) const;

  ANetOptions options_;
  PolyMesh input_;
  mutable PolyMesh current_;  // the iterate as a mesh, rewritten in place by MeasuresAt
  MeshNormalization norm_;
  std::unique_ptr<ClosestPointQuery> reference_;
  Problem problem_;
  int vertex_block_ = -1;
  ANetFamilies families_;
};

}  // namespace gproj
