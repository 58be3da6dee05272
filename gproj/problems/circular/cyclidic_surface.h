#pragma once
// The smooth cyclidic surface of a cyclidic net (000 §2.2; Bobenko & Huhnen-Venedey 2012,
// "Curvature line parametrized surfaces and orthogonal coordinate systems: discretization with
// Dupin cyclides").
//
// A cyclidic net is a circular quad net with an orthonormal frame (t1, t2, n) at every vertex,
// the frames of neighbours mirror images in the bisector plane of their edge. Every quad
// (a, b, c, d) then carries one patch of a Dupin cyclide, bounded by circular arcs: a → b
// leaves a along t1, a → d along t2, b → c leaves b along the mirror image of t2, d → c leaves d
// along that of t1. Both families of curvature lines are circles, and the circles of each
// family lie in the planes of a pencil: family 2 (from ab to dc) in λ·plane(ad) + μ·plane(bc),
// family 1 (from ad to bc) in λ·plane(ab) + μ·plane(dc). The family-2 circle through x on ab
// leaves x along t2 mirrored from a to x and ends on dc in its pencil plane; a patch point is
// where it meets the pencil plane of the family-1 circle through z on ad. Patches sharing an
// arc meet with a common tangent plane along it (C¹; the curvatures jump).
//
// The fine mesh follows the curvature lines across the whole net: the samples on the first
// row's and first column's arcs are equal angles, and every patch hands the images of its
// samples on its far arcs to the next patch, so neighbouring patches share their boundary
// vertices exactly.

#include <Eigen/Core>
#include <array>
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "gproj/geometry/io/mesh_io.h"
#include "gproj/geometry/mesh/quad_grid.h"
#include "gproj/problems/circular/canal_surface.h"
#include "gproj/problems/run/construction.h"
#include "gproj/problems/run/guided_problem.h"

namespace gproj::circular {

// A circular arc: from `start`, counter-clockwise about `normal` (seen from its tip) by `angle`
// radians (in (0, 2π)) around `centre`; or, `straight`, the segment from `start` to `end`.
struct Arc {
  Eigen::Vector3d centre, normal, start, end;
  double radius = 0.0, angle = 0.0;
  bool straight = false;
  Eigen::Vector3d At(double fraction) const;  // the point at `fraction` of the angle (length)
  Eigen::Vector3d Tangent(const Eigen::Vector3d& point) const;  // unit, in the arc's sense
  double Bend() const;  // sin of the angle between the chord and the tangent at the start
};

// The arc from a to b that leaves a along t (unit); straight when t runs along b − a (to
// 1e-12). Throws InputError naming `what` when a = b.
Arc ArcFrom(const Eigen::Vector3d& a, const Eigen::Vector3d& t, const Eigen::Vector3d& b,
            const std::string& what);

// One patch: corners a, b, c, d (a circular quad) and the frame at a with the arcs' senses
// (a → b leaves along t1, a → d along t2).
struct CyclidicPatch {
  std::array<Eigen::Vector3d, 4> corners;
  Frame frame;
};

// Points of the patch: grid[i][j] (xs.size() × zs.size()) where the family-2 circle through
// xs[i] (points of arc ab, xs.front() = a, xs.back() = b) meets the family-1 circle through
// zs[j] (points of arc ad, zs.front() = a, zs.back() = d). Where a plane meets a circle twice,
// the point taken is the one where the normals carried from a along both curvature lines agree
// (frames close around every curvature-line quad of a cyclide). grid[i][0] = xs[i], grid[0][j] =
// zs[j]; the last column holds the images of xs on arc dc, the last row those of zs on arc bc.
// A patch with an arc that is straight or nearly so (bend below 1e-3), or with opposite arcs in
// one plane (a flat patch), where the pencil planes are not defined or ill-conditioned, is
// evaluated after an inversion in a sphere about a point off the patch (which maps cyclide
// patches, their curvature circles and frames to the same of another) and mapped back. Throws
// InputError (naming `where`) when a curvature circle misses its far arc.
std::vector<std::vector<Eigen::Vector3d>> EvaluateCyclidicPatch(
    const CyclidicPatch& patch, const std::vector<Eigen::Vector3d>& xs,
    const std::vector<Eigen::Vector3d>& zs, const std::string& where);

// A net in grid order (GridShape: vertex (i, j) = i (cols + 1) + j) with a frame at every
// vertex: t1 along the rows (towards (i, j + 1)), t2 down the columns (towards (i + 1, j)).
struct CyclidicNet {
  GridShape shape;
  std::vector<Eigen::Vector3d> points;
  std::vector<Frame> frames;  // mirror images of the frame at (0, 0)
  // Patch (i, j) with the frame at (i, j) turned to the arcs' senses: each mirror image
  // reverses the sense of the frame vector along its edge.
  CyclidicPatch Patch(int i, int j) const;
};

// The frames carried from `start` at (0, 0) by reflections along row 0, then down every column.
// Throws InputError when a vertex repeats its neighbour.
CyclidicNet MakeCyclidicNet(const GridShape& shape, std::vector<Eigen::Vector3d> points,
                            const Frame& start);

// The frame at (0, 0) of a grid net from angles (as for canal strips): the normal n by λ, θ; t1
// the projection of the edge (0, 0) → (0, 1) onto the plane ⟂ n, turned by ψ about n; t2 =
// n × t1. The senses (the arcs') are then turned towards the first edges: t1 towards (0, 1), t2
// towards (1, 0), so ψ and ψ + π give the same frame.
Frame GridStartFrame(const GridShape& shape, const std::vector<Eigen::Vector3d>& points,
                     const FrameAngles& angles);

// The angles of the normal of face (0, 0) (its diagonals' cross product, towards the side of
// (0, 0) → (0, 1) × (0, 0) → (1, 0)) and ψ = 0: the default start of the frame.
FrameAngles DefaultGridAngles(const GridShape& shape, const std::vector<Eigen::Vector3d>& points);

// 000 eq. 5 for a grid net: Σ over its edges of 1 / R² of their arcs.
double GridNetEnergy(const CyclidicNet& net);

struct GridFrameFairing {
  FrameAngles angles;
  Frame frame;  // the frame of the angles, with the t2 sense of the start
  double initial_energy = 0.0, final_energy = 0.0;
  int iterations = 0;
  bool converged = false;
  bool aborted = false;            // stopped by the callback
  std::string message;             // Ceres' report line
  std::vector<RunRecord> history;  // every iterate (energy and smoothness_energy: eq. 5)
};

// The frame at (0, 0) (λ, θ, ψ) that minimises eq. 5 over the net's edges (000 §3.3: the
// smoothest cyclidic net on a circular mesh), by Ceres' line-search BFGS from `start`, with
// gradients by automatic differentiation. The senses of `frame` are turned towards the first
// edges as in GridStartFrame (eq. 5 does not see them; the patches do).
GridFrameFairing FairGridFrame(const GridShape& shape, const std::vector<Eigen::Vector3d>& points,
                               const FrameAngles& start, int max_iterations = 200,
                               const RunCallback& callback = nullptr);

// A canal strip's net: row 0 the curve P_0..P_n, row 1 the points Q_k; the strip's frame at P_0.
CyclidicNet CyclidicNetOfStrip(const CyclidicStrip& strip);

// Largest angle (degrees) by which the frames, carried around a face by its four reflections,
// miss themselves (0 for circular faces), and the face.
double MaxFaceFrameClosure(const CyclidicNet& net, int* worst_face = nullptr);

// The largest fine mesh MeshCyclidicSurface makes (about 2 GB with its OBJ text).
constexpr double kMaxFineVertices = 1e7;
// The largest seam gap (per mean edge of the net's rows) welded with weld_closed.
constexpr double kSurfaceWeldTolerance = 1e-5;

struct CyclidicSurfaceOptions {
  int segments = 8;  // fine quads along every arc, in [1, 1000]
  // Merge the last column of the fine mesh into the first when they coincide (to
  // kSurfaceWeldTolerance): a net closed around (its last column repeats the first).
  bool weld_closed = false;
  bool IsValid(std::string* why) const;
};

struct CyclidicSurface {
  PolyMesh mesh;  // (rows·s + 1) × (cols·s + 1) vertices in grid order (fewer when welded)
  GridShape fine_shape;
  bool welded = false;
  // patches, max_tangent_angle_deg (across shared arcs), max_face_frame_closure_deg,
  // fine_max_concyclicity (the fine quads are curvature-line quads of cyclides, hence circular),
  // folded_fine_quads (not convex: the surface folds or pinches there), long_arcs (patch arcs
  // beyond 225° round their circles: the surface wraps round) and, with weld_closed,
  // seam_gap (last fine column against the first, per mean edge of the net's rows).
  NamedValues measures;
};

// The fine mesh of the smooth surface, with its tangent-plane continuity measured across every
// arc two patches share: at the arc's inner fine vertices, the tangent plane of each patch is
// spanned by the arc's tangent and that of the patch's curvature circle crossing the arc there
// (the near patch's circle as constructed through the vertex; the far patch's frame vector
// carried to it), and the normals are compared with their senses (a fold shows as ~180°).
// Throws InputError when the fine mesh would exceed kMaxFineVertices.
CyclidicSurface MeshCyclidicSurface(const CyclidicNet& net, const CyclidicSurfaceOptions& options);

struct CyclidicMeshOptions {
  CyclidicSurfaceOptions surface;
  bool given_frame = false;  // use `angles` as they are; else minimise eq. 5 from the default
  FrameAngles angles;        // with given_frame; else only its ψ (the minimisation's start)
  int max_iterations = 200;  // BFGS iterations for the frame
  double closure_tolerance = 1e-4;  // degrees: frames carried around a face may miss by this
  RunCallback callback;             // called with every iterate of the frame's BFGS; false stops
  bool IsValid(std::string* why) const;
};

struct CyclidicMeshResult {
  bool given_frame = false;
  CyclidicSurface surface;
  FrameAngles angles;
  GridFrameFairing fairing;  // without given_frame
  // initial: smoothness_energy of the starting frame; final: the surface's measures,
  // smoothness_energy and fine_max_concyclicity.
  NamedValues initial, final;
};

// The smooth cyclidic surface of a circular quad mesh in grid order (`gproj cyclidic`): the frame
// at vertex 0 (given, or minimising eq. 5), the net, its faces checked, the fine mesh. Throws
// InputError (prefixed with `path`) for a mesh that is not a grid, a face that is not circular
// (frames carried around it miss by more than the tolerance; the face is named) or a patch that
// degenerates.
CyclidicMeshResult CyclidicSurfaceOfMesh(const PolyMesh& mesh, const CyclidicMeshOptions& options,
                                         const std::string& path = "");

// Why a smooth surface (its measures) is not usable, or "": folded fine quads (the surface folds
// or pinches: a frame that turns the patches through a cone point), long arcs (the surface wraps
// round), tangent planes that disagree by more than `tangent_tolerance` degrees, fine quads off
// their circles by more than 1e-4 of the mean edge (a point picked wrongly).
std::string CyclidicSurfaceFault(const NamedValues& measures, double tangent_tolerance);

// The run's report from `construction` (timed from before the build; method BFGS when the frame
// is minimised, closed form when given), converged when CyclidicSurfaceFault finds nothing
// (else the termination gives the fault); and its extra keys "frame" (λ, θ, ψ, normal) and
// "fine_mesh" (rows, cols).
RunReport CyclidicRunReport(const CyclidicMeshResult& result, double tangent_tolerance,
                            const Construction& construction);
nlohmann::json CyclidicJson(const CyclidicMeshResult& result);

}  // namespace gproj::circular
