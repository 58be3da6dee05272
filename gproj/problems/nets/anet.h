#pragma once
// A-nets (004 §3.2, eq. 10): a quad mesh roughly along the asymptotic directions of a
// negatively curved surface becomes a mesh with planar vertex stars, staying close to a
// reference surface (a triangle mesh, or the input itself) and fair.

#include <functional>
#include <memory>
#include <string>
#include <vector>

#include "gproj/geometry/io/mesh_io.h"
#include "gproj/geometry/mesh/closest_point.h"
#include "gproj/geometry/render/face_colours.h"
#include "gproj/problems/mesh/mesh_problem.h"
#include "gproj/problems/mesh/mesh_variables.h"
#include "gproj/problems/mesh/panel_bounds.h"
#include "gproj/problems/mesh/vertex_control.h"
#include "gproj/problems/run/guided_problem.h"
#include "gproj/solver/ceres_adapter.h"
#include "gproj/solver/guided_projection.h"
#include "gproj/solver/problem.h"

namespace gproj::nets {

enum class StarPlanarityForm {
  kNormals,  // an auxiliary unit normal per inner vertex, orthogonal to its star's edges
  kQuads,    // planarity of n − 2 quads of the star (diagonal-distance approximation)
};

// Which net's stars must be planar. kEdges: each vertex with its edge neighbours (the mesh is
// the A-net). kDiagonals: each vertex with the corners opposite it in its quads (the two
// diagonal meshes of the quad mesh are A-nets; ArchGeo's diagonal option): for meshes whose
// diagonals, not edges, follow the asymptotic directions. The quads, their bounds and fairness
// stay those of the mesh itself.
enum class NetKind { kEdges, kDiagonals };
// "edges", "diagonal"
const char* NetKindName(NetKind net);

// Calls visit(w) for the points w of v's star in cyclic order: its neighbours (kEdges), or the
// corners opposite v in its quads (kDiagonals; a boundary vertex's open fan gives one per quad).
template <typename Visit>
void ForEachStarPoint(const PolyMesh& mesh, PolyMesh::VertexHandle v, NetKind net, Visit visit) {
  if (net == NetKind::kEdges) {
    for (auto w : mesh.vv_range(v)) visit(w);
    return;
  }
  // The outgoing halfedges in the order vv_range gives the neighbours; each one's quad (when it
  // has one) has the corner after its head opposite v.
  for (auto h : mesh.voh_range(v))
    if (!mesh.is_boundary(h)) visit(mesh.to_vertex_handle(mesh.next_halfedge_handle(h)));
}
// The same as a list of vertex ids.
std::vector<int> StarPoints(const PolyMesh& mesh, PolyMesh::VertexHandle v, NetKind net);

// Guided projection's defaults for A-nets: 50 iterations, ω_f = 0.5, soft weights fading by 0.1
// per iteration down to 1e-12, monotone steps; the star-planarity measure decides convergence.
SolverOptions ANetSolverDefaults();

struct ANetOptions {
  // Guided projection (ω_f = solver.fairness_weight weighs the polyline fairness).
  SolverOptions solver = ANetSolverDefaults();
  StarPlanarityForm star_form = StarPlanarityForm::kNormals;
  NetKind net = NetKind::kEdges;
  double planarity_weight = 1.0;
  // Distance to the reference's tangent plane at the closest point, and to the closest point
  // itself (ten times weaker). Strong at the start, they fade with the soft schedule: weak ones
  // let the mesh slide along its own tangent planes (boundary and corners drift off) before
  // the stars are planar.
  double tangent_weight = 100.0;
  double point_weight = 10.0;
  double anchor_weight = 0.0;  // distance to the input positions (fixed points; 0: off)
  int fairness_order = 2;
  // Stop when the max star planarity (neighbour distance from the star plane / mean edge) is
  // ≤ this.
  double tolerance = 1e-9;
  // The Ceres cross-check's fixed factor on the soft (closeness, fairness) weights (0:
  // tolerance / 100, as for planarisation: the planarity left at the fixed-weight optimum is
  // roughly proportional to the soft weights).
  double ceres_soft_scale = 0.0;
  // Valid panels: corner-angle and edge-length bounds on the quads (on by default; the
  // H-net's vertex step keeps its own rows).
  PanelBoundsOptions panels;
  // Held and gliding vertices.
  VertexControlOptions vertices;

  bool IsValid(std::string* why) const;
};

struct StarPlanarityMeasures {
  double max_star_planarity = 0.0;   // max over star vertices and their neighbours
  double mean_star_planarity = 0.0;  // mean over star vertices of their max
  int worst_vertex = -1;
  double max_displacement = 0.0;     // / bbox diagonal of the reference positions
  QuadShapeSummary shape;            // convexity, corner angles, kinks of the quads
  double max_glide_distance = -1.0;  // of gliding boundary vertices / bbox diagonal (−1: none)
};

// Star planarity of every vertex with at least three star points (StarPoints of `net`): the
// largest distance of a star point from the least-squares plane through the vertex, divided by
// the mean edge length.
// As named values (the report's keys): max_star_planarity, mean_star_planarity, worst_vertex,
// max_displacement, the ShapeValues (non_convex_quads, min_corner_angle_deg, max_kink_deg,
// max_planarity_abs) and, with gliding, max_glide_distance.
NamedValues ToNamedValues(const StarPlanarityMeasures& m);

StarPlanarityMeasures MeasureStarPlanarity(const PolyMesh& mesh, const PolyMesh& reference,
                                           NetKind net = NetKind::kEdges);

// Per face: the largest star planarity (as in MeasureStarPlanarity) of its corners.
std::vector<double> FaceStarPlanarity(const PolyMesh& mesh, NetKind net = NetKind::kEdges);
// The table of `anet --face-values`: "face,star_planarity,kink_deg,min_angle_deg" per face.
std::string ANetFaceValuesCsv(const PolyMesh& mesh, NetKind net = NetKind::kEdges);
// The colour scale of the per-face pictures: FaceStarPlanarity on a log scale.
ColourScale StarPlanarityColourScale(const PolyMesh& result, NetKind net = NetKind::kEdges);

// The report's facts about a run besides the solver's: vertices, faces, shape_change (corner
// angles changed by more than 30°: A-net quads are skew, their angles move more than planar
// ones) and colour_scale.
nlohmann::json ANetFacts(const PolyMesh& input, const PolyMesh& result,
                         NetKind net = NetKind::kEdges);
// The corner-angle change (degrees) that counts as a large shape change for A-nets.
constexpr double kANetShapeChangeDeg = 30.0;

// Refuses (InputError naming the vertex/face) what an A-net cannot be: non-quad faces, and
// inner vertices of odd valence. `path` goes into the message.
void CheckANetTopology(const PolyMesh& mesh, const std::string& path);

// Adds the A-net families to `problem`: star planarity (in the chosen form; star normals are
// added as an eliminable block), closeness to `reference` via tangent planes and points,
// fairness. Vertices must already be a block of the problem; the star-normal block is created
// here, so call it before ResizeToLayout and LoadANetNormals after.
struct ANetFamilies {
  int normal_block = -1;  // −1 for the quad form
  // Vertices whose star must be planar: those with at least three star points (inner vertices,
  // and boundary vertices of valence ≥ 3, or with three or more quads for the diagonal net:
  // their star plane is the tangent plane of the patches meeting there), in block order.
  std::vector<int> star_vertices;
  std::vector<std::vector<int>> star_points;  // StarPoints of each star vertex
};
ANetFamilies AddANetLayout(const PolyMesh& mesh, const ANetOptions& options, Problem* problem);
void AddANetFamilies(const PolyMesh& mesh, const ANetOptions& options, int vertex_block,
                     const ANetFamilies& layout, const PolyMesh* reference,
                     const MeshNormalization& norm, Problem* problem);
// Initialises star normals from the least-squares planes of the stars at x.
void LoadANetNormals(const PolyMesh& mesh, int vertex_block, const ANetFamilies& layout,
                     Problem* problem);

// Run() is guided projection to the tolerance; RunCeres() minimises the same rows with fixed
// weights (soft terms × ceres_soft_scale) by Ceres LM.
class ANet : public MeshProblem {
 public:
  // `reference` may be null: the input itself is the reference surface.
  ANet(const PolyMesh& mesh, const PolyMesh* reference, const ANetOptions& options);

  // The options with ω_f² scaled by StartSoftScale of the start's star planarity.
  SolverOptions solver_options() const override;
  CeresOptions ceres_options(int max_iterations) const override;
  NamedValues MeasureAt(const Eigen::VectorXd& x) const override {
    NamedValues m = ToNamedValues(MeasuresAt(x));
    AddEdgeRange(MeshAt(x), options_.tolerance, &m);
    return m;
  }
  bool MeetsTolerance(const NamedValues& m) const override {
    return ValueOf(m, "max_star_planarity") <= options_.tolerance && EdgesInRange(m);
  }

  StarPlanarityMeasures Measures() const { return MeasuresAt(problem_.x()); }

 private:
  StarPlanarityMeasures MeasuresAt(const Eigen::VectorXd& x) const;

  ANetOptions options_;
  ANetFamilies families_;
  double start_planarity_ = 0.0;
};

}  // namespace gproj::nets
