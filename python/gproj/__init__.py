"""gproj: guided projection for architectural geometry, from numpy.

Meshes are numpy arrays: V (n, 3) float vertex positions and F (m, k) integer faces (0-based
vertex indices; a list of faces for meshes with faces of different sizes).

    read_mesh, write_mesh            meshes in and out (.obj, .off, .ply; paths or str)
    grid                             a test grid, as a Mesh (V, F)
    planarize, anet, hnet, field,    the command line's problems, one function each with the
    remesh, invert, cyclidic,        same names, defaults and checks; each returns a Result
    combescure, beams, mrevolution,  (vertices and faces or output, the other outputs, a
    weingarten, marionette, canal    Report) and takes an options object (PlanarizeOptions, ...)
    run(problem, ...)                a problem's function by its name
    schema()                         the registry of problems as a dict (`gproj schema`)
    Problem                          your own problem: variable blocks, built-in terms
                                     (planarity, closeness, fairness), terms written in Python,
                                     solved by guided projection or Ceres

Bad input raises ValueError or TypeError naming the argument; a run's warnings are
GprojWarning (a UserWarning).
"""

from gproj import _core
from gproj._core import Problem, schema
from gproj._utilities import bspline_curvature, face_values, read_mesh, write_mesh
from gproj._problems import GprojWarning, make_problems, run, _FUNCTIONS
from gproj._results import Mesh, Report, Result

__version__: str = _core.__version__

_functions, _options, _results = make_problems()
_FUNCTIONS.update(_functions)
globals().update(_functions)
globals().update(_options)
globals().update(_results)

__all__ = sorted(
    ["Mesh", "Report", "Result", "GprojWarning", "Problem", "bspline_curvature", "face_values",
     "schema", "read_mesh", "write_mesh", "run", "__version__"] + list(_functions) +
    list(_options) + list(_results))

del _functions, _options, _results, make_problems
