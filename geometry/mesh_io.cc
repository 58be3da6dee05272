#include "geometry/mesh_io.h"

#include <Eigen/Geometry>
#include <OpenMesh/Core/IO/MeshIO.hh>
#include <OpenMesh/Core/System/omstream.hh>
#include <algorithm>
#include <cctype>
#include <cerrno>
#include <charconv>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <limits>
#include <string_view>
#include <system_error>
#include <unordered_map>
#include <utility>

#ifdef _WIN32
#include <process.h>
#else
#include <unistd.h>
#endif

// Conventions for every message: one line, "<path>:<line>: " when the source line is known and
// "<path>: " otherwise; vertex and face numbers are 0-based indices in file order.

namespace gproj {
namespace {

namespace fs = std::filesystem;

enum class Format { kObj, kOff, kPly };

std::string Where(const std::string& path, int line) {
  return line > 0 ? path + ":" + std::to_string(line) + ": " : path + ": ";
}

[[noreturn]] void Fail(const std::string& path, int line, const std::string& what) {
  throw InputError(Where(path, line) + what);
}

// A token as it appears in a message: quoted, shortened, printable.
std::string Quote(std::string_view token) {
  constexpr std::size_t kMaxShown = 40;
  std::string shown;
  for (char c : token.substr(0, kMaxShown)) {
    shown += std::isprint(static_cast<unsigned char>(c)) ? c : '?';
  }
  if (token.size() > kMaxShown) shown += "...";
  return "\"" + shown + "\"";
}

std::string QuotePath(const std::string& path) { return "\"" + path + "\""; }

std::string ErrnoText() { return std::strerror(errno); }

std::string LowerExtension(const std::string& path) {
  std::string ext = fs::path(path).extension().string();
  for (char& c : ext) c = static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
  return ext;
}

Format FormatOf(const std::string& path) {
  const std::string ext = LowerExtension(path);
  if (ext == ".obj") return Format::kObj;
  if (ext == ".off") return Format::kOff;
  if (ext == ".ply") return Format::kPly;
  if (ext.empty()) Fail(path, 0, "the file name has no extension; expected .obj, .off or .ply");
  Fail(path, 0, "unknown mesh file extension " + Quote(ext) + "; expected .obj, .off or .ply");
}

// Silences OpenMesh's own logging (omerr/omlog) for its lifetime: the library prints nothing,
// and every failure is reported through InputError instead.
class QuietOpenMesh {
 public:
  QuietOpenMesh() : err_enabled_(::omerr().is_enabled()), log_enabled_(::omlog().is_enabled()) {
    ::omerr().disable();
    ::omlog().disable();
  }
  ~QuietOpenMesh() {
    // Flushing while disabled discards what was buffered.
    ::omerr().flush();
    ::omlog().flush();
    if (err_enabled_) ::omerr().enable();
    if (log_enabled_) ::omlog().enable();
  }
  QuietOpenMesh(const QuietOpenMesh&) = delete;
  QuietOpenMesh& operator=(const QuietOpenMesh&) = delete;

 private:
  bool err_enabled_;
  bool log_enabled_;
};

// ---------------------------------------------------------------------------------------------
// Text parsing.

std::string ReadWholeFile(const std::string& path) {
  std::error_code ec;
  if (fs::is_directory(path, ec)) Fail(path, 0, "cannot read the file: it is a directory");
  errno = 0;
  std::ifstream in(path, std::ios::binary);
  if (!in) {
    Fail(path, 0,
         "cannot open the file for reading: " +
             (errno != 0 ? ErrnoText() : std::string("unknown error")));
  }
  std::string text((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  if (in.bad()) Fail(path, 0, "cannot read the file: " + ErrnoText());
  return text;
}

bool IsBlank(std::string_view text) {
  return std::all_of(text.begin(), text.end(),
                     [](char c) { return std::isspace(static_cast<unsigned char>(c)) != 0; });
}

// Yields the lines of a text without their '#' comments, with 1-based line numbers (a '\r'
// before the '\n' is left to the tokenizer as whitespace).
class LineReader {
 public:
  explicit LineReader(std::string_view text) : text_(text) {}

  bool Next(std::string_view* line, int* line_number) {
    if (pos_ >= text_.size()) return false;
    std::size_t end = text_.find('\n', pos_);
    if (end == std::string_view::npos) end = text_.size();
    std::string_view raw = text_.substr(pos_, end - pos_);
    pos_ = end + 1;
    ++line_number_;
    const std::size_t hash = raw.find('#');
    if (hash != std::string_view::npos) raw = raw.substr(0, hash);
    *line = raw;
    *line_number = line_number_;
    return true;
  }

 private:
  std::string_view text_;
  std::size_t pos_ = 0;
  int line_number_ = 0;
};

std::vector<std::string_view> Tokens(std::string_view line) {
  std::vector<std::string_view> tokens;
  std::size_t i = 0;
  while (i < line.size()) {
    while (i < line.size() && std::isspace(static_cast<unsigned char>(line[i]))) ++i;
    std::size_t j = i;
    while (j < line.size() && !std::isspace(static_cast<unsigned char>(line[j]))) ++j;
    if (j > i) tokens.push_back(line.substr(i, j - i));
    i = j;
  }
  return tokens;
}

// Next line with at least one token; false at the end of the text.
bool NextTokens(LineReader* reader, std::vector<std::string_view>* tokens, int* line_number) {
  std::string_view line;
  while (reader->Next(&line, line_number)) {
    *tokens = Tokens(line);
    if (!tokens->empty()) return true;
  }
  return false;
}

// Locale-independent; accepts a leading '+', "nan" and "inf" (rejected later as non-finite).
bool ParseDouble(std::string_view token, double* value) {
  if (token.size() > 1 && token[0] == '+' && token[1] != '-' && token[1] != '+') {
    token.remove_prefix(1);
  }
  const char* begin = token.data();
  const char* end = begin + token.size();
  const auto [ptr, ec] = std::from_chars(begin, end, *value);
  if (ec == std::errc::result_out_of_range && ptr == end) {
    // Overflow gives ±inf, underflow gives 0 or a subnormal, as strtod does.
    *value = std::strtod(std::string(token).c_str(), nullptr);
    return true;
  }
  return ec == std::errc() && ptr == end;
}

bool ParseInt(std::string_view token, long long* value) {
  if (token.size() > 1 && token[0] == '+' && token[1] != '-' && token[1] != '+') {
    token.remove_prefix(1);
  }
  const char* end = token.data() + token.size();
  const auto [ptr, ec] = std::from_chars(token.data(), end, *value);
  return ec == std::errc() && ptr == end;
}

void AddVertex(const std::string& path, int line, const std::vector<std::string_view>& tokens,
               std::size_t first, PolygonSoup* soup) {
  const std::size_t vertex = soup->vertices.size();
  const std::size_t given = tokens.size() - first;
  if (given < 3) {
    Fail(path, line,
         "vertex " + std::to_string(vertex) + " has " + std::to_string(given) +
             (given == 1 ? " coordinate" : " coordinates") + "; 3 are required");
  }
  Eigen::Vector3d p;
  for (int k = 0; k < 3; ++k) {
    const std::string_view token = tokens[first + k];
    if (!ParseDouble(token, &p[k])) {
      Fail(path, line,
           "vertex " + std::to_string(vertex) + " has a malformed coordinate " + Quote(token));
    }
    if (!std::isfinite(p[k])) {
      Fail(path, line,
           "vertex " + std::to_string(vertex) + " has a non-finite coordinate " + Quote(token));
    }
  }
  soup->vertices.push_back(p);
  soup->vertex_lines.push_back(line);
}

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

int ParseCount(const std::string& path, int line, std::string_view token, const char* what) {
  long long count = 0;
  if (!ParseInt(token, &count) || count < 0 || count > std::numeric_limits<int>::max()) {
    Fail(path, line, std::string("malformed ") + what + " count " + Quote(token));
  }
  return static_cast<int>(count);
}

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

// ---------------------------------------------------------------------------------------------
// PLY, through OpenMesh.

// Reads the ASCII header that every PLY file (ASCII or binary) starts with and returns the
// declared number of faces (-1 when there is no "element face" line).
long long ReadPlyFaceCount(const std::string& path) {
  std::error_code ec;
  if (fs::is_directory(path, ec)) Fail(path, 0, "cannot read the file: it is a directory");
  errno = 0;
  std::ifstream in(path, std::ios::binary);
  if (!in) {
    Fail(path, 0,
         "cannot open the file for reading: " +
             (errno != 0 ? ErrnoText() : std::string("unknown error")));
  }
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

// ---------------------------------------------------------------------------------------------
// Validation.

int LineOf(const std::vector<int>& lines, std::size_t i) { return i < lines.size() ? lines[i] : 0; }

// A face is degenerate when its vector area is negligible against its longest edge.
bool IsDegenerate(const PolygonSoup& soup, const std::vector<int>& face) {
  constexpr double kRelativeArea = 1e-12;
  const std::size_t n = face.size();
  Eigen::Vector3d centroid = Eigen::Vector3d::Zero();
  for (int v : face) centroid += soup.vertices[v];
  centroid /= static_cast<double>(n);
  Eigen::Vector3d twice_area = Eigen::Vector3d::Zero();
  double max_edge_squared = 0.0;
  for (std::size_t i = 0; i < n; ++i) {
    const Eigen::Vector3d& a = soup.vertices[face[i]];
    const Eigen::Vector3d& b = soup.vertices[face[(i + 1) % n]];
    twice_area += (a - centroid).cross(b - centroid);
    max_edge_squared = std::max(max_edge_squared, (b - a).squaredNorm());
  }
  return 0.5 * twice_area.norm() <= kRelativeArea * max_edge_squared;
}

struct EdgeUse {
  int count = 0;
  int faces[2] = {-1, -1};
  int from = -1;  // start vertex of the edge as the first face traverses it
};

void Validate(const PolygonSoup& soup, const std::string& path,
              const MeshRequirements& requirements) {
  if (soup.faces.empty()) Fail(path, 0, "the mesh has no faces");
  const int num_vertices = static_cast<int>(soup.vertices.size());
  for (int v = 0; v < num_vertices; ++v) {
    if (!soup.vertices[v].allFinite()) {
      Fail(path, LineOf(soup.vertex_lines, v),
           "vertex " + std::to_string(v) + " has a non-finite coordinate");
    }
  }

  std::unordered_map<std::uint64_t, EdgeUse> edges;
  edges.reserve(2 * soup.faces.size() + 16);
  for (std::size_t f = 0; f < soup.faces.size(); ++f) {
    const std::vector<int>& face = soup.faces[f];
    const int line = LineOf(soup.face_lines, f);
    const std::string face_name = "face " + std::to_string(f);
    const std::size_t n = face.size();
    for (int v : face) {
      if (v < 0 || v >= num_vertices) {
        Fail(path, line,
             face_name + " references vertex " + std::to_string(v) + ", but the mesh has " +
                 std::to_string(num_vertices) + " vertices");
      }
    }
    if (n < 3) {
      Fail(path, line,
           face_name + " has " + std::to_string(n) + (n == 1 ? " vertex" : " vertices") +
               "; at least 3 are required");
    }
    for (std::size_t i = 0; i < n; ++i) {
      for (std::size_t j = i + 1; j < n; ++j) {
        if (face[i] == face[j]) {
          Fail(path, line,
               face_name + " uses vertex " + std::to_string(face[i]) +
                   " more than once (degenerate face)");
        }
      }
    }
    if (requirements.quads_only && n != 4) {
      Fail(path, line,
           face_name + " has " + std::to_string(n) + " vertices; a quad mesh is required");
    }
    if (IsDegenerate(soup, face)) {
      Fail(path, line, face_name + " is degenerate: its area is zero relative to its edge lengths");
    }
    for (std::size_t i = 0; i < n; ++i) {
      const int from = face[i];
      const int to = face[(i + 1) % n];
      const auto lo = static_cast<std::uint64_t>(std::min(from, to));
      const auto hi = static_cast<std::uint64_t>(std::max(from, to));
      EdgeUse& use = edges[(lo << 32) | hi];
      if (use.count == 2) {
        Fail(path, line,
             face_name + " uses the edge between vertices " + std::to_string(from) + " and " +
                 std::to_string(to) + ", which faces " + std::to_string(use.faces[0]) + " and " +
                 std::to_string(use.faces[1]) + " already share (non-manifold edge)");
      }
      if (use.count == 1 && use.from == from) {
        Fail(path, line,
             face_name + " traverses the edge from vertex " + std::to_string(from) + " to vertex " +
                 std::to_string(to) + " in the same direction as face " +
                 std::to_string(use.faces[0]) + " (inconsistent orientation)");
      }
      if (use.count == 0) use.from = from;
      use.faces[use.count++] = static_cast<int>(f);
    }
  }
}

// ---------------------------------------------------------------------------------------------
// Atomic writes.

long long ProcessId() {
#ifdef _WIN32
  return _getpid();
#else
  return static_cast<long long>(getpid());
#endif
}

// "dir/out.obj" -> "dir/.out.obj.tmp-<pid>.obj": same directory, so that the rename is atomic,
// hidden, and with the target's extension.
std::string TemporaryPathFor(const std::string& path) {
  const fs::path target(path);
  const std::string name = target.filename().string();
  if (name.empty() || name == "." || name == "..") Fail(path, 0, "the path names no file");
  const std::string temporary_name =
      "." + name + ".tmp-" + std::to_string(ProcessId()) + target.extension().string();
  return (target.parent_path() / temporary_name).string();
}

// Removes the temporary file unless it was renamed into place.
class TemporaryFile {
 public:
  explicit TemporaryFile(std::string path) : path_(std::move(path)) {}
  ~TemporaryFile() {
    if (!committed_) {
      std::error_code ignored;
      fs::remove(path_, ignored);
    }
  }
  TemporaryFile(const TemporaryFile&) = delete;
  TemporaryFile& operator=(const TemporaryFile&) = delete;

  const std::string& path() const { return path_; }

  void CommitTo(const std::string& target) {
    std::error_code ec;
    fs::rename(path_, target, ec);
    if (ec) {
      Fail(target, 0,
           "cannot move the temporary file " + QuotePath(path_) + " into place: " + ec.message());
    }
    committed_ = true;
  }

 private:
  std::string path_;
  bool committed_ = false;
};

// Writes `contents` to the new file `temporary` and flushes it to disk; messages name `path`.
void WriteNewFile(const std::string& path, const std::string& temporary,
                  const std::string& contents) {
  errno = 0;
  std::FILE* file = std::fopen(temporary.c_str(), "wb");
  if (file == nullptr) {
    Fail(path, 0, "cannot create the temporary file " + QuotePath(temporary) + ": " + ErrnoText());
  }
  bool ok = std::fwrite(contents.data(), 1, contents.size(), file) == contents.size();
  ok = ok && std::fflush(file) == 0;
#ifndef _WIN32
  ok = ok && fsync(fileno(file)) == 0;
#endif
  const int write_errno = errno;
  const bool closed = std::fclose(file) == 0;
  if (!ok || !closed) {
    if (!ok) errno = write_errno;
    Fail(path, 0, "cannot write the temporary file " + QuotePath(temporary) + ": " + ErrnoText());
  }
}

// Shortest decimal text that reads back as the same double.
void AppendDouble(double value, std::string* out) {
  char buffer[32];
  const auto result = std::to_chars(buffer, buffer + sizeof(buffer), value);
  out->append(buffer, result.ptr);
}

// The mesh as OBJ, OFF or ASCII PLY with exact double coordinates. OpenMesh's own writers are
// not used: in OpenMesh 9 they pass points through Vec3f and lose half the digits.
std::string MeshText(const PolyMesh& mesh, Format format) {
  // Compact numbering of the live vertices (deleted elements may not be garbage-collected yet).
  std::vector<int> index(mesh.n_vertices(), -1);
  int num_vertices = 0;
  for (const auto vh : mesh.vertices()) index[vh.idx()] = num_vertices++;
  std::size_t num_faces = 0;
  std::size_t max_valence = 0;
  for (const auto fh : mesh.faces()) {
    ++num_faces;
    max_valence = std::max<std::size_t>(max_valence, mesh.valence(fh));
  }

  std::string out;
  const std::string counts =
      std::to_string(num_vertices) + " vertices, " + std::to_string(num_faces) + " faces";
  switch (format) {
    case Format::kObj:
      out += "# gproj mesh: " + counts + "\n";
      break;
    case Format::kOff:
      out += "OFF\n" + std::to_string(num_vertices) + " " + std::to_string(num_faces) + " 0\n";
      break;
    case Format::kPly:
      out += "ply\nformat ascii 1.0\ncomment gproj mesh\nelement vertex " +
             std::to_string(num_vertices) +
             "\nproperty double x\nproperty double y\nproperty double z\nelement face " +
             std::to_string(num_faces) + "\nproperty list " +
             (max_valence > 255 ? "int" : "uchar") + " int vertex_indices\nend_header\n";
      break;
  }
  for (const auto vh : mesh.vertices()) {
    const PolyMesh::Point& p = mesh.point(vh);
    if (format == Format::kObj) out += "v ";
    AppendDouble(p[0], &out);
    out += ' ';
    AppendDouble(p[1], &out);
    out += ' ';
    AppendDouble(p[2], &out);
    out += '\n';
  }
  for (const auto fh : mesh.faces()) {
    if (format == Format::kObj) {
      out += 'f';
    } else {
      out += std::to_string(mesh.valence(fh));
    }
    for (const auto vh : mesh.fv_range(fh)) {
      out += ' ';
      out += std::to_string(index[vh.idx()] + (format == Format::kObj ? 1 : 0));
    }
    out += '\n';
  }
  return out;
}

}  // namespace

PolygonSoup ReadPolygonSoup(const std::string& path) {
  switch (FormatOf(path)) {
    case Format::kObj:
      return ReadObj(path, ReadWholeFile(path));
    case Format::kOff:
      return ReadOff(path, ReadWholeFile(path));
    case Format::kPly:
      return ReadPly(path);
  }
  Fail(path, 0, "unknown mesh format");
}

PolyMesh BuildMesh(const PolygonSoup& soup, const std::string& path,
                   const MeshRequirements& requirements) {
  Validate(soup, path, requirements);

  PolyMesh mesh;
  mesh.reserve(soup.vertices.size(), soup.vertices.size() + soup.faces.size(), soup.faces.size());
  std::vector<PolyMesh::VertexHandle> handles;
  handles.reserve(soup.vertices.size());
  for (const Eigen::Vector3d& p : soup.vertices) {
    handles.push_back(mesh.add_vertex(PolyMesh::Point(p.x(), p.y(), p.z())));
  }
  QuietOpenMesh quiet;
  std::vector<PolyMesh::VertexHandle> face_handles;
  for (std::size_t f = 0; f < soup.faces.size(); ++f) {
    face_handles.clear();
    for (int v : soup.faces[f]) face_handles.push_back(handles[v]);
    if (!mesh.add_face(face_handles).is_valid()) {
      // Edges were checked above, so what is left is a vertex whose faces form no single fan.
      Fail(path, LineOf(soup.face_lines, f),
           "face " + std::to_string(f) +
               " cannot join the mesh: one of its vertices would become non-manifold");
    }
  }
  return mesh;
}

PolyMesh ReadMesh(const std::string& path, const MeshRequirements& requirements) {
  return BuildMesh(ReadPolygonSoup(path), path, requirements);
}

void WriteMeshAtomically(const PolyMesh& mesh, const std::string& path) {
  const Format format = FormatOf(path);
  for (const auto vh : mesh.vertices()) {
    const PolyMesh::Point& p = mesh.point(vh);
    if (!std::isfinite(p[0]) || !std::isfinite(p[1]) || !std::isfinite(p[2])) {
      Fail(path, 0,
           "vertex " + std::to_string(vh.idx()) + " has a non-finite coordinate; nothing written");
    }
  }
  WriteTextFileAtomically(path, MeshText(mesh, format));
}

void WriteTextFileAtomically(const std::string& path, const std::string& contents) {
  TemporaryFile temporary(TemporaryPathFor(path));
  WriteNewFile(path, temporary.path(), contents);
  temporary.CommitTo(path);
}

}  // namespace gproj
