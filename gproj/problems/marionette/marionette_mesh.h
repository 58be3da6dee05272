#pragma once
// Marionette meshes beyond the regular grid (002 §2.4, §4.1). The plan is a quad mesh of any
// connectivity (disk-like; inner vertices may have valence ≠ 4), and every vertex moves on its
// own fixed line p_i = o_i + t_i d_i (002 Fig. 14):
//   vertical     o_i = (x_i, y_i, 0), d_i = e_z: t is the height (the plan's z is ignored);
//   cylindrical  the line through the plan vertex perpendicular to an axis, from the axis:
//                t is the distance from the axis (towers, 002 §4.1);
//   central      the line through a centre and the plan vertex: t is the distance from it.
// With three vertices of a quad known, planarity fixes the fourth on its line: the line meets
// the plane of the three (002 eq. 2 for vertical lines). Propagating this face by face from
// guide values lifts the whole mesh in linear time, provided the guides cross every strip of
// faces exactly once (002 §2.4: one guide curve across each strip of patches).

#include <Eigen/Core>
#include <string>
#include <vector>

#include "gproj/geometry/io/mesh_io.h"
#include "gproj/problems/marionette/marionette.h"
#include "gproj/solver/guided_projection.h"
#include "gproj/solver/problem.h"

namespace gproj::marionette {

enum class MarionetteProjection { kVertical, kCylindrical, kCentral };
const char* MarionetteProjectionName(MarionetteProjection projection);
// "vertical", "cylindrical" or "central"; false for anything else.
bool ParseMarionetteProjection(const std::string& name, MarionetteProjection* projection);

struct MarionetteProjectionOptions {
  MarionetteProjection type = MarionetteProjection::kVertical;
  // Cylindrical: a point of the axis and its direction (any non-zero length).
  Eigen::Vector3d axis_point = Eigen::Vector3d::Zero();
  Eigen::Vector3d axis_direction = Eigen::Vector3d::UnitZ();
  // Central: the common centre of all lines.
  Eigen::Vector3d centre = Eigen::Vector3d::Zero();

  bool IsValid(std::string* why) const;
};

// A plan quad mesh with one line per vertex.
struct MarionetteLines {
  PolyMesh mesh;  // the plan: connectivity, and the positions that define the lines
  MarionetteProjection projection = MarionetteProjection::kVertical;
  std::vector<Eigen::Vector3d> origin, direction;  // #V each; directions have unit length
  Eigen::VectorXd plan_parameters;  // #V: t of the plan vertices (0 for vertical: z ignored)

  int num_vertices() const { return static_cast<int>(origin.size()); }
  Eigen::Vector3d Point(int v, double t) const { return origin[v] + t * direction[v]; }
};

// Builds the lines of a quad mesh (ReadMesh with quads_only). Throws InputError naming the
// vertex when a cylindrical plan vertex lies on the axis or a central one at the centre, and
// for invalid options. `path` is used in messages only.
MarionetteLines MakeMarionetteLines(const PolyMesh& plan,
                                    const MarionetteProjectionOptions& options,
                                    const std::string& path = "");

// The lifted mesh: vertex i at o_i + t_i d_i (t: #V).
PolyMesh MarionetteLiftedMesh(const MarionetteLines& lines, const Eigen::VectorXd& t);

// Max over faces of |det(p1 − p0, p2 − p0, p3 − p0)| / (|p1 − p0| |p2 − p0| |p3 − p0|): 0 for
// planar quads, scale free.
double MaxLiftPlanarity(const MarionetteLines& lines, const Eigen::VectorXd& t);

// The decomposition of 002 §2.4 into regular four-sided patches. Separatrices are the mesh
// polylines traced straight on (through inner valence-4 vertices) from every singular vertex
// (inner valence ≠ 4; boundary valence 2 or ≥ 4) until they reach the boundary, a singular
// vertex or another separatrix; patches are the face regions they and the boundary enclose.
// Strips: a face strip enters a face through one edge and leaves through the opposite one,
// from boundary to boundary (or around a loop); face strips that run through the same patches
// form a strip of patches. Open face strips of a disk each add one dimension to the space of
// vertical lifts: its dimension is (#open face strips + 1), the number of guide values needed.
struct MarionettePatch {
  std::vector<int> faces;
  std::vector<int> corners;  // vertices with one face of the patch (4 for a regular patch)
  int rows = 0, cols = 0;    // faces along its sides; 0 when the patch is not four-sided
  bool four_sided() const { return rows > 0; }
};

struct MarionettePatchStrip {
  std::vector<int> patches;      // patches it runs through, in order
  std::vector<int> face_strips;  // its face strips (the width of the strip)
  bool closed = false;
};

struct MarionettePatchLayout {
  std::vector<int> singular_vertices;
  std::vector<std::vector<int>> separatrices;  // vertex polylines
  std::vector<MarionettePatch> patches;
  std::vector<int> patch_of_face;       // #F
  std::vector<int> face_strip_of_edge;  // #E: the face strip that crosses the edge
  std::vector<int> patch_strip_of_face_strip;
  std::vector<MarionettePatchStrip> patch_strips;
  int num_face_strips = 0, num_closed_face_strips = 0;

  // Guide values that determine a vertical lift of a disk without closed strips.
  int design_dimension() const { return num_face_strips - num_closed_face_strips + 1; }
};

MarionettePatchLayout DecomposeIntoPatches(const PolyMesh& mesh);

// The straight mesh polyline from `start` through its neighbour `next`: it continues through
// inner vertices of even valence k (k / 2 edges on), and along the boundary through boundary
// vertices of valence 3 when it arrived along the boundary. Returns at most `max_vertices`
// vertices (fewer when it cannot continue, or when it comes back to `start`).
std::vector<int> TraceMeshPolyline(const PolyMesh& mesh, int start, int next, int max_vertices);

// Guide values (heights, or line parameters t) of 002 §2.4: on straight mesh polylines given
// by a start vertex, a neighbour and one value per polyline vertex, or on single vertices.
struct MarionetteGuide {
  int start = -1, next = -1;
  std::vector<double> values;
  std::string where;  // for messages, e.g. "guides.txt:3"; empty: "guide k"
};

// The prescribed vertex values of a set of guides. Throws InputError naming the guide for a
// vertex id out of range, `next` not a neighbour of `start`, a polyline shorter than its
// values (it meets the boundary or an odd-valence vertex), or a vertex given two different
// values (beyond 1e-12 relative).
std::vector<MarionetteTarget> ResolveMarionetteGuides(const PolyMesh& mesh,
                                                      const std::vector<MarionetteGuide>& guides,
                                                      const std::vector<MarionetteTarget>& single);

struct MarionetteMeshLift {
  Eigen::VectorXd t;             // #V line parameters (heights for vertical)
  std::vector<int> patch_order;  // patches in the order their last face was lifted
  // Faces whose four vertices were determined elsewhere (guides that over-determine them),
  // with values that happen to be compatible (planar within the tolerance), and their patches.
  std::vector<int> redundant_faces, over_determined_patches;
};

// Direct lift by propagation in dependency order (a face is lifted as soon as three of its
// vertices are known): linear time. `prescribed` from ResolveMarionetteGuides. Throws
// InputError, one line each:
//   under-determined: names the patches with vertices left without a value, some of those
//     vertices, and the strips of patches that no guide crosses;
//   incompatible: a face whose four vertices were determined elsewhere is not planar (relative
//     residual of MaxLiftPlanarity > compatibility_tolerance): names face, patch, vertices;
//   degenerate: the line of the vertex to determine is parallel to the plane of the three
//     known ones (vertical: they are collinear in x, y): names the face and the vertices.
MarionetteMeshLift LiftMarionetteMesh(const MarionetteLines& lines,
                                      const MarionettePatchLayout& layout,
                                      const std::vector<MarionetteTarget>& prescribed,
                                      double compatibility_tolerance = 1e-9);

// The same lift as a gproj problem: one parameter item t per vertex (block "parameters"),
// guide rows t_v − value (constraints, weight 1). Vertical: one planarity row per face, linear
// in the heights (002 eq. 2 on the best-conditioned corner of the plan quad); the problem is
// linear and one iteration solves it. Otherwise: an auxiliary unit normal per face (block
// "normals") and LineQuadPlanarity rows, bilinear, solved in several iterations. x starts at
// the plan's parameters with the prescribed values put in. Throws InputError naming the face
// when a vertical plan quad is degenerate (every corner collinear with its neighbours).
Problem MakeMarionetteMeshProblem(const MarionetteLines& lines,
                                  const std::vector<MarionetteTarget>& prescribed);

// Solver options: vertical one iteration (as MarionetteSolverOptions); otherwise up to
// `max_iterations` until every planarity / guide row is below `tolerance`.
SolverOptions MarionetteMeshSolverOptions(MarionetteProjection projection, int max_iterations = 50,
                                          double tolerance = 1e-12);

// The parameters t (#V) of a solved MakeMarionetteMeshProblem.
Eigen::VectorXd MarionetteMeshParameters(const Problem& problem);

}  // namespace gproj::marionette
