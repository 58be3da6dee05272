#pragma once
// Quad mesh extraction from an integer-grid map of a triangle mesh, after Ebke, Bommes, Chen,
// Kobbelt, "QEx: robust quad mesh extraction", ACM TOG 32 (6), 2013: the quad vertices are the
// integer points of the map, the quad edges are traced along the integer iso-lines from vertex
// to vertex (crossing the map's seams by its transition functions), and the quads are the
// faces of the resulting graph with four sides. Where an iso-line leaves the surface at its
// boundary, the edge is missing and the cells there are dropped: the quad mesh covers the
// surface up to a band along the boundary, with no T-junctions and no partial quads.

#include <Eigen/Core>
#include <array>
#include <vector>

#include "gproj/geometry/io/mesh_io.h"

namespace gproj {

// A piecewise-linear map of a triangle mesh into the plane whose transitions across its seams
// are grid automorphisms (a quarter turn and an integer translation; Bommes, Zimmer, Kobbelt,
// "Mixed-integer quadrangulation", ACM TOG 28 (3), 2009).
struct IntegerGridMap {
  // Per face, the map at its corners in the order of the face's vertices (cfv_iter).
  std::vector<std::array<Eigen::Vector2d, 3>> corner_uv;
  // Per halfedge h with a face on both sides: uv in face(opposite(h)) = R^k uv in face(h) + t,
  // R the quarter turn, k = halfedge_rotation[h] in 0..3 (t follows from the corners). 0
  // elsewhere.
  std::vector<int> halfedge_rotation;
};

// The rotation by k quarter turns (k taken mod 4), exact.
Eigen::Matrix2d QuarterTurns(int k);

// Signed area of face f's image (negative: the map folds the face over).
double MappedArea(const IntegerGridMap& map, int face);

struct QuadExtraction {
  PolyMesh quads;
  // Per traced edge of `quads` (each once): its quad vertices and the triangle the trace left
  // from.
  struct Edge {
    int from = -1, to = -1, triangle = -1;
  };
  std::vector<Edge> edges;
  int grid_points = 0;       // integer points of the map on the surface
  int folded_triangles = 0;  // triangles whose image is folded (their points are skipped)
  int open_edges = 0;        // traces that left the surface or found no end point
  int dropped_cycles = 0;    // faces of the edge graph that are not quads (boundary band)
};

// `triangles` and `map` describe the same triangle mesh (corner_uv.size() == n_faces,
// halfedge_rotation.size() == n_halfedges). Throws InputError when they do not.
QuadExtraction ExtractQuads(const PolyMesh& triangles, const IntegerGridMap& map);

}  // namespace gproj
