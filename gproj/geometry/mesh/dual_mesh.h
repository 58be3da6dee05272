#pragma once
// The dual polygon mesh of a triangle mesh: one vertex per triangle, one face per vertex (the
// triangles around it, in order), the usual start of a planar hexagonal or hex-dominant mesh
// (Wang, Liu et al. 2008: where the triangle mesh's vertices have valence 6 its dual's faces are
// hexagons).
//
// A dual vertex sits at its triangle's centroid, or (kTangentPlanes) where the tangent planes of
// the triangle's three vertices meet: the planes n_i · x = n_i · p_i, n_i the angle-weighted vertex
// normals, solved for the point nearest the centroid among their least-squares solutions (an
// SVD: where the normals are dependent, as on a plane, the point of the shared line or plane
// nearest the centroid). Every dual vertex around a vertex v then lies on v's tangent plane, so
// the dual's faces are planar; on a convex surface (and a triangulation without right angles)
// they are convex, where the surface is negatively curved some are not (Wang, Liu et al. 2008).
// Where the planes meet farther from the centroid than the triangle's longest edge (they nearly
// share a line: on a cylinder, along the asymptotic directions of a saddle, where the vertex
// normals are one-sided at a boundary) the point is not well conditioned: the dual vertex is
// the point at that distance from the centroid nearest the three planes (least squares), and
// is counted. Two neighbouring triangles whose planes meet in (nearly) the same point (four
// vertices on one circle of a sphere: the two halves of a split square; symmetric
// configurations) would give a dual edge shorter than a hundredth of the edge it crosses: both stay
// at their centroids, and are counted.
//
// Boundary: kDrop gives faces to the interior vertices only (a boundary vertex has no closed ring
// of triangles); kKeep also closes each boundary vertex's ring with the midpoints of its two
// boundary edges and the vertex itself where the outline has a corner there (its two boundary
// edges meet at less than kOutlineCornerDeg; elsewhere the midpoints are joined directly), so
// the dual covers the triangle mesh up to its border (exactly where the border is straight
// between its corners).

#include <string>

#include "gproj/geometry/io/mesh_io.h"

namespace gproj {

constexpr double kOutlineCornerDeg = 170.0;

enum class DualStart { kCentroids, kTangentPlanes };
enum class DualBoundary { kDrop, kKeep };

struct DualOptions {
  DualStart start = DualStart::kCentroids;
  DualBoundary boundary = DualBoundary::kDrop;
  // Singular values of the three unit normals below this fraction of the largest count as zero
  // (kTangentPlanes).
  double rank_tolerance = 1e-10;
};

struct DualStats {
  int tangent_plane_vertices = 0;  // placed where the three tangent planes meet
  int rank_deficient = 0;          // of those, where the planes share a line or coincide
  int held_within_reach = 0;       // not well conditioned: nearest the planes within reach
  int centroid_fallbacks = 0;      // normals undefined (a degenerate neighbourhood): centroid
  // Where the planes of two neighbouring triangles meet in (nearly) the same point (a dual edge
  // shorter than a hundredth of the edge it crosses): both at their centroids. Counted in
  // tangent_plane_vertices or held_within_reach too.
  int coincident = 0;
  int boundary_faces = 0;  // faces of boundary vertices (kKeep)
};

// Throws InputError naming the face that is not a triangle, or saying why the dual has no faces
// (kDrop and no interior vertex). The dual's faces are oriented as the input's.
PolyMesh DualMesh(const PolyMesh& triangles, const DualOptions& options,
                  DualStats* stats = nullptr);

}  // namespace gproj
