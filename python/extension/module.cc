// The `gproj` Python module: guided projection from numpy.
#include "python/extension/module.h"

#include "gproj/common/input_error.h"
#include "gproj/problems/run/option_schema.h"
#include "gproj/problems/run/registry.h"

PYBIND11_MODULE(_core, m) {
  m.doc() = R"(gproj: guided projection for architectural geometry, from numpy.

Meshes are numpy arrays: V (n, 3) float64 vertex positions and F (m, k) int32 faces (0-based
vertex indices; a list of faces for meshes with faces of different sizes).

    read_mesh, write_mesh            meshes in and out (.obj, .off, .ply)
    grid                             a test grid (V, F)
    planarize, anet, hnet, field,    the command line's problems, one call each with the same
    remesh, invert, cyclidic,        names and defaults, returning the result and the report as
    combescure, beams, mrevolution,  a dict (the keys of --report)
    weingarten, marionette, canal
    schema                           the registry of problems as a dict (`gproj schema`)
    Problem                          your own problem: variable blocks, built-in terms
                                     (planarity, closeness, fairness), terms written in Python,
                                     solved by guided projection or Ceres

Bad input raises ValueError with the command line's message.)";
  namespace py = pybind11;
  py::register_exception_translator([](std::exception_ptr error) {
    try {
      if (error) std::rethrow_exception(error);
    } catch (const gproj::OptionError& e) {
      PyErr_SetString(e.type_mismatch() ? PyExc_TypeError : PyExc_ValueError,
                      gproj::SpellOptions(e.what(), false).c_str());
    } catch (const gproj::InputError& e) {
      PyErr_SetString(PyExc_ValueError, gproj::SpellOptions(e.what(), false).c_str());
    }
  });
  gproj::python::BindMeshIo(m);
  gproj::python::BindRegistry(m);
  gproj::python::BindWeingarten(m);
  gproj::python::BindGenericProblem(m);
}
