#pragma once
// Vertex control for the mesh problems (planarisation, circular meshes, A-nets): vertices held
// exactly (Problem::SetConstant: no derivative, untouched bit for bit), boundary vertices gliding
// along the input's boundary loops (PolylineGliding rows, met to the constraint tolerance; the
// loops cut at their corners, which are held), and closeness to a reference surface through the
// tangent plane of the closest point plus a weaker point term (004 §3.2), so vertices slide along
// the surface instead of being pinned to their start.

#include <map>
#include <string>
#include <vector>

#include "gproj/constraints/control_net.h"
#include "gproj/geometry/io/mesh_io.h"
#include "gproj/geometry/mesh/closest_point.h"
#include "gproj/problems/mesh/mesh_variables.h"
#include "gproj/problems/run/guided_problem.h"

namespace gproj {

struct VertexControlOptions {
  std::vector<int> fixed;       // vertex ids held exactly
  bool fix_boundary = false;    // every boundary vertex held
  bool glide_boundary = false;  // boundary vertices not held slide along their boundary path
                                // between corners (kBoundaryCornerTurnDeg), corners held

  bool IsValid(std::string* why) const;
};

// 0-based vertex ids from a text file, separated by whitespace or newlines, '#' comments.
// Throws InputError naming the file, line and word for an id that is not an integer in
// [0, num_vertices).
std::vector<int> ReadVertexIds(const std::string& path, int num_vertices);

// What ApplyVertexControl set up.
struct VertexControl {
  std::vector<int> held;             // held vertices, sorted
  PolylineGliding* glide = nullptr;  // null without gliding
  double bbox_diagonal = 1.0;        // of the input, in input units
  double scale = 1.0;                // MeshNormalization::scale

  // Positions given to held vertices after the set-up (MeshProblem::Resolve), input units.
  std::map<int, PolyMesh::Point> moved;

  // Copies the held vertices from `input` (or `moved`) into `mesh` (the result), so that they
  // are as given bit for bit rather than after a round trip through the normalisation.
  void RestoreHeld(const PolyMesh& input, PolyMesh* mesh) const;

  // Max distance of a gliding vertex from its boundary loop / bbox diagonal (0 without).
  double MaxGlideDistance(const VariableLayout& layout, const Eigen::VectorXd& x) const;
};

// Holds and glides the vertices of `mesh` (items of `vertex_block`, normalised by `norm`) as the
// options say; x must hold the start. Throws InputError for an id out of range.
VertexControl ApplyVertexControl(const PolyMesh& mesh, const MeshNormalization& norm,
                                 int vertex_block, const VertexControlOptions& options,
                                 Problem* problem);

// Soft closeness of every vertex to `reference`: the tangent-plane row with `tangent_weight`,
// the point rows with `point_weight` (either 0: left out).
void AddReferenceCloseness(const PolyMesh& reference, const MeshNormalization& norm,
                           int vertex_block, int num_vertices, double tangent_weight,
                           double point_weight, Problem* problem);

// The boundary loops of a mesh, each as its vertex ids in order.
std::vector<std::vector<int>> BoundaryLoops(const PolyMesh& mesh);

// A boundary vertex is a corner when it lies in one face only (the corner of a quad grid) or
// the boundary turns there by more than this angle.
inline constexpr double kBoundaryCornerTurnDeg = 30.0;
bool IsBoundaryCorner(const PolyMesh& mesh, int previous, int v, int next);

// A boundary loop cut at its corners into paths from corner to corner (each corner ends one path
// and starts the next); a loop without corners comes back closed (first id repeated at the end).
std::vector<std::vector<int>> SplitAtCorners(const PolyMesh& mesh, const std::vector<int>& loop);

}  // namespace gproj
