#include "gproj/problems/nets/diagonal_mesh.h"

#include "gproj/common/input_error.h"
#include "gproj/problems/mesh/panel_bounds.h"
#include "gproj/problems/nets/hnet.h"

namespace gproj::nets {

namespace {

// The rings of the inner vertices of the colour other than `colour` (the faces of its diagonal
// mesh), their centres in out->face_centres, those left open in out->open_rings.
std::vector<std::vector<int>> Rings(const PolyMesh& quads, const std::vector<int>& colours,
                                    int colour, DiagonalRings which, DiagonalMesh* out) {
  std::vector<std::vector<int>> rings;
  for (auto w : quads.vertices()) {
    if (colours[w.idx()] == colour || quads.is_boundary(w) || quads.valence(w) == 0) continue;
    std::vector<int> ring;
    for (auto a : quads.vv_ccw_range(w)) ring.push_back(a.idx());
    if (which == DiagonalRings::kQuads && ring.size() != 4) {
      out->open_rings.push_back(w.idx());
      continue;
    }
    rings.push_back(std::move(ring));
    out->face_centres.push_back(w.idx());
  }
  return rings;
}

void RefuseNoFace(const std::string& which, const DiagonalMesh& out) {
  throw InputError("the diagonal mesh" + which + " has no face (" +
                   (out.open_rings.empty()
                        ? std::string("no inner vertex of the other colour")
                        : "the rings of the other colour's inner vertices are not quads") +
                   ")");
}

}  // namespace

DiagonalMesh MakeDiagonalFaces(const PolyMesh& quads, int colour) {
  const std::vector<int> colours = TwoColourVertices(quads);
  DiagonalMesh out;
  for (auto v : quads.vertices()) out.mesh.add_vertex(quads.point(v));
  for (const int c : {0, 1}) {
    if (colour >= 0 && c != colour) continue;
    for (const std::vector<int>& ring : Rings(quads, colours, c, DiagonalRings::kAll, &out)) {
      std::vector<PolyMesh::VertexHandle> face;
      for (int a : ring) face.push_back(PolyMesh::VertexHandle(a));
      if (!out.mesh.add_face(face).is_valid())
        throw InputError("the diagonal mesh is not a manifold at the ring of vertex " +
                         std::to_string(out.face_centres[out.mesh.n_faces()]));
    }
  }
  if (out.mesh.n_faces() == 0)
    RefuseNoFace(colour >= 0 ? " of colour " + std::to_string(colour) : "es", out);
  for (int v = 0; v < static_cast<int>(quads.n_vertices()); ++v) {
    out.input_vertices.push_back(v);
    out.vertex_of.push_back(v);
  }
  return out;
}

DiagonalMesh MakeDiagonalMesh(const PolyMesh& quads, int colour, DiagonalRings which) {
  const std::vector<int> colours = TwoColourVertices(quads);
  DiagonalMesh out;
  out.vertex_of.assign(quads.n_vertices(), -1);
  const std::vector<std::vector<int>> rings = Rings(quads, colours, colour, which, &out);
  if (rings.empty()) RefuseNoFace(" of colour " + std::to_string(colour), out);
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
      throw InputError("the diagonal mesh is not a manifold at the ring of vertex " +
                       std::to_string(out.face_centres[out.mesh.n_faces()]));
  }
  return out;
}

std::string FacesNamed(const std::vector<int>& faces, const DiagonalMesh* diagonal) {
  if (!diagonal) return FaceList(faces);
  constexpr size_t kShown = 10;
  std::string text = faces.size() == 1 ? "the ring of vertex " : "the rings of vertices ";
  for (size_t i = 0; i < faces.size() && i < kShown; ++i)
    text += (i > 0 ? ", " : "") + std::to_string(diagonal->face_centres[faces[i]]);
  if (faces.size() > kShown) text += " (and " + std::to_string(faces.size() - kShown) + " more)";
  return text;
}

}  // namespace gproj::nets
