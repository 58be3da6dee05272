// OFF (and COFF, NOFF, …): header, counts, vertices, faces.
#include <cmath>
#include <limits>
#include <string>
#include <vector>

#include "geometry/mesh_text.h"

namespace gproj {
namespace mesh_io_internal {

PolygonSoup ReadOff(const std::string& path, std::string_view text) {
  if (IsBlank(text)) Fail(path, 0, "the file is empty");
  LineReader reader(text);
  std::vector<std::string_view> tokens;
  int line = 0;
  if (!NextTokens(&reader, &tokens, &line)) Fail(path, 0, "the file has no faces");

  // Colour / normal variants carry extra columns after x y z, which are ignored.
  const std::string_view header = tokens[0];
  if (header != "OFF" && header != "COFF" && header != "NOFF" && header != "CNOFF") {
    Fail(path, line, "expected the header \"OFF\" (or COFF, NOFF, CNOFF), found " + Quote(header));
  }
  if (tokens.size() > 1 && tokens[1] == "BINARY") {
    Fail(path, line, "binary OFF is not supported; use ASCII OFF, OBJ or PLY");
  }
  // The counts "#V #F [#E]" follow on the header line or on the next line.
  tokens.erase(tokens.begin());
  if (tokens.empty() && !NextTokens(&reader, &tokens, &line)) {
    Fail(path, 0, "the file ends before the vertex and face counts");
  }
  if (tokens.size() < 2) {
    Fail(path, line, "expected the counts \"#vertices #faces [#edges]\" on this line");
  }
  const int num_vertices = ParseCount(path, line, tokens[0], "vertex");
  const int num_faces = ParseCount(path, line, tokens[1], "face");
  if (num_faces == 0) Fail(path, line, "the file has no faces");

  PolygonSoup soup;
  constexpr int kMaxReserve = 1 << 20;  // the counts are not trusted for allocation
  soup.vertices.reserve(std::min(num_vertices, kMaxReserve));
  soup.vertex_lines.reserve(std::min(num_vertices, kMaxReserve));
  for (int v = 0; v < num_vertices; ++v) {
    if (!NextTokens(&reader, &tokens, &line)) {
      Fail(path, 0,
           "the file ends after " + std::to_string(v) + " of " + std::to_string(num_vertices) +
               " vertices");
    }
    AddVertex(path, line, tokens, 0, &soup);
  }
  soup.faces.reserve(std::min(num_faces, kMaxReserve));
  soup.face_lines.reserve(std::min(num_faces, kMaxReserve));
  for (int f = 0; f < num_faces; ++f) {
    if (!NextTokens(&reader, &tokens, &line)) {
      Fail(path, 0,
           "the file ends after " + std::to_string(f) + " of " + std::to_string(num_faces) +
               " faces");
    }
    const std::string face_name = "face " + std::to_string(f);
    long long size = 0;
    if (!ParseInt(tokens[0], &size) || size < 0) {
      Fail(path, line, face_name + " has a malformed vertex count " + Quote(tokens[0]));
    }
    if (static_cast<long long>(tokens.size()) - 1 < size) {
      Fail(path, line,
           face_name + " declares " + std::to_string(size) + " vertices but lists " +
               std::to_string(tokens.size() - 1));
    }
    std::vector<int> face;
    face.reserve(static_cast<std::size_t>(size));
    for (long long i = 1; i <= size; ++i) {
      long long index = 0;
      if (!ParseInt(tokens[i], &index)) {
        Fail(path, line, face_name + " has a malformed vertex index " + Quote(tokens[i]));
      }
      if (index < 0 || index >= num_vertices) {
        Fail(path, line,
             face_name + " references vertex " + std::to_string(index) + ", but the file has " +
                 std::to_string(num_vertices) + " vertices");
      }
      face.push_back(static_cast<int>(index));
    }
    // Anything after the indices (a face colour) is ignored.
    soup.faces.push_back(std::move(face));
    soup.face_lines.push_back(line);
  }
  return soup;
}

}  // namespace mesh_io_internal
}  // namespace gproj
