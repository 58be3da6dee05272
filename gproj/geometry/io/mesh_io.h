#pragma once
// Polygon-mesh input and output for gproj: OBJ / OFF / PLY, with validation that names the
// file, line, vertex or face of every problem, and atomic writes (temporary file + rename).

#include <Eigen/Core>
#include <OpenMesh/Core/Mesh/PolyMesh_ArrayKernelT.hh>
#include <stdexcept>
#include <string>
#include <string_view>
#include <vector>

#include "gproj/common/input_error.h"

namespace gproj {

// Double-precision OpenMesh polygon mesh.
struct MeshTraits : public OpenMesh::DefaultTraits {
  using Point = OpenMesh::Vec3d;
  using Normal = OpenMesh::Vec3d;
};
using PolyMesh = OpenMesh::PolyMesh_ArrayKernelT<MeshTraits>;

// Faces and vertices as read, before any topology is built. Line numbers are 1-based source
// lines for text formats and 0 where the format has none (binary PLY).
struct PolygonSoup {
  std::vector<Eigen::Vector3d> vertices;  // #V
  std::vector<std::vector<int>> faces;    // #F, 0-based vertex indices
  std::vector<int> vertex_lines;          // #V
  std::vector<int> face_lines;            // #F
};

struct MeshRequirements {
  bool quads_only = false;  // every face must have exactly four vertices
  // Vertices within kWeldTolerance of an earlier one are merged into it (an unwelded mesh, each
  // face with its own copies of its corners, as CAD exports often are, becomes one surface);
  // without it such a mesh is refused.
  bool weld = false;
  // Whether coincident vertices are refused (false for meshes being written, not read).
  bool check_welded = true;
};

// Coincidence tolerance of welding, relative to the bounding-box diagonal.
constexpr double kWeldTolerance = 1e-9;

// `soup` with every vertex within `tolerance` × its bounding-box diagonal of an earlier vertex
// merged into the earliest, the faces renumbered; (*map)[v] is the new index of vertex v.
PolygonSoup WeldVertices(const PolygonSoup& soup, double tolerance, std::vector<int>* map);

// Reads OBJ / OFF / PLY (ASCII or binary) with gproj's own readers, which name the line (or,
// in binary PLY, the element) of every problem. Text may start with a UTF-8 byte-order mark
// and use CRLF line ends. Throws InputError for: unreadable file, unknown extension, empty
// file / no faces, malformed numbers or headers, NaN or infinite coordinates, face index out
// of range, a face of fewer than 3 vertices (OFF, PLY), counts that the file size or the
// machine's memory cannot hold (checked before allocating).
PolygonSoup ReadPolygonSoup(const std::string& path);
// The same readers on a file's contents held in memory (the HTTP service's uploads): `format`
// is "obj", "off" or "ply" (any case); `name` stands for the path in messages.
PolygonSoup ParsePolygonSoup(const std::string& name, const std::string& format,
                             std::string_view contents);

// Validates and builds the mesh. Throws InputError for: no faces, a face with fewer than 3
// vertices or a repeated vertex, a degenerate face (zero area), a non-manifold edge (shared
// by more than two faces, or by two faces with the same orientation), a non-quad face when
// requirements.quads_only, two vertices used by faces within kWeldTolerance of each other
// unless requirements.weld (which merges them first and gives the map of WeldVertices in
// *weld_map when not null). `path` is used in messages only.
PolyMesh BuildMesh(const PolygonSoup& soup, const std::string& path,
                   const MeshRequirements& requirements, std::vector<int>* weld_map = nullptr);

// ReadPolygonSoup + BuildMesh.
PolyMesh ReadMesh(const std::string& path, const MeshRequirements& requirements = {},
                  std::vector<int>* weld_map = nullptr);

// Writes by extension (.obj/.off/.ply) to a temporary file in the same directory, then renames
// it over `path`. On any failure the temporary is removed, `path` is untouched, and an
// InputError naming the path is thrown. Throws if any coordinate is non-finite.
void WriteMeshAtomically(const PolyMesh& mesh, const std::string& path);
// Throws InputError unless `path` names a mesh format gproj reads and writes (.obj, .off,
// .ply, any case).
void CheckMeshExtension(const std::string& path);

// Line segments (a, b) as OBJ text: a comment line, two vertices per segment (exact doubles),
// then one "l" element per segment. For fields and axes that are not faces.
std::string SegmentsObj(const std::string& comment,
                        const std::vector<std::pair<Eigen::Vector3d, Eigen::Vector3d>>& segments);

// Writes `contents` to `path` atomically (temporary file + rename); throws InputError.
void WriteTextFileAtomically(const std::string& path, const std::string& contents);

// The files of one run, written all or none. Each Add* writes its contents to a hidden temporary
// next to the target and flushes it to disk, so a full disk or an unwritable folder shows before
// any target changes; Commit then renames the temporaries over their targets. If an Add* or
// Commit throws (InputError naming the path), or the set is destroyed uncommitted, every
// temporary is removed and the targets Commit had already replaced get their previous contents
// back (or disappear if they did not exist): a failed run leaves none of its outputs.
class OutputFiles {
 public:
  OutputFiles() = default;
  OutputFiles(const OutputFiles&) = delete;
  OutputFiles& operator=(const OutputFiles&) = delete;
  ~OutputFiles();

  void AddText(const std::string& path, const std::string& contents);
  // By extension (.obj/.off/.ply), exact doubles; throws if any coordinate is non-finite.
  void AddMesh(const PolyMesh& mesh, const std::string& path);
  void Commit();

 private:
  struct Staged {
    std::string path, temporary, backup;  // backup: hard link to the replaced file, if any
    bool moved = false;
  };
  void RollBack();
  std::vector<Staged> staged_;
  bool committed_ = false;
};

}  // namespace gproj
