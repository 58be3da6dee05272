// OBJ: v / f lines (texture and normal indices ignored, negative indices relative).
#include <cmath>
#include <limits>
#include <string>
#include <vector>

#include "gproj/geometry/io/internal/mesh_text.h"

namespace gproj {
namespace mesh_io_internal {

PolygonSoup ReadObj(const std::string& path, std::string_view text) {
  PolygonSoup soup;
  LineReader reader(text);
  std::vector<std::string_view> tokens;
  int line = 0;
  while (NextTokens(&reader, &tokens, &line)) {
    if (tokens[0] == "v") {
      AddVertex(path, line, tokens, 1, &soup);
    } else if (tokens[0] == "f") {
      const std::string face_name = "face " + std::to_string(soup.faces.size());
      std::vector<int> face;
      for (std::size_t i = 1; i < tokens.size(); ++i) {
        // "a", "a/b", "a//c" or "a/b/c": only the position index matters.
        const std::string_view token = tokens[i].substr(0, tokens[i].find('/'));
        long long index = 0;
        if (!ParseInt(token, &index)) {
          Fail(path, line, face_name + " has a malformed vertex index " + Quote(tokens[i]));
        }
        if (index == 0) {
          Fail(path, line, face_name + " uses vertex index 0; OBJ indices start at 1");
        }
        const long long preceding = static_cast<long long>(soup.vertices.size());
        if (index < 0) {
          if (preceding + index < 0) {
            Fail(path, line,
                 face_name + " uses relative vertex index " + std::to_string(index) +
                     ", but only " + std::to_string(preceding) + " vertices precede it");
          }
          face.push_back(static_cast<int>(preceding + index));
        } else {
          // Absolute indices may refer to vertices defined later; checked after the last line.
          if (index > std::numeric_limits<int>::max()) {
            Fail(path, line,
                 face_name + " references vertex " + std::to_string(index - 1) + " (written as " +
                     std::to_string(index) + "), beyond the supported number of vertices");
          }
          face.push_back(static_cast<int>(index - 1));
        }
      }
      soup.faces.push_back(std::move(face));
      soup.face_lines.push_back(line);
    }
    // vn, vt, vp, g, o, s, usemtl, mtllib, l, p, ...: not geometry of the polygon mesh.
  }
  if (soup.faces.empty()) {
    Fail(path, 0, IsBlank(text) ? "the file is empty" : "the file has no faces");
  }
  const int num_vertices = static_cast<int>(soup.vertices.size());
  for (std::size_t f = 0; f < soup.faces.size(); ++f) {
    for (int v : soup.faces[f]) {
      if (v >= num_vertices) {
        Fail(path, soup.face_lines[f],
             "face " + std::to_string(f) + " references vertex " + std::to_string(v) +
                 " (written as " + std::to_string(v + 1) + "), but the file has " +
                 std::to_string(num_vertices) + " vertices");
      }
    }
  }
  return soup;
}

}  // namespace mesh_io_internal
}  // namespace gproj
