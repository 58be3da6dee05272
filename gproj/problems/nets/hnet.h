#pragma once
// H-nets (004 §2–3): an A-net extended to a patchwork of rational bilinear patches (pieces of
// hyperboloids and hyperbolic paraboloids) joined with tangent-plane continuity.
//   1. shape parameters W per face w.r.t. the diagonal through the colour-0 vertices, from a
//      seed patch over the dual graph by 004 eq. 7;
//   2. the scale λ minimising Σ (λW_i − 1)² + (1/(λW_i) − 1)² (004 eq. 11, a quartic);
//   3. with W fixed, a vertex update for A-net + frame-point planarity; alternate 1–3.

#include <array>
#include <functional>
#include <string>
#include <utility>
#include <vector>

#include "gproj/geometry/io/mesh_io.h"
#include "gproj/problems/nets/anet.h"
#include "gproj/problems/run/report_json.h"

namespace gproj::nets {

// 0/1 colour per vertex such that every edge joins different colours. Throws InputError when
// the vertex graph is not bipartite.
std::vector<int> TwoColourVertices(const PolyMesh& mesh);

// The four vertices of the edge pair around halfedge h (from b0 to b3, b0 of colour 0):
// left face (b0 b1 b2 b3) = face of opposite(h), right face (b0 b3 b4 b5) = face of h.
struct EdgeStencil {
  int b[6];
  int left_face, right_face;
};
// The stencil of the inner edge e, oriented so that b0 has colour 0.
EdgeStencil EdgeStencilOf(const PolyMesh& mesh, const std::vector<int>& colour,
                          PolyMesh::EdgeHandle e);

// det(b30, b50, b20) / det(b30, b10, b40) of 004 eq. 7 (= W_r / W_l).
double ShapeParameterRatio(const PolyMesh& mesh, const EdgeStencil& s);

// Both sides of the closure condition 004 eq. 9 at inner vertex v:
// (∏ det(b_{2i+1,0}, b_{2i+3,0}, b_{2i,0}), ∏ det(b_{2i+1,0}, b_{2i−1,0}, b_{2i+2,0})).
std::pair<double, double> ClosureProducts(const PolyMesh& mesh, PolyMesh::VertexHandle v);

struct ShapeParameters {
  std::vector<double> w;  // per face, w.r.t. the colour-0 diagonal, scaled by λ
  double lambda = 1.0;
  double max_inconsistency = 0.0;  // max |W_predicted / W − 1| over edges off the BFS tree
};
// Propagates W from `seed_face` (W = 1) by eq. 7 and scales it by the optimal λ.
ShapeParameters PropagateShapeParameters(const PolyMesh& mesh, const std::vector<int>& colour,
                                         int seed_face);

// λ > 0 minimising Σ (λW_i − 1)² + (1/(λW_i) − 1)²: the best positive root of
// (ΣW²) λ⁴ − (ΣW) λ³ + (Σ1/W) λ − Σ1/W² = 0.
double OptimalShapeScale(const std::vector<double>& w);

// Corner weights of face f (in the face's vertex order) for shape parameter W: the colour-0
// corner k gets W, the others 1, so w_k w_{k+2} / (w_{k+1} w_{k+3}) = W.
std::array<double, 4> CornerWeights(const PolyMesh& mesh, const std::vector<int>& colour,
                                    PolyMesh::FaceHandle f, double w);

// The rational bilinear patch of 004 eq. 1 on face f with corner weights; point and unit normal
// at (u, v) ∈ [0, 1]².
void EvaluatePatch(const PolyMesh& mesh, PolyMesh::FaceHandle f, const std::array<double, 4>& w,
                   double u, double v, Eigen::Vector3d* point, Eigen::Vector3d* normal);

// The parameter t ∈ [0, 1] along a patch edge from a corner of weight w0 to one of weight w1 at
// which the rational edge ((1 − t) w0 A + t w1 B) / ((1 − t) w0 + t w1) reaches the point at
// fraction s of the straight segment A B (the edge of a rational bilinear patch is that
// segment). Weights of different signs (a pole on the edge): t = s.
double EdgeParameterAt(double s, double w0, double w1);
// (u, v) of the point at parameter t along the edge from corner k to corner k + 1 of a patch
// (corners at (0, 0), (1, 0), (1, 1), (0, 1)).
Eigen::Vector2d PatchEdgeUv(int k, double t);

// Per edge the max angle (degrees) between the tangent planes of its two patches, sampled at
// `samples` + 1 points along it (0 on the boundary).
std::vector<double> TangentPlaneAngles(const PolyMesh& mesh,
                                       const std::vector<std::array<double, 4>>& weights,
                                       int samples = 8);
// Their max over the inner edges.
double MaxTangentPlaneAngle(const PolyMesh& mesh, const std::vector<std::array<double, 4>>& weights,
                            int samples = 8);

// Inner edges whose determinants of Remark 2 have different signs (the patches' weights would
// not both be positive), as (vertex, vertex) pairs.
std::vector<std::pair<int, int>> EquitwistViolations(const PolyMesh& mesh,
                                                     const std::vector<int>& colour);

// Empty when the mesh is a topological disk or sphere; otherwise why it is not.
std::string SimplyConnectedProblem(const PolyMesh& mesh);

// A triangle mesh sampling every patch on a (k + 1) × (k + 1) grid, welded: a mesh vertex and
// the k − 1 inner samples of a mesh edge (at equal fractions of the straight edge) are one
// vertex each, shared by the patches around them, so a viewer shades the surface smoothly
// across the patches. #V + #E (k − 1) + #F (k − 1)² vertices, 2 k² triangles per patch.
PolyMesh SampleHNetSurface(const PolyMesh& mesh, const std::vector<std::array<double, 4>>& weights,
                           int samples);

struct HNetOptions {
  ANetOptions anet;           // the A-net step and the A-net part of the vertex update
  double frame_weight = 1.0;  // frame-point planarity rows
  int max_rounds = 8;         // alternations of the weight and vertex updates
  int iterations_per_round = 20;
  // Alternation stops when the weights change by less than this (max |W_new/W_old − 1|).
  double weight_tolerance = 1e-6;
  // Soft (closeness, fairness) weight factor at the start of every vertex update: the A-net is
  // already close and fair, the update should mostly satisfy the frame-point rows.
  double round_soft_scale = 1e-8;
  // Residual tolerance of the vertex update (scaled mesh, mean edge 1).
  double residual_tolerance = 1e-10;
  // Allow meshes that are not simply connected (the extension is then an optimisation only:
  // the vertices and the shape parameters W are solved for together, with W near 1 and W ≥
  // min_shape_parameter, in at most anet.solver.max_iterations iterations).
  bool allow_not_simply_connected = false;
  double shape_regularity = 1e-2;     // weight of W − 1 and 1/W − 1 (soft, 004 eq. 11)
  double min_shape_parameter = 1e-2;  // W ≥ this (positive weights)
  // kCeres, the cross-check: the A-net step and every vertex update by Ceres'
  // Levenberg–Marquardt on the same rows (the A-net step's soft terms at anet.ceres_soft_scale,
  // the updates' at round_soft_scale) instead of guided projection.
  SolverKind solver = SolverKind::kGuidedProjection;
};

struct HNetRound {
  int round = 0;
  double max_tangent_angle_deg = 0.0;
  double weight_change = 0.0;
  double min_w = 0.0, max_w = 0.0;
  double max_inconsistency = 0.0;
  StarPlanarityMeasures star;
  int solver_iterations = 0;
  bool vertex_update_converged = false;  // met residual_tolerance within iterations_per_round
  double seconds = 0.0;
};

struct HNetSummary {
  // The run as one report: history holds the A-net step's records; initial the input's star
  // measures, final the result's with max_tangent_angle_deg, weight_change (of the
  // last round), w_min, w_max and max_inconsistency; converged: the weights and vertices settled;
  // iterations: the A-net step's and every vertex update's; variables: the vertex update's.
  RunReport report;
  bool anet_step_run = false;
  std::vector<HNetRound> rounds;
  std::vector<std::pair<int, int>> equitwist_violations;
  // With a reference surface: the largest distance of a vertex to it over its bounding-box
  // diagonal (also report.final's max_reference_distance).
  double max_reference_distance = 0.0;
  // The inner edges whose patches meet at 1e-6° or more, worst first (up to 100): objects
  // {"vertices": [a, b], "tangent_angle_deg": angle}.
  nlohmann::json worst_edges = nlohmann::json::array();
  bool simply_connected = true;
  // The faces whose corners sit on their corner-angle bound after the last vertex update (the
  // updates keep the A-net step's panel bounds): where the bound blocks the frame rows.
  std::vector<int> faces_at_angle_bound;
};

// A round as named values (the report's keys): round, max_tangent_angle_deg, weight_change,
// w_min, w_max, max_inconsistency, the star measures, solver_iterations, seconds.
NamedValues ToNamedValues(const HNetRound& r);

// The H-net as JSON: "vertices", "faces" and four corner "weights" per face.
nlohmann::json HNetJson(const PolyMesh& mesh, const std::vector<std::array<double, 4>>& weights);

// The mean edge lengths the H-net rounds accept (their formulas multiply coordinates).
inline constexpr double kMinHNetEdge = 1e-100, kMaxHNetEdge = 1e100;

class HNet {
 public:
  // Checks the topology (quads, even inner valence, bipartite, simply connected unless allowed)
  // and the scale (mean edge in [kMinHNetEdge, kMaxHNetEdge]); throws InputError.
  HNet(const PolyMesh& mesh, const PolyMesh* reference, const HNetOptions& options);

  using RoundCallback = std::function<void(const HNetRound&)>;
  // The records of every iterate: the A-net step's, then the vertex updates' (numbered on after
  // the A-net step's; each update's start, the previous iterate, is not passed again), with the
  // star measures. Returning false stops the run at that iterate: no later update or round
  // starts, and the termination reads USER_ABORT.
  using IterationCallback = RunCallback;
  HNetSummary Run(const IterationCallback& on_iteration = nullptr,
                  const RoundCallback& on_round = nullptr);

  const PolyMesh& mesh() const { return mesh_; }
  const std::vector<std::array<double, 4>>& weights() const { return weights_; }
  const std::vector<double>& shape_parameters() const { return w_; }

  // The report's own keys of a run: rounds, worst_edges, simply_connected and
  // equitwist_violations (the rest is the shared schema of summary.report).
  static nlohmann::json ReportFacts(const HNetSummary& summary);

 private:
  // Runs the A-net step when the stars are not planar to tolerance; false (with the message in
  // *summary) when it fails.
  bool RunANetStep(const PolyMesh& reference, StopTracker* stop, HNetSummary* summary);
  // The alternation of weight and vertex updates (004 §3.2).
  void RunRounds(const PolyMesh& reference, const RoundCallback& on_round, StopTracker* stop,
                 HNetSummary* summary);
  // Meshes that are not simply connected: the weights propagated (round 0, for comparison), then
  // the vertices and weights optimised together (round 1).
  void RunJoint(const PolyMesh& reference, const RoundCallback& on_round, StopTracker* stop,
                HNetSummary* summary);
  // One solve of the vertices and the weights together (frame rows with W as unknowns), from the
  // current state, recorded as round `round`; true when its rows are met, W > 0 and the stars
  // planar to the tolerance. Sets report.failed on a numerical failure; stopped by `stop`, the
  // round holds the last iterate.
  bool SolveJointly(int round, double soft_scale, const PolyMesh& reference,
                    const RoundCallback& on_round, StopTracker* stop, HNetSummary* summary);
  // Shape parameters and corner weights from the current vertices, with the round's measures.
  HNetRound UpdateWeights(int round, const PolyMesh& reference);
  // Corner weights from w_ and the round's measures.
  HNetRound MeasureRound(int round);

  HNetOptions options_;
  PolyMesh input_, mesh_;
  const PolyMesh* reference_;
  std::vector<int> colour_;
  std::vector<double> w_;
  std::vector<std::array<double, 4>> weights_;
  std::string topology_note_;
};

}  // namespace gproj::nets
