#include "gproj/geometry/io/mesh_io.h"

#include <Eigen/Geometry>
#include <OpenMesh/Core/IO/MeshIO.hh>
#include <OpenMesh/Core/System/omstream.hh>
#include <algorithm>
#include <array>
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
#include <signal.h>
#include <unistd.h>
#endif

#include "gproj/geometry/io/internal/mesh_text.h"
#include "gproj/geometry/mesh/scale_free.h"

namespace gproj {
namespace {

namespace fs = std::filesystem;
using namespace mesh_io_internal;  // NOLINT(build/namespaces): the readers' shared pieces

Format FormatOf(const std::string& path) {
  const std::string ext = LowerExtension(path);
  if (ext == ".obj") return Format::kObj;
  if (ext == ".off") return Format::kOff;
  if (ext == ".ply") return Format::kPly;
  if (ext.empty()) Fail(path, 0, "the file name has no extension; expected .obj, .off or .ply");
  Fail(path, 0, "unknown mesh file extension " + Quote(ext) + "; expected .obj, .off or .ply");
}

// ---------------------------------------------------------------------------------------------
// Validation.

int LineOf(const std::vector<int>& lines, std::size_t i) { return i < lines.size() ? lines[i] : 0; }

// A face is degenerate when its vector area is negligible against its longest edge.
bool IsDegenerate(const PolygonSoup& soup, const std::vector<int>& face) {
  constexpr double kRelativeArea = 1e-12;
  const std::size_t n = face.size();
  // Measured at unit size, so that no product overflows or underflows at any finite scale.
  std::vector<Eigen::Vector3d> p(n);
  for (std::size_t i = 0; i < n; ++i) p[i] = soup.vertices[face[i]];
  if (NormalizePolygon(p.data(), static_cast<int>(n)) == 0.0) return true;
  Eigen::Vector3d centroid = Eigen::Vector3d::Zero();
  for (const Eigen::Vector3d& q : p) centroid += q;
  centroid /= static_cast<double>(n);
  Eigen::Vector3d twice_area = Eigen::Vector3d::Zero();
  double max_edge_squared = 0.0;
  for (std::size_t i = 0; i < n; ++i) {
    const Eigen::Vector3d& a = p[i];
    const Eigen::Vector3d& b = p[(i + 1) % n];
    twice_area += (a - centroid).cross(b - centroid);
    max_edge_squared = std::max(max_edge_squared, (b - a).squaredNorm());
  }
  return 0.5 * twice_area.norm() <= kRelativeArea * max_edge_squared;
}

// The first vertex, in face order, that the face uses more than once; -1 if none. Sorts a copy,
// so that a face of many thousand vertices takes no quadratic time.
int FirstRepeatedVertex(const std::vector<int>& face) {
  std::vector<int> sorted = face;
  std::sort(sorted.begin(), sorted.end());
  if (std::adjacent_find(sorted.begin(), sorted.end()) == sorted.end()) return -1;
  for (int v : face) {
    const auto range = std::equal_range(sorted.begin(), sorted.end(), v);
    if (range.second - range.first > 1) return v;
  }
  return -1;
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
    const int repeated = FirstRepeatedVertex(face);
    if (repeated >= 0) {
      Fail(path, line,
           face_name + " uses vertex " + std::to_string(repeated) +
               " more than once (degenerate face)");
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

// "dir/out.obj" -> "dir/.out.obj.<kind>-<pid>.obj" (kind "tmp" for a temporary, "old" for the
// backup of a replaced file): same directory, so that the rename is atomic, hidden, and with
// the target's extension.
std::string SidePathFor(const std::string& path, const char* kind) {
  const fs::path target(path);
  const std::string name = target.filename().string();
  if (name.empty() || name == "." || name == "..") Fail(path, 0, "the path names no file");
  const std::string side_name =
      "." + name + "." + kind + "-" + std::to_string(ProcessId()) + target.extension().string();
  return (target.parent_path() / side_name).string();
}

// Whether process `pid` still runs (a temporary of a running gproj must be left alone).
bool ProcessRuns(long long pid) {
#ifdef _WIN32
  return true;  // not checked: stale temporaries are left
#else
  if (pid <= 0 || pid > std::numeric_limits<pid_t>::max()) return false;
  return kill(static_cast<pid_t>(pid), 0) == 0 || errno == EPERM;
#endif
}

// Removes the temporaries and backups of `path` that killed runs left behind
// (".out.obj.tmp-<pid>.obj", ".out.obj.old-<pid>.obj" of a process that no longer runs).
// Errors are ignored: this is housekeeping.
void RemoveStaleTemporaries(const std::string& path) {
  const fs::path target(path);
  const std::string stem = "." + target.filename().string() + ".";
  const std::string suffix = target.extension().string();
  const std::size_t kind_size = 4;  // "tmp-" or "old-"
  const fs::path folder = target.parent_path().empty() ? fs::path(".") : target.parent_path();
  std::error_code ec;
  for (fs::directory_iterator it(folder, ec), end; !ec && it != end; it.increment(ec)) {
    const std::string name = it->path().filename().string();
    if (name.size() <= stem.size() + kind_size + suffix.size() ||
        name.compare(0, stem.size(), stem) != 0 ||
        name.compare(name.size() - suffix.size(), suffix.size(), suffix) != 0)
      continue;
    const std::string kind = name.substr(stem.size(), kind_size);
    if (kind != "tmp-" && kind != "old-") continue;
    const std::size_t digits_start = stem.size() + kind_size;
    const std::string digits =
        name.substr(digits_start, name.size() - digits_start - suffix.size());
    long long pid = 0;
    const auto parsed = std::from_chars(digits.data(), digits.data() + digits.size(), pid);
    if (parsed.ec != std::errc() || parsed.ptr != digits.data() + digits.size()) continue;
    if (pid != ProcessId() && !ProcessRuns(pid)) {
      std::error_code ignored;
      fs::remove(it->path(), ignored);
    }
  }
}

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
  const Format format = FormatOf(path);
  const std::string data = ReadWholeFile(path);
  const std::string_view text = WithoutByteOrderMark(data);
  switch (format) {
    case Format::kObj:
      return ReadObj(path, text);
    case Format::kOff:
      return ReadOff(path, text);
    case Format::kPly:
      return ReadPly(path, text);
  }
  Fail(path, 0, "unknown mesh format");
}

PolygonSoup ParsePolygonSoup(const std::string& name, const std::string& format,
                             std::string_view contents) {
  std::string lower = format;
  for (char& c : lower) c = static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
  const std::string_view text = WithoutByteOrderMark(contents);
  if (lower == "obj") return ReadObj(name, text);
  if (lower == "off") return ReadOff(name, text);
  if (lower == "ply") return ReadPly(name, text);
  Fail(name, 0, "unknown mesh format " + Quote(format) + "; expected obj, off or ply");
}

namespace {

// Vertices near each other: a hash grid of cells of the tolerance's size, searched in the 27
// cells around a point.
class CoincidenceGrid {
 public:
  CoincidenceGrid(const std::vector<Eigen::Vector3d>& points, double tolerance) : points_(points) {
    Eigen::Vector3d lo = Eigen::Vector3d::Constant(INFINITY), hi = -lo;
    for (const Eigen::Vector3d& p : points) {
      lo = lo.cwiseMin(p);
      hi = hi.cwiseMax(p);
    }
    lo_ = lo;
    radius_ = points.empty() ? 0.0 : tolerance * (hi - lo).stableNorm();
    cells_.reserve(points.size());
  }

  // The first vertex inserted within the radius of point i, or -1.
  int Find(int i) const {
    if (!(radius_ > 0.0)) return -1;
    const auto [x, y, z] = CellOf(points_[i]);
    int found = -1;
    for (std::int64_t dx = -1; dx <= 1; ++dx)
      for (std::int64_t dy = -1; dy <= 1; ++dy)
        for (std::int64_t dz = -1; dz <= 1; ++dz) {
          const auto cell = cells_.find(Key(x + dx, y + dy, z + dz));
          if (cell == cells_.end()) continue;
          for (int j : cell->second)
            if ((points_[j] - points_[i]).norm() <= radius_ && (found < 0 || j < found)) found = j;
        }
    return found;
  }

  void Insert(int i) {
    if (!(radius_ > 0.0)) return;
    const auto [x, y, z] = CellOf(points_[i]);
    cells_[Key(x, y, z)].push_back(i);
  }

 private:
  std::array<std::int64_t, 3> CellOf(const Eigen::Vector3d& p) const {
    const Eigen::Vector3d c = ((p - lo_) / radius_).array().floor();
    return {static_cast<std::int64_t>(c.x()), static_cast<std::int64_t>(c.y()),
            static_cast<std::int64_t>(c.z())};
  }
  static std::uint64_t Key(std::int64_t x, std::int64_t y, std::int64_t z) {
    std::uint64_t h = static_cast<std::uint64_t>(x) * 0x9E3779B97F4A7C15ull;
    h ^= static_cast<std::uint64_t>(y) * 0xC2B2AE3D27D4EB4Full + (h << 6) + (h >> 2);
    h ^= static_cast<std::uint64_t>(z) * 0x165667B19E3779F9ull + (h << 6) + (h >> 2);
    return h;
  }

  const std::vector<Eigen::Vector3d>& points_;
  Eigen::Vector3d lo_;
  double radius_ = 0.0;
  std::unordered_map<std::uint64_t, std::vector<int>> cells_;
};

// Refuses two vertices used by faces within kWeldTolerance of each other, naming the first
// pair and the count.
void CheckWelded(const PolygonSoup& soup, const std::string& path) {
  std::vector<char> used(soup.vertices.size(), 0);
  for (const std::vector<int>& face : soup.faces)
    for (int v : face) used[v] = 1;
  CoincidenceGrid grid(soup.vertices, kWeldTolerance);
  int first = -1, first_match = -1, count = 0;
  for (int v = 0; v < static_cast<int>(soup.vertices.size()); ++v) {
    if (!used[v]) continue;
    const int match = grid.Find(v);
    if (match >= 0) {
      if (first < 0) first = v, first_match = match;
      ++count;
    }
    grid.Insert(v);
  }
  if (count == 0) return;
  Fail(path, LineOf(soup.vertex_lines, first),
       "vertex " + std::to_string(first) + " coincides with vertex " + std::to_string(first_match) +
           " (" + std::to_string(count) + " of the " + std::to_string(soup.vertices.size()) +
           " vertices repeat an earlier one, within 1e-9 of the bounding-box diagonal): its "
           "faces are not joined (an unwelded mesh); `weld` merges them");
}

}  // namespace

PolygonSoup WeldVertices(const PolygonSoup& soup, double tolerance, std::vector<int>* map) {
  PolygonSoup out;
  std::vector<int> index(soup.vertices.size(), -1);
  CoincidenceGrid grid(soup.vertices, tolerance);
  for (int v = 0; v < static_cast<int>(soup.vertices.size()); ++v) {
    const int match = grid.Find(v);
    if (match >= 0) {
      index[v] = index[match];
      continue;
    }
    grid.Insert(v);
    index[v] = static_cast<int>(out.vertices.size());
    out.vertices.push_back(soup.vertices[v]);
    if (v < static_cast<int>(soup.vertex_lines.size()))
      out.vertex_lines.push_back(soup.vertex_lines[v]);
  }
  out.faces = soup.faces;
  for (std::vector<int>& face : out.faces)
    for (int& v : face)
      if (v >= 0 && v < static_cast<int>(index.size())) v = index[v];
  out.face_lines = soup.face_lines;
  if (map) *map = std::move(index);
  return out;
}

PolyMesh BuildMesh(const PolygonSoup& given, const std::string& path,
                   const MeshRequirements& requirements, std::vector<int>* weld_map) {
  PolygonSoup welded;
  if (requirements.weld) {
    Validate(given, path, MeshRequirements{requirements.quads_only});
    welded = WeldVertices(given, kWeldTolerance, weld_map);
  }
  const PolygonSoup& soup = requirements.weld ? welded : given;
  Validate(soup, path, requirements);
  if (!requirements.weld && requirements.check_welded) CheckWelded(soup, path);

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

PolyMesh ReadMesh(const std::string& path, const MeshRequirements& requirements,
                  std::vector<int>* weld_map) {
  return BuildMesh(ReadPolygonSoup(path), path, requirements, weld_map);
}

void CheckMeshExtension(const std::string& path) { FormatOf(path); }

void WriteMeshAtomically(const PolyMesh& mesh, const std::string& path) {
  OutputFiles files;
  files.AddMesh(mesh, path);
  files.Commit();
}

std::string SegmentsObj(const std::string& comment,
                        const std::vector<std::pair<Eigen::Vector3d, Eigen::Vector3d>>& segments) {
  std::ostringstream out;
  out.precision(17);
  out << "# " << comment << '\n';
  for (const auto& [a, b] : segments)
    out << "v " << a.x() << ' ' << a.y() << ' ' << a.z() << "\nv " << b.x() << ' ' << b.y() << ' '
        << b.z() << '\n';
  for (size_t k = 0; k < segments.size(); ++k) out << "l " << 2 * k + 1 << ' ' << 2 * k + 2 << '\n';
  return out.str();
}

void WriteTextFileAtomically(const std::string& path, const std::string& contents) {
  OutputFiles files;
  files.AddText(path, contents);
  files.Commit();
}

OutputFiles::~OutputFiles() {
  if (!committed_) RollBack();
}

void OutputFiles::AddText(const std::string& path, const std::string& contents) {
  if (committed_) throw std::logic_error("OutputFiles::AddText after Commit");
  for (const Staged& s : staged_)
    if (s.path == path) throw std::logic_error("OutputFiles: " + path + " added twice");
  RemoveStaleTemporaries(path);
  staged_.push_back({path, SidePathFor(path, "tmp"), "", false});
  WriteNewFile(path, staged_.back().temporary, contents);
}

void OutputFiles::AddMesh(const PolyMesh& mesh, const std::string& path) {
  const Format format = FormatOf(path);
  for (const auto vh : mesh.vertices()) {
    const PolyMesh::Point& p = mesh.point(vh);
    if (!std::isfinite(p[0]) || !std::isfinite(p[1]) || !std::isfinite(p[2])) {
      Fail(path, 0,
           "vertex " + std::to_string(vh.idx()) + " has a non-finite coordinate; nothing written");
    }
  }
  AddText(path, MeshText(mesh, format));
}

void OutputFiles::Commit() {
  if (committed_) throw std::logic_error("OutputFiles::Commit twice");
  for (Staged& s : staged_) {
    // A hard link keeps the file being replaced, so that a later failure can put it back.
    std::error_code ec;
    if (fs::is_regular_file(s.path, ec)) {
      const std::string backup = SidePathFor(s.path, "old");
      fs::remove(backup, ec);
      fs::create_hard_link(s.path, backup, ec);
      if (!ec) s.backup = backup;
    }
    fs::rename(s.temporary, s.path, ec);
    if (ec) {
      const std::string path = s.path;
      const std::string message = "cannot move the temporary file " + QuotePath(s.temporary) +
                                  " into place: " + ec.message() + "; no output written";
      RollBack();
      Fail(path, 0, message);
    }
    s.moved = true;
  }
  committed_ = true;
  for (const Staged& s : staged_) {
    std::error_code ignored;
    if (!s.backup.empty()) fs::remove(s.backup, ignored);
  }
}

void OutputFiles::RollBack() {
  for (const Staged& s : staged_) {
    std::error_code ignored;
    if (!s.moved) {
      fs::remove(s.temporary, ignored);
      if (!s.backup.empty()) fs::remove(s.backup, ignored);
    } else if (!s.backup.empty()) {
      fs::rename(s.backup, s.path, ignored);  // the previous contents back
    } else {
      fs::remove(s.path, ignored);  // did not exist before
    }
  }
  staged_.clear();
}

}  // namespace gproj
