// PLY (ASCII and binary), through OpenMesh after checking the header ourselves.
#include <OpenMesh/Core/IO/MeshIO.hh>
#include <cerrno>
#include <filesystem>
#include <fstream>
#include <limits>
#include <string>
#include <system_error>
#include <vector>

#include "geometry/mesh_text.h"

namespace gproj {
namespace mesh_io_internal {

namespace fs = std::filesystem;

namespace {

// Reads the ASCII header that every PLY file (ASCII or binary) starts with and returns the
// declared number of faces (-1 when there is no "element face" line).
long long ReadPlyFaceCount(const std::string& path) {
  std::ifstream in = OpenForReading(path);
  if (in.peek() == std::ifstream::traits_type::eof()) Fail(path, 0, "the file is empty");
  constexpr int kMaxHeaderLines = 10000;
  long long num_faces = -1;
  std::string line;
  for (int number = 1; number <= kMaxHeaderLines && std::getline(in, line); ++number) {
    if (!line.empty() && line.back() == '\r') line.pop_back();
    const std::vector<std::string_view> tokens = Tokens(line);
    if (number == 1) {
      if (tokens.size() != 1 || tokens[0] != "ply") {
        Fail(path, 1, "not a PLY file: the first line is not \"ply\"");
      }
      continue;
    }
    if (tokens.size() == 1 && tokens[0] == "end_header") return num_faces;
    if (tokens.size() == 3 && tokens[0] == "element") {
      long long count = 0;
      if (!ParseInt(tokens[2], &count) || count < 0) {
        Fail(path, number, "malformed element count " + Quote(tokens[2]));
      }
      if (tokens[1] == "face") num_faces = count;
    }
  }
  Fail(path, 0, "the PLY header has no \"end_header\" line");
}

// Note: OpenMesh 9 reads PLY coordinates through float (about 7 significant digits).
}  // namespace

PolygonSoup ReadPly(const std::string& path) {
  const long long num_faces = ReadPlyFaceCount(path);
  if (num_faces == 0) Fail(path, 0, "the file has no faces");

  PolyMesh mesh;
  // ImporterT splits off a face that would break manifoldness (duplicating its vertices) and
  // marks it fixed_nonmanifold; requesting face status lets that be reported, not hidden.
  mesh.request_face_status();
  OpenMesh::IO::Options options;
  bool ok = false;
  {
    QuietOpenMesh quiet;
    ok = OpenMesh::IO::read_mesh(mesh, path, options);
  }
  if (!ok) Fail(path, 0, "OpenMesh could not read the PLY file");
  const long long read_faces = static_cast<long long>(mesh.n_faces());
  if (num_faces > read_faces) {
    Fail(path, 0,
         "OpenMesh dropped " + std::to_string(num_faces - read_faces) + " of " +
             std::to_string(num_faces) +
             " faces (fewer than 3 vertices, a repeated vertex or an index out of range)");
  }
  for (const auto fh : mesh.faces()) {
    if (mesh.status(fh).fixed_nonmanifold()) {
      Fail(path, 0,
           "face " + std::to_string(fh.idx()) +
               " cannot join the mesh: it makes an edge or a vertex non-manifold, or its "
               "orientation disagrees with a neighbour");
    }
  }
  if (mesh.n_faces() == 0) Fail(path, 0, "the file has no faces");

  PolygonSoup soup;
  soup.vertices.reserve(mesh.n_vertices());
  for (const auto vh : mesh.vertices()) {
    const OpenMesh::Vec3d& p = mesh.point(vh);
    if (!std::isfinite(p[0]) || !std::isfinite(p[1]) || !std::isfinite(p[2])) {
      Fail(path, 0, "vertex " + std::to_string(vh.idx()) + " has a non-finite coordinate");
    }
    soup.vertices.emplace_back(p[0], p[1], p[2]);
  }
  soup.vertex_lines.assign(soup.vertices.size(), 0);
  soup.faces.reserve(mesh.n_faces());
  for (const auto fh : mesh.faces()) {
    std::vector<int> face;
    for (const auto vh : mesh.fv_range(fh)) face.push_back(vh.idx());
    soup.faces.push_back(std::move(face));
  }
  soup.face_lines.assign(soup.faces.size(), 0);
  return soup;
}

}  // namespace mesh_io_internal
}  // namespace gproj
