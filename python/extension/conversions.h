#pragma once
// numpy arrays and Python objects to gproj's types and back. Bad input raises InputError (the
// module turns it into ValueError) with the command line's message for the same defect: the
// mesh checks are the library's (BuildMesh), with "mesh" in place of the file name.

#include <pybind11/numpy.h>
#include <pybind11/pybind11.h>

#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "gproj/geometry/io/mesh_io.h"

namespace gproj::python {

namespace py = pybind11;

// V: (n, 3) real array → #V points. `name` names the argument in messages.
std::vector<Eigen::Vector3d> PointsFromArray(const py::handle& array, const std::string& name);
// F: (m, k) integer array, or a sequence of sequences of vertex indices → #F faces.
std::vector<std::vector<int>> FacesFromPython(const py::handle& faces, const std::string& name);
// The mesh of (V, F), validated like a mesh file (quads only when `quads_only`).
// "(3, 1600)", "(4,)": an array's shape as numpy prints it.
std::string ShapeText(const py::array& array);

PolyMesh MeshFromArrays(const py::handle& vertices, const py::handle& faces,
                        const MeshRequirements& requirements, std::vector<int>* weld_map = nullptr);

// #V × 3 float64 array of the mesh's points.
py::array_t<double> VerticesToArray(const PolyMesh& mesh);
// (m, k) int32 array when every face has k vertices, else a list of lists.
py::object FacesToPython(const PolyMesh& mesh);
// (V, F) of a mesh.
py::tuple MeshToPython(const PolyMesh& mesh);

// A point (x, y, z) from a sequence of three finite numbers; InputError naming `name`.
Eigen::Vector3d Vector3FromPython(const py::handle& value, const std::string& name);

// JSON values as Python objects (null → None, objects → dict, arrays → list) and back (numpy
// arrays through tolist()).
py::object JsonToPython(const nlohmann::json& j);
nlohmann::json PythonToJson(const py::handle& value);

}  // namespace gproj::python
