// OFF (and COFF, NOFF, …): header, counts, vertices, faces, read token by token so that a face
// list may span lines. A vertex is its first three numbers and a face its count and indices;
// what follows them on the same line (colours, normals) is ignored.
#include <cmath>
#include <limits>
#include <string>
#include <vector>

#include "gproj/geometry/io/internal/mesh_text.h"

namespace gproj {
namespace mesh_io_internal {

namespace {

struct OffCounts {
  int vertices = 0;
  int faces = 0;
};

// The header and the counts "#V #F [#E]" (#E only on the line of #F).
OffCounts ReadOffHeader(const std::string& path, TokenReader* reader) {
  Token header;
  if (!reader->Next(&header)) Fail(path, 0, "the file has no faces");
  if (header.text != "OFF" && header.text != "COFF" && header.text != "NOFF" &&
      header.text != "CNOFF") {
    Fail(path, header.line,
         "expected the header \"OFF\" (or COFF, NOFF, CNOFF), found " + Quote(header.text));
  }
  Token token;
  if (reader->NextOnLine(header.line, &token) && token.text == "BINARY") {
    Fail(path, header.line, "binary OFF is not supported; use ASCII OFF, OBJ or PLY");
  }
  Token vertices = token;
  if (token.line != header.line && !reader->Next(&vertices)) {
    Fail(path, 0, "the file ends before the vertex and face counts");
  }
  Token faces;
  if (!reader->Next(&faces)) Fail(path, 0, "the file ends before the vertex and face counts");
  OffCounts counts;
  counts.vertices = ParseCount(path, vertices.line, vertices.text, "vertex");
  counts.faces = ParseCount(path, faces.line, faces.text, "face");
  if (counts.faces == 0) Fail(path, faces.line, "the file has no faces");
  reader->SkipRestOfLine(faces.line);  // #E

  // A vertex takes at least 3 tokens, a face (3 vertices at least) 4.
  const double tokens = 3.0 * counts.vertices + 4.0 * counts.faces;
  const std::string declared = "the counts declare " + std::to_string(counts.vertices) +
                               " vertices and " + std::to_string(counts.faces) + " faces";
  CheckTokensFit(path, faces.line, declared, tokens, reader->remaining(), "after the counts");
  CheckMemory(path, faces.line, declared,
              MeshMemoryEstimate(counts.vertices, counts.faces, 3.0 * counts.faces));
  return counts;
}

void ReadOffVertex(const std::string& path, int num_vertices, TokenReader* reader,
                   PolygonSoup* soup) {
  std::vector<std::string_view> coordinates;
  Token token;
  int line = 0;
  while (coordinates.size() < 3 && reader->Next(&token)) {
    if (coordinates.empty()) line = token.line;
    coordinates.push_back(token.text);
  }
  if (coordinates.empty()) {
    Fail(path, 0,
         "the file ends after " + std::to_string(soup->vertices.size()) + " of " +
             std::to_string(num_vertices) + " vertices");
  }
  AddVertex(path, line, coordinates, 0, soup);
  reader->SkipRestOfLine(token.line);
}

void ReadOffFace(const std::string& path, int num_vertices, int num_faces, TokenReader* reader,
                 PolygonSoup* soup) {
  const std::size_t f = soup->faces.size();
  Token token;
  if (!reader->Next(&token)) {
    Fail(
        path, 0,
        "the file ends after " + std::to_string(f) + " of " + std::to_string(num_faces) + " faces");
  }
  const int line = token.line;
  const std::string face_name = "face " + std::to_string(f);
  long long size = 0;
  if (!ParseInt(token.text, &size) || size < 0) {
    Fail(path, line, face_name + " has a malformed vertex count " + Quote(token.text));
  }
  if (size < 3) {
    Fail(path, line,
         face_name + " has " + std::to_string(size) + (size == 1 ? " vertex" : " vertices") +
             "; at least 3 are required");
  }
  std::vector<int> face;
  for (long long i = 0; i < size; ++i) {
    if (!reader->Next(&token)) {
      Fail(path, line,
           face_name + " declares " + std::to_string(size) + " vertices but lists " +
               std::to_string(i));
    }
    long long index = 0;
    if (!ParseInt(token.text, &index)) {
      Fail(path, token.line, face_name + " has a malformed vertex index " + Quote(token.text));
    }
    if (index < 0 || index >= num_vertices) {
      Fail(path, token.line,
           face_name + " references vertex " + std::to_string(index) + ", but the file has " +
               std::to_string(num_vertices) + " vertices");
    }
    face.push_back(static_cast<int>(index));
  }
  reader->SkipRestOfLine(token.line);  // a face colour
  soup->faces.push_back(std::move(face));
  soup->face_lines.push_back(line);
}

}  // namespace

PolygonSoup ReadOff(const std::string& path, std::string_view text) {
  if (IsBlank(text)) Fail(path, 0, "the file is empty");
  TokenReader reader(text, /*hash_comments=*/true);
  const OffCounts counts = ReadOffHeader(path, &reader);

  PolygonSoup soup;
  soup.vertices.reserve(counts.vertices);
  soup.vertex_lines.reserve(counts.vertices);
  for (int v = 0; v < counts.vertices; ++v) ReadOffVertex(path, counts.vertices, &reader, &soup);
  soup.faces.reserve(counts.faces);
  soup.face_lines.reserve(counts.faces);
  for (int f = 0; f < counts.faces; ++f) {
    ReadOffFace(path, counts.vertices, counts.faces, &reader, &soup);
  }
  return soup;
}

}  // namespace mesh_io_internal
}  // namespace gproj
