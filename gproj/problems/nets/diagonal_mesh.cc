#include "gproj/problems/nets/diagonal_mesh.h"

#include "gproj/common/input_error.h"
#include "gproj/problems/nets/hnet.h"

namespace gproj::nets {

DiagonalMesh MakeDiagonalMesh(const PolyMesh& quads, int colour, DiagonalRings which) {
  const std::vector<int> colours = TwoColourVertices(quads);
  DiagonalMesh out;
  out.vertex_of.assign(quads.n_vertices(), -1);
  std::vector<std::vector<int>> rings;
  for (auto w : quads.vertices()) {
    if (colours[w.idx()] == colour || quads.is_boundary(w) || quads.valence(w) == 0) continue;
    std::vector<int> ring;
    for (auto a : quads.vv_ccw_range(w)) ring.push_back(a.idx());
    if (which == DiagonalRings::kQuads && ring.size() != 4) {
      out.open_rings.push_back(w.idx());
      continue;
    }
    rings.push_back(std::move(ring));
  }
  if (rings.empty())
    throw InputError("the diagonal mesh of colour " + std::to_string(colour) + " has no face (" +
                     (out.open_rings.empty()
                          ? std::string("no inner vertex of the other colour")
                          : "the rings of the other colour's inner vertices are not quads") +
                     ")");
  for (const std::vector<int>& ring : rings)
    for (int a : ring)
      if (out.vertex_of[a] < 0) {
        out.vertex_of[a] = static_cast<int>(out.input_vertices.size());
        out.input_vertices.push_back(a);
        out.mesh.add_vertex(quads.point(PolyMesh::VertexHandle(a)));
      }
  for (const std::vector<int>& ring : rings) {
    std::vector<PolyMesh::VertexHandle> face;
    for (int a : ring) face.push_back(PolyMesh::VertexHandle(out.vertex_of[a]));
    if (!out.mesh.add_face(face).is_valid())
      throw InputError("the diagonal mesh is not a manifold at the ring of a vertex near " +
                       std::to_string(ring.front()));
  }
  return out;
}

}  // namespace gproj::nets
