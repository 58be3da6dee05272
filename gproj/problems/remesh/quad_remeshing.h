#pragma once
// Field-aligned quad remeshing of a triangle mesh (004 §3.1, Fig. 4: "remesh S into a quad mesh
// Q that follows the asymptotic directions"; the same with principal directions gives the
// starting nets of PQ and circular meshes).
//   1. the direction field of geometry/curvature_field (jet fit, smoothed principal lines),
//      per face as a frame (a, b): the asymptotic pair, or the principal pair;
//   2. the frames' matchings across edges and their singularities (Ray et al. 2008; the frame's
//      quarter turn is (a, b) → (b, −a); the principal cross matches by quarter turns, the
//      asymptotic pair, whose families never trade places, by half turns);
//   3. a seamless integer-grid map after Bommes, Zimmer, Kobbelt, "Mixed-integer
//      quadrangulation", ACM TOG 28 (3), 2009: the surface is cut into a disk through its holes
//      (shortest paths joining every boundary loop to the longest one), around its handles (two
//      arcs between boundary vertices per handle, by tree–cotree) and from every
//      singularity to the boundary, the frames combed across the remaining edges, and the map
//      u: S → R² whose gradient best fits the frame (∇u a = (1, 0) / h, ∇u b = (0, 1) / h, in
//      the least-squares sense over the area) is found by one sparse Cholesky solve
//      (CHOLMOD); across a cut the map jumps by the cut's quarter turn R and a translation:
//      (I − R) u(s) across a singularity's cut (s a fixed point), an unknown t across a hole's
//      or a handle's; the singularities' map and the other cuts' t are rounded to integers and the
//      map solved again, so every transition is a grid automorphism;
//   4. quad extraction along the integer iso-lines (geometry/quad_extraction, after QEx).
// A singularity of index i becomes a quad vertex of valence 4 − 4i (004 Theorem 6: an ordinary
// flat point, index −½, a vertex of valence 6).

#include <Eigen/Core>
#include <string>
#include <vector>

#include "gproj/geometry/io/mesh_io.h"
#include "gproj/geometry/mesh/curvature_field.h"
#include "gproj/geometry/mesh/quad_extraction.h"
#include "gproj/solver/sparse_cholesky.h"

namespace gproj::remesh {

struct QuadRemeshOptions {
  DirectionKind directions = DirectionKind::kAsymptotic;
  // Edge length of the quads in the input's units; 0: 3 × the mean edge length of the triangles.
  // At least a quarter of that mean edge length.
  double edge_length = 0.0;
  // Alignment weight of the principal-line smoothing (SmoothPrincipalField); larger follows the
  // fitted lines more closely, smaller gives a smoother field with fewer singularities.
  double smoothing = 1.0;
  CurvatureFitOptions fit;
  // Asymptotic pairs closer than this angle (degrees; near parabolic points, where they merge)
  // are opened to it, so the quads stay bounded in shape.
  double min_net_angle_deg = 30.0;
  // Weight σ of the quads' size against their alignment: the map's gradient is fitted by
  // ∇u·b = ∇v·a = 0 (edges along the field) and σ(∇u·a − 1/h) = σ(∇v·b − 1/h) = 0 (edge length
  // h); below 1 the edges follow the field more closely and the lengths vary more.
  double size_weight = 0.3;
  LinearSolverType linear_solver = LinearSolverType::kCholmod;
  bool IsValid(std::string* why) const;
};

// A singularity of the frame field: an inner vertex and its index, a multiple of ¼.
struct FrameSingularity {
  int vertex = -1;
  double index = 0.0;
};

struct FieldParametrization {
  IntegerGridMap map;
  // Per face the frame the map follows, as unit 3D tangents (a, b) (the net's two directions).
  std::vector<Eigen::Vector3d> frame_a, frame_b;
  std::vector<FrameSingularity> singularities;
  std::vector<int> cut_edges;  // the edges the surface was cut along
  int boundary_loops = 0;      // 1: a disk; more: a surface with holes, cut through them
  int handles = 0;             // the surface's genus, each handle cut open by two arcs
  int folded_faces = 0;        // faces whose image is folded (negative area)
  double edge_length = 0.0;    // the quads' edge length, input units
};

// The number of boundary loops of `mesh`; throws InputError unless it is a triangulated surface
// the remeshing can cut into a disk: triangles only, connected, manifold vertices, at least one
// boundary loop (handles are cut open from the boundary). The message names the rule broken.
int CheckTriangulatedSurface(const PolyMesh& mesh);

// The field-aligned integer-grid map of `triangles` for `field` (EstimateDirectionField on the
// same mesh). Throws InputError for a mesh CheckTriangulatedSurface refuses, invalid options, a
// singularity that cannot be joined to the boundary without crossing another cut, or a failed
// factorisation.
FieldParametrization ParametrizeAlongField(const PolyMesh& triangles, const DirectionField& field,
                                           const QuadRemeshOptions& options);

struct QuadRemeshResult {
  DirectionField field;
  FieldParametrization parametrization;
  QuadExtraction extraction;  // extraction.quads is the remeshed surface, input units
  // Measures of the quad mesh.
  std::vector<int> inner_valence_count;  // index: valence (inner vertices)
  int odd_inner_vertices = 0;            // inner vertices of odd valence
  double mean_alignment_deg = 0.0;       // edges against the nearer frame line of their face
  double max_alignment_deg = 0.0;
  double area_covered = 0.0;  // quad area / triangle area
  int nonconvex_quads = 0;
  double min_corner_angle_deg = 0.0;
  // Why the quad vertices cannot be 2-coloured (an odd cycle of edges, as around a hole whose
  // grid closes with an odd shift); empty when they can.
  std::string odd_cycle;
  // The quads' topology against the surface's: pieces (faces joined by edges), vertices where
  // the quads meet at a corner only (more than one boundary fan), and the Euler characteristic
  // (the surface's is 2 − 2 handles − its boundary loops; the quads' differs where a hole was lost,
  // or merged with the boundary or another hole).
  int components = 0;
  int pinched_vertices = 0;
  long euler_characteristic = 0, surface_euler_characteristic = 0;
  double seconds_field = 0.0, seconds_map = 0.0, seconds_extraction = 0.0;
  // Why the quads are not a valid net, one entry per kind (empty: valid): inner vertices of
  // valence 2, non-convex quads, triangles folded by the map, and, for asymptotic directions,
  // inner vertices of odd valence, vertices that cannot be 2-coloured and K >= 0 on more than 1%
  // of the area; and quads in several pieces, pinched, or of another topology than the surface.
  std::vector<std::string> Problems() const;
};

// The angle (degrees) between a quad edge d and the nearer of its triangle's frame lines a, b,
// with d projected onto the triangle's plane first (an edge crossing a curved surface leaves the
// plane of the triangle it starts in; that tilt is no deviation from the field).
double EdgeAgainstFrameDeg(const Eigen::Vector3d& d, const Eigen::Vector3d& a,
                           const Eigen::Vector3d& b);

// EstimateDirectionField → ParametrizeAlongField → ExtractQuads, with the measures. Throws
// InputError as those do, and when no quad could be extracted (the edge length is too large
// for the surface).
QuadRemeshResult RemeshAlongField(const PolyMesh& triangles, const QuadRemeshOptions& options);

}  // namespace gproj::remesh
