// gproj.read_mesh, gproj.write_mesh and gproj.face_values.
#include <string>
#include <vector>

#include "gproj/geometry/mesh/quad_shape.h"
#include "python/extension/conversions.h"
#include "python/extension/module.h"

namespace gproj::python {
namespace {

py::tuple ReadMeshArrays(const std::string& path) {
  PolyMesh mesh;
  {
    py::gil_scoped_release release;
    mesh = ReadMesh(path, MeshRequirements{false, false, false});  // checked when run
  }
  return MeshToPython(mesh);
}

void WriteMeshArrays(const std::string& path, const py::object& vertices, const py::object& faces) {
  CheckMeshExtension(path);
  const PolyMesh mesh = MeshFromArrays(vertices, faces, MeshRequirements{false, false, false});
  py::gil_scoped_release release;
  WriteMeshAtomically(mesh, path);
}

// Per quad: the columns of `--face-values` (MeasureFaceValues), as arrays.
py::dict FaceValueArrays(const py::object& vertices, const py::object& faces, bool circular) {
  const FaceValues values = MeasureFaceValues(
      MeshFromArrays(vertices, faces, MeshRequirements{true, false, false}), circular);
  const auto array = [](const std::vector<double>& v) {
    return py::array_t<double>(static_cast<py::ssize_t>(v.size()), v.data());
  };
  py::array_t<bool> convex(static_cast<py::ssize_t>(values.convex.size()));
  for (std::size_t f = 0; f < values.convex.size(); ++f) convex.mutable_at(f) = values.convex[f];
  py::dict result;
  result["planarity"] = array(values.planarity);
  result["planarity_abs"] = array(values.planarity_abs);
  result["kink_deg"] = array(values.kink_deg);
  result["min_angle_deg"] = array(values.min_angle_deg);
  result["convex"] = convex;
  if (circular) result["concyclicity"] = array(values.concyclicity);
  return result;
}

}  // namespace

void BindMeshIo(py::module_& m) {
  m.def("read_mesh", &ReadMeshArrays, py::arg("path"),
        R"(Reads an .obj, .off or .ply polygon mesh, checked like the command line's inputs.

    path: the file.

Returns V: (n, 3) float64 and F: (m, k) int32 when every face has k vertices, else a list of
faces (lists of 0-based vertex indices). Raises ValueError naming the file, line and rule for a
bad file (the command line's message).
)");
  m.def("write_mesh", &WriteMeshArrays, py::arg("path"), py::arg("V"), py::arg("F"),
        R"(Writes a mesh atomically (temporary file, then rename) with exact double coordinates.

    path: .obj, .off or .ply.
    V: (n, 3) float64 vertex positions.
    F: (m, k) integer faces, or a list of faces (0-based vertex indices).

Raises ValueError for a bad mesh (non-finite coordinate, index out of range, degenerate or
non-manifold face) or a path that cannot be written.
)");
  m.def(
      "face_values", &FaceValueArrays, py::arg("V"), py::arg("F"), py::kw_only(),
      py::arg("circular") = false,
      R"(The per-quad measures of `--face-values` (and of the report's maxima), as arrays of shape (m,).

    V: (n, 3) float64, F: (m, 4) integer quads.
    circular: also give each quad's concyclicity.

Returns {"planarity": distance between the diagonals / the mesh's mean edge length,
"planarity_abs": that distance in the mesh's units, "kink_deg": the larger angle between the
two triangles of either diagonal split, "min_angle_deg": the smallest corner angle, "convex":
bool, and with circular "concyclicity": distance of the corners to their fitted circle / mean
edge}.
)");
}

}  // namespace gproj::python
