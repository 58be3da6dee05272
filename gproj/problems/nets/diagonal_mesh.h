#pragma once
// The diagonal meshes of a quad mesh: the quads' diagonals as edges, one face per inner vertex
// (the ring of its neighbours). When the vertices can be 2-coloured the diagonals split into
// two meshes, one on each colour: the faces of one are the rings of the other's inner vertices.
// A net whose diagonals follow the asymptotic directions is an A-net / H-net on these.

#include <string>
#include <vector>

#include "gproj/geometry/io/mesh_io.h"

namespace gproj::nets {

struct DiagonalMesh {
  PolyMesh mesh;                    // its vertices numbered from 0
  std::vector<int> input_vertices;  // diagonal-mesh vertex → vertex of the quad mesh
  std::vector<int> vertex_of;       // quad-mesh vertex → diagonal-mesh vertex (−1: not on it)
  // Inner vertices of the other colour whose rings are not quads (singular vertices), left
  // open: holes of the diagonal mesh (with DiagonalRings::kQuads).
  std::vector<int> open_rings;
  std::vector<int> face_centres;  // per face: the quad-mesh vertex it is the ring of
};

enum class DiagonalRings {
  kAll,    // every ring a face
  kQuads,  // rings of 4 vertices only; the others left open (DiagonalMesh::open_rings)
};

// The diagonal mesh of colour `colour` (0: the colour of the lowest vertex of each component, as
// TwoColourVertices gives it; 1 the other): one face per inner vertex of the other colour, the
// ring of its neighbours, oriented like the quads. Throws InputError when the vertices cannot be
// 2-coloured and when the diagonal mesh has no face.
DiagonalMesh MakeDiagonalMesh(const PolyMesh& quads, int colour, DiagonalRings rings);

// The faces of the diagonal meshes of `quads` on the quad mesh's own vertices (same numbering;
// vertices on no ring are left isolated): of colour `colour` (0 or 1), or of both (−1), every
// ring a face (DiagonalRings::kAll). face_centres[k] is the vertex face k is the ring of. The
// faces a net on the diagonals makes planar. Throws InputError as MakeDiagonalMesh does (with
// both colours, when neither has a face).
DiagonalMesh MakeDiagonalFaces(const PolyMesh& quads, int colour);

// Faces for messages: by id ("faces 3, 17 (and 12 more)"), or, of a diagonal mesh, by the
// quad-mesh vertex each is the ring of ("the rings of vertices 40, 52").
std::string FacesNamed(const std::vector<int>& faces, const DiagonalMesh* diagonal);

}  // namespace gproj::nets
