#pragma once
// The parts of the `gproj` Python module, each defined in its own file (module.cc calls them).

#include <pybind11/pybind11.h>

namespace gproj::python {

namespace py = pybind11;

void BindMeshIo(py::module_& m);          // read_mesh, write_mesh, face_values
void BindRegistry(py::module_& m);        // the registry's problems (planarize, ...), schema
void BindWeingarten(py::module_& m);      // bspline_curvature
void BindGenericProblem(py::module_& m);  // Problem: blocks, terms, solve

}  // namespace gproj::python
