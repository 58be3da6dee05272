#pragma once
// Valid panels for every quad-mesh problem (planarisation, circular meshes, A-nets, H-nets) and
// the polygons of polygon planarisation: inequality rows (gproj/constraints/panel_validity.h)
// that keep each corner angle within [θ, 180° − θ] and each edge within [ℓ_min, ℓ_max] while the
// other rows act. A bound the input already breaks is relaxed to the input's value, so such a
// panel (a reflex corner of a hexagon in a negatively curved region) or edge is only kept from
// getting worse.

#include <array>
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "gproj/constraints/panel_validity.h"
#include "gproj/geometry/io/mesh_io.h"
#include "gproj/geometry/mesh/quad_shape.h"
#include "gproj/geometry/render/face_colours.h"
#include "gproj/problems/mesh/mesh_variables.h"
#include "gproj/problems/run/guided_problem.h"

namespace gproj {

struct PanelBoundsOptions {
  // Corner rows on every quad (off: panels may fold, as without bounds).
  bool corners = true;
  // θ in degrees, in [0, 60): every corner angle stays in [θ, 180° − θ]; 0 keeps quads convex.
  double min_angle_deg = 5.0;
  // Edge lengths in the input's units (0: no such bound). Without ℓ_min, every edge keeps at
  // least min_edge_fraction of its input length (0 disables), so no edge collapses.
  double min_edge_length = 0.0;
  double max_edge_length = 0.0;
  double min_edge_fraction = 0.1;

  // No bounds at all (--allow-folds): neither corner rows nor the default edge floor.
  void AllowFolds() {
    corners = false;
    min_edge_fraction = 0.0;
  }

  bool IsValid(std::string* why) const;
};

// The rows added to a problem; null where a bound is off.
// Polygons of up to this many corners get corner rows (faces of more corners get none, and
// AddPanelBounds lists them).
constexpr int kMaxBoundedCorners = 8;

struct PanelBounds {
  QuadCornerTerm* corners = nullptr;
  EdgeLengthTerm* min_edges = nullptr;
  EdgeLengthTerm* max_edges = nullptr;
  std::vector<QuadCornerBounds> corner_bounds;  // per face (quads only)
  std::vector<double> min_edge, max_edge;       // per mesh edge, input units (empty: off)
  // Faces of 5 to kMaxBoundedCorners corners: the face and its corners' lower sine bounds.
  std::vector<std::pair<int, std::vector<double>>> polygon_corner_bounds;
  std::vector<int> unbounded_polygons;  // faces of more corners: no corner rows
};

// Adds the bounds over the quads (and polygons of 5 to kMaxBoundedCorners corners) and edges of
// `mesh`, whose vertices are the items of `vertex_block` in the normalisation `norm`. The
// bounds are measured on `mesh` (relaxed to its corners, the default edge floor from its
// lengths), which may be another state than the start in problem->x() (a later stage bounded
// by its input); the slacks start from x. The families' names begin with `prefix` (a second
// set of faces on the same vertices needs its own).
PanelBounds AddPanelBounds(const PolyMesh& mesh, const MeshNormalization& norm, int vertex_block,
                           const PanelBoundsOptions& options, Problem* problem,
                           const std::string& prefix = "");

// The faces of `mesh` whose corners sit on their bound (within `margin` of the sine).
std::vector<int> FacesAtCornerBound(const PolyMesh& mesh, const PanelBounds& bounds,
                                    double margin = 1e-6);

// The edges of `mesh` (input units) within a relative `margin` of their length bound, measured
// as the rows do (the lower one along the edge's direction in `input`), as vertex pairs.
std::vector<std::array<int, 2>> EdgesAtLengthBound(const PolyMesh& input, const PolyMesh& mesh,
                                                   const PanelBounds& bounds, double margin = 1e-3);
std::string EdgeList(const std::vector<std::array<int, 2>>& edges, int shown = 10);

// The shape measures a designer reads, as named values: non_convex_quads, min_corner_angle_deg,
// max_kink_deg, max_planarity_abs (diagonal distance in the mesh's units).
NamedValues ShapeValues(const QuadShapeSummary& summary);

// The report's "colour_scale" object.
nlohmann::json ColourScaleJson(const ColourScale& scale);

// The report's "shape_change" object.
nlohmann::json ShapeChangeJson(const ShapeChange& change);

// "faces 3, 17, 40 (and 12 more)" for messages.
std::string FaceList(const std::vector<int>& faces, int shown = 10);

}  // namespace gproj
