# Generated from the registry by `python3 -m gproj._stubgen`; do not edit.
import os
from typing import Any, Callable, Dict, List, Literal, Mapping, Optional, Sequence, Tuple, Union

import numpy as np
import numpy.typing as npt
from numpy.typing import ArrayLike

from gproj._core import Problem as Problem
from gproj._core import schema as schema
from gproj._utilities import bspline_curvature as bspline_curvature
from gproj._utilities import face_values as face_values
from gproj._utilities import read_mesh as read_mesh
from gproj._utilities import write_mesh as write_mesh
from gproj._problems import GprojWarning as GprojWarning
from gproj._results import Mesh as Mesh
from gproj._results import Report as Report
from gproj._results import Result as Result

__version__: str

def run(problem: str, *args: Any, **kwargs: Any) -> Result: ...

class PlanarizeOptions:
    """The options of planarize()."""
    solver: Literal['gp', 'ceres']
    """(choice) gp: guided projection; ceres: Levenberg-Marquardt on the same rows (cross-check)."""
    tolerance: float
    """(number, > 0) Stop when max planarity (diagonal distance; for a polygon of 5 or more vertices, twice its largest distance from its least-squares plane; / mean edge length) is <= this."""
    closeness: float
    """(number, >= 0) Weight of closeness to the input vertices (mesh scaled to mean edge 1)."""
    circular: bool
    """(bool) Circular quads (planar and concyclic, 000 §2) instead of planar ones; the tolerance also bounds the concyclicity (distance to the fitted circle / mean edge)."""
    fairness_order: int
    """(int, >= 2, <= 3) 2: second differences, 3: third differences."""
    ceres_soft_scale: float
    """(number, >= 0) With solver ceres: fixed factor on the closeness and fairness weights (0: tolerance / 100)."""
    max_iterations: int
    """(int, >= 0, <= 100000) Iterations at most."""
    fairness: float
    """(number, >= 0) omega_f: weight of the fairness (second differences along polylines; at vertices of polygon meshes that no polyline passes, twice the offset from the neighbours' centroid)."""
    soft_decay: float
    """(number, >= 1e-12, <= 1) Closeness and fairness weights are multiplied by this each iteration ...."""
    soft_floor: float
    """(number, >= 0, <= 1) ... down to this fraction of their initial value."""
    soft_residual: float
    """(number, >= 0) ... and, when > 0, also by this times the max constraint residual of the iteration (the soft weights vanish as the constraints converge)."""
    epsilon: float
    """(number, > 0) epsilon: weight of the proximal term eps^2 |x - x^k|^2."""
    epsilon_min: float
    """(number, >= 0) When > 0, epsilon follows the constraint residual down to this (quadratic convergence near the solution)."""
    linear_solver: Literal['cholmod', 'eigen']
    """(choice) Sparse Cholesky backend for gp: cholmod (supernodal) or eigen."""
    threads: int
    """(int, >= 0, <= 256) Threads for BLAS / Ceres (0: default)."""
    monotone: bool
    """(bool) Monotone steps: keep a step only if it lowers the energy, else damp it (plain steps: take every Gauss-Newton step)."""
    step_control: Literal['dogleg', 'damping']
    """(choice) How a monotone step that does not lower the energy is shortened: dogleg (a trust region on the iteration's factor: a rejected trial costs an evaluation) or damping (epsilon grows and the step is refactorised)."""
    min_angle: float
    """(number, deg, >= 0, <= 59.9) Every quad corner angle stays within [min_angle, 180 - min_angle] (a corner already outside in the input is kept from getting worse); 0 only keeps quads convex."""
    edge_length: Optional[Sequence[float]]
    """(numbers, input units, >= 0, 2 values) Every edge length ends within these, to the tolerance (an edge outside in the input is brought in; the run converges only when all are); without it no edge shrinks below 10% of its input length."""
    allow_folds: bool
    """(bool) No corner-angle or default edge bounds: quads may turn non-convex or fold."""
    fix_boundary: bool
    """(bool) Every boundary vertex stays where it is."""
    glide_boundary: bool
    """(bool) Boundary vertices slide along the input's boundary (they stay on it to rounding)."""
    net: Literal['edges', 'diagonal']
    """(choice) Which faces to make planar: edges (the mesh's own faces) or diagonal (the faces of the quad mesh's diagonal meshes: the ring of every inner vertex, whose edges are the quads' diagonals; the result keeps the input's faces)."""
    diagonal_colour: Optional[int]
    """(int, >= 0, <= 1) With net diagonal: one diagonal mesh only, by the colour of its vertices (0: the one through vertex 0; the other colour's vertices stay in place); not given: both."""
    def __init__(
        self,
        *,
        solver: Literal['gp', 'ceres'] = 'gp',
        tolerance: float = 1e-09,
        closeness: float = 100.0,
        circular: bool = False,
        fairness_order: int = 2,
        ceres_soft_scale: float = 0.0,
        max_iterations: int = 50,
        fairness: float = 1.0,
        soft_decay: float = 0.1,
        soft_floor: float = 0.0,
        soft_residual: float = 1.0,
        epsilon: float = 0.001,
        epsilon_min: float = 1e-06,
        linear_solver: Literal['cholmod', 'eigen'] = 'cholmod',
        threads: int = 0,
        monotone: bool = True,
        step_control: Literal['dogleg', 'damping'] = 'dogleg',
        min_angle: float = 5.0,
        edge_length: Optional[Sequence[float]] = None,
        allow_folds: bool = False,
        fix_boundary: bool = False,
        glide_boundary: bool = False,
        net: Literal['edges', 'diagonal'] = 'edges',
        diagonal_colour: Optional[int] = None,
    ) -> None: ...

class PlanarizeResult(Result):
    """The result of planarize(): the planarised mesh."""
    output: Optional[Mesh]
    picture: Optional[str]
    """a shaded picture of the result, each face coloured by its planarity (None unless asked in outputs=)"""
    face_values: Optional[str]
    """per-face values: face, planarity (/ mean edge), planarity_abs (input units), kink_deg (between the quad's two triangles), min_angle_deg (and concyclicity when circular) (None unless asked in outputs=)"""
    heatmap: Optional[str]
    """the result with a colour per face (planarity, log scale; the scale is in the report) (None unless asked in outputs=)"""
    diagonal_mesh: Optional[Mesh]
    """with net diagonal: the planarised diagonal faces on the input's vertices (the picture, face values and heat map show these faces) (None unless asked in outputs=)"""

def planarize(
    V: ArrayLike,
    F: ArrayLike,
    *,
    options: Optional[PlanarizeOptions] = None,
    reference: Optional[Tuple[ArrayLike, ArrayLike]] = None,
    fixed: Union[ArrayLike, str, os.PathLike[str], None] = None,
    weld: bool = False,
    solver: Literal['gp', 'ceres'] = 'gp',
    tolerance: float = 1e-09,
    closeness: float = 100.0,
    circular: bool = False,
    fairness_order: int = 2,
    ceres_soft_scale: float = 0.0,
    max_iterations: int = 50,
    fairness: float = 1.0,
    soft_decay: float = 0.1,
    soft_floor: float = 0.0,
    soft_residual: float = 1.0,
    epsilon: float = 0.001,
    epsilon_min: float = 1e-06,
    linear_solver: Literal['cholmod', 'eigen'] = 'cholmod',
    threads: int = 0,
    monotone: bool = True,
    step_control: Literal['dogleg', 'damping'] = 'dogleg',
    min_angle: float = 5.0,
    edge_length: Optional[Sequence[float]] = None,
    allow_folds: bool = False,
    fix_boundary: bool = False,
    glide_boundary: bool = False,
    net: Literal['edges', 'diagonal'] = 'edges',
    diagonal_colour: Optional[int] = None,
    outputs: Sequence[str] = (),
    callback: Optional[Callable[[Dict[str, Any]], Optional[bool]]] = None,
) -> PlanarizeResult:
    """PQ planarisation: make every quad of a mesh planar (or circular: planar and concyclic) while staying close to the input and fair. Polygon meshes too (hexagonal, hex-dominant: every face of 4 or more vertices planar; triangles are left to closeness and fairness).

Arguments:
    V: the mesh: (n, 3) float vertex positions. Quad mesh (or any polygon mesh; circular needs quads) to planarise.
    F: (m, k) integer faces, 0-based (a list of faces for mixed sizes).
    options: a PlanarizeOptions; keyword arguments override its fields.
    reference: a mesh (V, F). Reference surface (triangle or polygon mesh): vertices keep close to it through the tangent plane of their closest point (sliding along it) instead of to their start.
    fixed: 0-based vertex ids, a boolean mask over the vertices, or the path of a file of ids. Vertices that do not move at all (0-based ids; returned bit for bit).
    weld: merge the input meshes' coincident vertices (within 1e-9 of the bounding-box diagonal) first, as unwelded exports need; without it such a mesh is refused. Vertex ids (fixed, ...) then number the welded mesh; result.weld_map maps each input vertex to it.
    solver: (choice) gp: guided projection; ceres: Levenberg-Marquardt on the same rows (cross-check).
    tolerance: (number, > 0) Stop when max planarity (diagonal distance; for a polygon of 5 or more vertices, twice its largest distance from its least-squares plane; / mean edge length) is <= this.
    closeness: (number, >= 0) Weight of closeness to the input vertices (mesh scaled to mean edge 1).
    circular: (bool) Circular quads (planar and concyclic, 000 §2) instead of planar ones; the tolerance also bounds the concyclicity (distance to the fitted circle / mean edge).
    fairness_order: (int, >= 2, <= 3) 2: second differences, 3: third differences.
    ceres_soft_scale: (number, >= 0) With solver ceres: fixed factor on the closeness and fairness weights (0: tolerance / 100).
    max_iterations: (int, >= 0, <= 100000) Iterations at most.
    fairness: (number, >= 0) omega_f: weight of the fairness (second differences along polylines; at vertices of polygon meshes that no polyline passes, twice the offset from the neighbours' centroid).
    soft_decay: (number, >= 1e-12, <= 1) Closeness and fairness weights are multiplied by this each iteration ....
    soft_floor: (number, >= 0, <= 1) ... down to this fraction of their initial value.
    soft_residual: (number, >= 0) ... and, when > 0, also by this times the max constraint residual of the iteration (the soft weights vanish as the constraints converge).
    epsilon: (number, > 0) epsilon: weight of the proximal term eps^2 |x - x^k|^2.
    epsilon_min: (number, >= 0) When > 0, epsilon follows the constraint residual down to this (quadratic convergence near the solution).
    linear_solver: (choice) Sparse Cholesky backend for gp: cholmod (supernodal) or eigen.
    threads: (int, >= 0, <= 256) Threads for BLAS / Ceres (0: default).
    monotone: (bool) Monotone steps: keep a step only if it lowers the energy, else damp it (plain steps: take every Gauss-Newton step).
    step_control: (choice) How a monotone step that does not lower the energy is shortened: dogleg (a trust region on the iteration's factor: a rejected trial costs an evaluation) or damping (epsilon grows and the step is refactorised).
    min_angle: (number, deg, >= 0, <= 59.9) Every quad corner angle stays within [min_angle, 180 - min_angle] (a corner already outside in the input is kept from getting worse); 0 only keeps quads convex.
    edge_length: (numbers, input units, >= 0, 2 values) Every edge length ends within these, to the tolerance (an edge outside in the input is brought in; the run converges only when all are); without it no edge shrinks below 10% of its input length.
    allow_folds: (bool) No corner-angle or default edge bounds: quads may turn non-convex or fold.
    fix_boundary: (bool) Every boundary vertex stays where it is.
    glide_boundary: (bool) Boundary vertices slide along the input's boundary (they stay on it to rounding).
    net: (choice) Which faces to make planar: edges (the mesh's own faces) or diagonal (the faces of the quad mesh's diagonal meshes: the ring of every inner vertex, whose edges are the quads' diagonals; the result keeps the input's faces).
    diagonal_colour: (int, >= 0, <= 1) With net diagonal: one diagonal mesh only, by the colour of its vertices (0: the one through vertex 0; the other colour's vertices stay in place); not given: both.
    outputs: optional outputs to make as well (picture, face_values, heatmap, diagonal_mesh); each is an attribute of the result.
    callback: called with each iteration record (the keys of report.history's entries); returning False stops the run (status USER_ABORT). Ctrl-C stops it too and raises KeyboardInterrupt.

Returns a PlanarizeResult: `report` (a Report: status, converged, iterations, history, initial and final measures, options), `vertices` and `faces` (the mesh): the planarised mesh, and
    picture: a shaded picture of the result, each face coloured by its planarity (None unless asked in outputs=)
    face_values: per-face values: face, planarity (/ mean edge), planarity_abs (input units), kink_deg (between the quad's two triangles), min_angle_deg (and concyclicity when circular) (None unless asked in outputs=)
    heatmap: the result with a colour per face (planarity, log scale; the scale is in the report) (None unless asked in outputs=)
    diagonal_mesh: with net diagonal: the planarised diagonal faces on the input's vertices (the picture, face values and heat map show these faces) (None unless asked in outputs=)
When the run fails numerically, the result's mesh and outputs are None and report.status is FAILURE.

Raises TypeError or ValueError naming the argument for bad arguments; warns (GprojWarning) when the input is far from the asked net or the result needs attention.
"""
    ...

class DualOptions:
    """The options of dual()."""
    start: Literal['centroids', 'tangent_planes']
    """(choice) Where each dual vertex sits: centroids (of its triangle) or tangent_planes (where the tangent planes of its triangle's three vertices meet, where that is well conditioned; planar faces to first order, the start of Wang, Liu et al. 2008)."""
    boundary: Literal['drop', 'keep']
    """(choice) drop: faces for the interior vertices only; keep: boundary vertices get faces too, closed by the midpoints of their boundary edges and the vertex itself."""
    def __init__(
        self,
        *,
        start: Literal['centroids', 'tangent_planes'] = 'centroids',
        boundary: Literal['drop', 'keep'] = 'drop',
    ) -> None: ...

class DualResult(Result):
    """The result of dual(): the dual polygon mesh."""
    output: Optional[Mesh]
    picture: Optional[str]
    """a shaded picture of the dual (None unless asked in outputs=)"""

def dual(
    V: ArrayLike,
    F: ArrayLike,
    *,
    options: Optional[DualOptions] = None,
    weld: bool = False,
    start: Literal['centroids', 'tangent_planes'] = 'centroids',
    boundary: Literal['drop', 'keep'] = 'drop',
    outputs: Sequence[str] = (),
    callback: Optional[Callable[[Dict[str, Any]], Optional[bool]]] = None,
) -> DualResult:
    """The dual polygon mesh of a triangle mesh: one vertex per triangle, one face per vertex (hexagons where the triangle mesh has valence 6), the start of a planar hexagonal or hex-dominant mesh. Dual vertices at the triangles' centroids or where their vertices' tangent planes meet.

Arguments:
    V: the mesh: (n, 3) float vertex positions. Triangle mesh.
    F: (m, k) integer faces, 0-based (a list of faces for mixed sizes).
    options: a DualOptions; keyword arguments override its fields.
    weld: merge the input meshes' coincident vertices (within 1e-9 of the bounding-box diagonal) first, as unwelded exports need; without it such a mesh is refused. Vertex ids (fixed, ...) then number the welded mesh; result.weld_map maps each input vertex to it.
    start: (choice) Where each dual vertex sits: centroids (of its triangle) or tangent_planes (where the tangent planes of its triangle's three vertices meet, where that is well conditioned; planar faces to first order, the start of Wang, Liu et al. 2008).
    boundary: (choice) drop: faces for the interior vertices only; keep: boundary vertices get faces too, closed by the midpoints of their boundary edges and the vertex itself.
    outputs: optional outputs to make as well (picture); each is an attribute of the result.
    callback: called with each iteration record (the keys of report.history's entries); returning False stops the run (status USER_ABORT). Ctrl-C stops it too and raises KeyboardInterrupt.

Returns a DualResult: `report` (a Report: status, converged, iterations, history, initial and final measures, options), `vertices` and `faces` (the mesh): the dual polygon mesh, and
    picture: a shaded picture of the dual (None unless asked in outputs=)
When the run fails numerically, the result's mesh and outputs are None and report.status is FAILURE.

Raises TypeError or ValueError naming the argument for bad arguments; warns (GprojWarning) when the input is far from the asked net or the result needs attention.
"""
    ...

class AnetOptions:
    """The options of anet()."""
    solver: Literal['gp', 'ceres']
    """(choice) gp: guided projection; ceres: Levenberg-Marquardt on the same rows (cross-check)."""
    star_form: Literal['normals', 'quads']
    """(choice) Vertex-star planarity: normals (auxiliary normal per inner vertex) or quads (n-2 quads of each star)."""
    tolerance: float
    """(number, > 0) The A-net step stops when max star planarity (neighbour distance from the star plane / mean edge) is <= this."""
    tangent: float
    """(number, >= 0) Weight of the distance to the reference's tangent planes."""
    point: float
    """(number, >= 0) Weight of the distance to the reference's closest points."""
    fairness_order: int
    """(int, >= 2, <= 3) 2: second differences, 3: third differences."""
    max_iterations: int
    """(int, >= 0, <= 100000) Iterations at most."""
    fairness: float
    """(number, >= 0) omega_f: weight of the fairness (second differences along polylines; at vertices of polygon meshes that no polyline passes, twice the offset from the neighbours' centroid)."""
    soft_decay: float
    """(number, >= 1e-12, <= 1) Closeness and fairness weights are multiplied by this each iteration ...."""
    soft_floor: float
    """(number, >= 0, <= 1) ... down to this fraction of their initial value."""
    soft_residual: float
    """(number, >= 0) ... and, when > 0, also by this times the max constraint residual of the iteration (the soft weights vanish as the constraints converge)."""
    epsilon: float
    """(number, > 0) epsilon: weight of the proximal term eps^2 |x - x^k|^2."""
    epsilon_min: float
    """(number, >= 0) When > 0, epsilon follows the constraint residual down to this (quadratic convergence near the solution)."""
    linear_solver: Literal['cholmod', 'eigen']
    """(choice) Sparse Cholesky backend for gp: cholmod (supernodal) or eigen."""
    threads: int
    """(int, >= 0, <= 256) Threads for BLAS / Ceres (0: default)."""
    monotone: bool
    """(bool) Monotone steps: keep a step only if it lowers the energy, else damp it (plain steps: take every Gauss-Newton step)."""
    step_control: Literal['dogleg', 'damping']
    """(choice) How a monotone step that does not lower the energy is shortened: dogleg (a trust region on the iteration's factor: a rejected trial costs an evaluation) or damping (epsilon grows and the step is refactorised)."""
    min_angle: float
    """(number, deg, >= 0, <= 59.9) Every quad corner angle stays within [min_angle, 180 - min_angle] (a corner already outside in the input is kept from getting worse); 0 only keeps quads convex."""
    edge_length: Optional[Sequence[float]]
    """(numbers, input units, >= 0, 2 values) Every edge length ends within these, to the tolerance (an edge outside in the input is brought in; the run converges only when all are); without it no edge shrinks below 10% of its input length."""
    allow_folds: bool
    """(bool) No corner-angle or default edge bounds: quads may turn non-convex or fold."""
    fix_boundary: bool
    """(bool) Every boundary vertex stays where it is."""
    glide_boundary: bool
    """(bool) Boundary vertices slide along the input's boundary (they stay on it to rounding)."""
    net: Literal['edges', 'diagonal']
    """(choice) Whose stars must be planar: edges (each vertex with its neighbours: the mesh is the A-net) or diagonal (each vertex with the corners opposite it in its quads: the mesh's two diagonal meshes are A-nets, for meshes whose diagonals follow the asymptotic directions; the quads, their bounds and fairness stay the mesh's own)."""
    def __init__(
        self,
        *,
        solver: Literal['gp', 'ceres'] = 'gp',
        star_form: Literal['normals', 'quads'] = 'normals',
        tolerance: float = 1e-09,
        tangent: float = 100.0,
        point: float = 10.0,
        fairness_order: int = 2,
        max_iterations: int = 50,
        fairness: float = 0.5,
        soft_decay: float = 0.1,
        soft_floor: float = 1e-12,
        soft_residual: float = 1.0,
        epsilon: float = 0.001,
        epsilon_min: float = 1e-06,
        linear_solver: Literal['cholmod', 'eigen'] = 'cholmod',
        threads: int = 0,
        monotone: bool = True,
        step_control: Literal['dogleg', 'damping'] = 'dogleg',
        min_angle: float = 5.0,
        edge_length: Optional[Sequence[float]] = None,
        allow_folds: bool = False,
        fix_boundary: bool = False,
        glide_boundary: bool = False,
        net: Literal['edges', 'diagonal'] = 'edges',
    ) -> None: ...

class AnetResult(Result):
    """The result of anet(): the A-net."""
    output: Optional[Mesh]
    picture: Optional[str]
    """a shaded picture of the result, each face coloured by the star planarity of its corners (None unless asked in outputs=)"""
    face_values: Optional[str]
    """per-face values: face, star_planarity (largest of its corners), kink_deg, min_angle_deg (None unless asked in outputs=)"""
    heatmap: Optional[str]
    """the result with a colour per face (star planarity, log scale; the scale is in the report) (None unless asked in outputs=)"""

def anet(
    V: ArrayLike,
    F: ArrayLike,
    *,
    options: Optional[AnetOptions] = None,
    reference: Optional[Tuple[ArrayLike, ArrayLike]] = None,
    fixed: Union[ArrayLike, str, os.PathLike[str], None] = None,
    weld: bool = False,
    solver: Literal['gp', 'ceres'] = 'gp',
    star_form: Literal['normals', 'quads'] = 'normals',
    tolerance: float = 1e-09,
    tangent: float = 100.0,
    point: float = 10.0,
    fairness_order: int = 2,
    max_iterations: int = 50,
    fairness: float = 0.5,
    soft_decay: float = 0.1,
    soft_floor: float = 1e-12,
    soft_residual: float = 1.0,
    epsilon: float = 0.001,
    epsilon_min: float = 1e-06,
    linear_solver: Literal['cholmod', 'eigen'] = 'cholmod',
    threads: int = 0,
    monotone: bool = True,
    step_control: Literal['dogleg', 'damping'] = 'dogleg',
    min_angle: float = 5.0,
    edge_length: Optional[Sequence[float]] = None,
    allow_folds: bool = False,
    fix_boundary: bool = False,
    glide_boundary: bool = False,
    net: Literal['edges', 'diagonal'] = 'edges',
    outputs: Sequence[str] = (),
    callback: Optional[Callable[[Dict[str, Any]], Optional[bool]]] = None,
) -> AnetResult:
    """A-net (004 §3.2): make the vertex stars of a quad mesh roughly along asymptotic directions planar, close to a reference surface (the input itself by default) and fair.

Arguments:
    V: the mesh: (n, 3) float vertex positions. Quad mesh roughly along asymptotic directions (inner vertices of even valence).
    F: (m, k) integer faces, 0-based (a list of faces for mixed sizes).
    options: a AnetOptions; keyword arguments override its fields.
    reference: a mesh (V, F). Reference surface (polygon mesh) to stay close to; default: the input itself.
    fixed: 0-based vertex ids, a boolean mask over the vertices, or the path of a file of ids. Vertices that do not move at all (0-based ids; returned bit for bit).
    weld: merge the input meshes' coincident vertices (within 1e-9 of the bounding-box diagonal) first, as unwelded exports need; without it such a mesh is refused. Vertex ids (fixed, ...) then number the welded mesh; result.weld_map maps each input vertex to it.
    solver: (choice) gp: guided projection; ceres: Levenberg-Marquardt on the same rows (cross-check).
    star_form: (choice) Vertex-star planarity: normals (auxiliary normal per inner vertex) or quads (n-2 quads of each star).
    tolerance: (number, > 0) The A-net step stops when max star planarity (neighbour distance from the star plane / mean edge) is <= this.
    tangent: (number, >= 0) Weight of the distance to the reference's tangent planes.
    point: (number, >= 0) Weight of the distance to the reference's closest points.
    fairness_order: (int, >= 2, <= 3) 2: second differences, 3: third differences.
    max_iterations: (int, >= 0, <= 100000) Iterations at most.
    fairness: (number, >= 0) omega_f: weight of the fairness (second differences along polylines; at vertices of polygon meshes that no polyline passes, twice the offset from the neighbours' centroid).
    soft_decay: (number, >= 1e-12, <= 1) Closeness and fairness weights are multiplied by this each iteration ....
    soft_floor: (number, >= 0, <= 1) ... down to this fraction of their initial value.
    soft_residual: (number, >= 0) ... and, when > 0, also by this times the max constraint residual of the iteration (the soft weights vanish as the constraints converge).
    epsilon: (number, > 0) epsilon: weight of the proximal term eps^2 |x - x^k|^2.
    epsilon_min: (number, >= 0) When > 0, epsilon follows the constraint residual down to this (quadratic convergence near the solution).
    linear_solver: (choice) Sparse Cholesky backend for gp: cholmod (supernodal) or eigen.
    threads: (int, >= 0, <= 256) Threads for BLAS / Ceres (0: default).
    monotone: (bool) Monotone steps: keep a step only if it lowers the energy, else damp it (plain steps: take every Gauss-Newton step).
    step_control: (choice) How a monotone step that does not lower the energy is shortened: dogleg (a trust region on the iteration's factor: a rejected trial costs an evaluation) or damping (epsilon grows and the step is refactorised).
    min_angle: (number, deg, >= 0, <= 59.9) Every quad corner angle stays within [min_angle, 180 - min_angle] (a corner already outside in the input is kept from getting worse); 0 only keeps quads convex.
    edge_length: (numbers, input units, >= 0, 2 values) Every edge length ends within these, to the tolerance (an edge outside in the input is brought in; the run converges only when all are); without it no edge shrinks below 10% of its input length.
    allow_folds: (bool) No corner-angle or default edge bounds: quads may turn non-convex or fold.
    fix_boundary: (bool) Every boundary vertex stays where it is.
    glide_boundary: (bool) Boundary vertices slide along the input's boundary (they stay on it to rounding).
    net: (choice) Whose stars must be planar: edges (each vertex with its neighbours: the mesh is the A-net) or diagonal (each vertex with the corners opposite it in its quads: the mesh's two diagonal meshes are A-nets, for meshes whose diagonals follow the asymptotic directions; the quads, their bounds and fairness stay the mesh's own).
    outputs: optional outputs to make as well (picture, face_values, heatmap); each is an attribute of the result.
    callback: called with each iteration record (the keys of report.history's entries); returning False stops the run (status USER_ABORT). Ctrl-C stops it too and raises KeyboardInterrupt.

Returns a AnetResult: `report` (a Report: status, converged, iterations, history, initial and final measures, options), `vertices` and `faces` (the mesh): the A-net, and
    picture: a shaded picture of the result, each face coloured by the star planarity of its corners (None unless asked in outputs=)
    face_values: per-face values: face, star_planarity (largest of its corners), kink_deg, min_angle_deg (None unless asked in outputs=)
    heatmap: the result with a colour per face (star planarity, log scale; the scale is in the report) (None unless asked in outputs=)
When the run fails numerically, the result's mesh and outputs are None and report.status is FAILURE.

Raises TypeError or ValueError naming the argument for bad arguments; warns (GprojWarning) when the input is far from the asked net or the result needs attention.
"""
    ...

class HnetOptions:
    """The options of hnet()."""
    solver: Literal['gp', 'ceres']
    """(choice) gp: guided projection; ceres: Levenberg-Marquardt on the same rows (cross-check)."""
    star_form: Literal['normals', 'quads']
    """(choice) Vertex-star planarity: normals (auxiliary normal per inner vertex) or quads (n-2 quads of each star)."""
    tolerance: float
    """(number, > 0) The A-net step stops when max star planarity (neighbour distance from the star plane / mean edge) is <= this."""
    tangent: float
    """(number, >= 0) Weight of the distance to the reference's tangent planes."""
    point: float
    """(number, >= 0) Weight of the distance to the reference's closest points."""
    fairness_order: int
    """(int, >= 2, <= 3) 2: second differences, 3: third differences."""
    max_iterations: int
    """(int, >= 0, <= 100000) Iterations at most."""
    fairness: float
    """(number, >= 0) omega_f: weight of the fairness (second differences along polylines; at vertices of polygon meshes that no polyline passes, twice the offset from the neighbours' centroid)."""
    soft_decay: float
    """(number, >= 1e-12, <= 1) Closeness and fairness weights are multiplied by this each iteration ...."""
    soft_floor: float
    """(number, >= 0, <= 1) ... down to this fraction of their initial value."""
    soft_residual: float
    """(number, >= 0) ... and, when > 0, also by this times the max constraint residual of the iteration (the soft weights vanish as the constraints converge)."""
    epsilon: float
    """(number, > 0) epsilon: weight of the proximal term eps^2 |x - x^k|^2."""
    epsilon_min: float
    """(number, >= 0) When > 0, epsilon follows the constraint residual down to this (quadratic convergence near the solution)."""
    linear_solver: Literal['cholmod', 'eigen']
    """(choice) Sparse Cholesky backend for gp: cholmod (supernodal) or eigen."""
    threads: int
    """(int, >= 0, <= 256) Threads for BLAS / Ceres (0: default)."""
    monotone: bool
    """(bool) Monotone steps: keep a step only if it lowers the energy, else damp it (plain steps: take every Gauss-Newton step)."""
    step_control: Literal['dogleg', 'damping']
    """(choice) How a monotone step that does not lower the energy is shortened: dogleg (a trust region on the iteration's factor: a rejected trial costs an evaluation) or damping (epsilon grows and the step is refactorised)."""
    min_angle: float
    """(number, deg, >= 0, <= 59.9) Every quad corner angle stays within [min_angle, 180 - min_angle] (a corner already outside in the input is kept from getting worse); 0 only keeps quads convex."""
    edge_length: Optional[Sequence[float]]
    """(numbers, input units, >= 0, 2 values) Every edge length ends within these, to the tolerance (an edge outside in the input is brought in; the run converges only when all are); without it no edge shrinks below 10% of its input length."""
    allow_folds: bool
    """(bool) No corner-angle or default edge bounds: quads may turn non-convex or fold."""
    fix_boundary: bool
    """(bool) Every boundary vertex stays where it is."""
    glide_boundary: bool
    """(bool) Boundary vertices slide along the input's boundary (they stay on it to rounding)."""
    rounds: int
    """(int, >= 1, <= 1000) Alternations of weight and vertex updates at most."""
    frame_weight: float
    """(number, > 0) Weight of frame-point planarity."""
    allow_not_simply_connected: bool
    """(bool) Optimise meshes that are not simply connected (no exact extension exists in general): the vertices and the shape parameters are solved for together."""
    samples: int
    """(int, >= 1, <= 200) Samples per patch edge of the surface_mesh output."""
    net: Literal['edges', 'diagonal']
    """(choice) Which net to extend: edges (the mesh itself) or diagonal (one of the mesh's two diagonal meshes, for meshes whose diagonals follow the asymptotic directions: its edges are the quads' diagonals, its faces the rings of the other vertices; the H-net's vertices are the input's of one colour)."""
    diagonal_colour: Optional[int]
    """(int, >= 0, <= 1) With net diagonal: which diagonal mesh, by the colour of its vertices (0, the default: the one through vertex 0)."""
    def __init__(
        self,
        *,
        solver: Literal['gp', 'ceres'] = 'gp',
        star_form: Literal['normals', 'quads'] = 'normals',
        tolerance: float = 1e-09,
        tangent: float = 100.0,
        point: float = 10.0,
        fairness_order: int = 2,
        max_iterations: int = 50,
        fairness: float = 0.5,
        soft_decay: float = 0.1,
        soft_floor: float = 1e-12,
        soft_residual: float = 1.0,
        epsilon: float = 0.001,
        epsilon_min: float = 1e-06,
        linear_solver: Literal['cholmod', 'eigen'] = 'cholmod',
        threads: int = 0,
        monotone: bool = True,
        step_control: Literal['dogleg', 'damping'] = 'dogleg',
        min_angle: float = 5.0,
        edge_length: Optional[Sequence[float]] = None,
        allow_folds: bool = False,
        fix_boundary: bool = False,
        glide_boundary: bool = False,
        rounds: int = 8,
        frame_weight: float = 1.0,
        allow_not_simply_connected: bool = False,
        samples: int = 8,
        net: Literal['edges', 'diagonal'] = 'edges',
        diagonal_colour: Optional[int] = None,
    ) -> None: ...

class HnetResult(Result):
    """The result of hnet(): the H-net: vertices, quad faces, four corner weights per face."""
    output: Optional[Dict[str, Any]]
    surface_mesh: Optional[Mesh]
    """a triangle mesh sampling every patch on a (samples + 1)^2 grid (None unless asked in outputs=)"""
    picture: Optional[str]
    """a shaded picture of the patchwork (None unless asked in outputs=)"""

def hnet(
    V: ArrayLike,
    F: ArrayLike,
    *,
    options: Optional[HnetOptions] = None,
    reference: Optional[Tuple[ArrayLike, ArrayLike]] = None,
    fixed: Union[ArrayLike, str, os.PathLike[str], None] = None,
    weld: bool = False,
    solver: Literal['gp', 'ceres'] = 'gp',
    star_form: Literal['normals', 'quads'] = 'normals',
    tolerance: float = 1e-09,
    tangent: float = 100.0,
    point: float = 10.0,
    fairness_order: int = 2,
    max_iterations: int = 50,
    fairness: float = 0.5,
    soft_decay: float = 0.1,
    soft_floor: float = 1e-12,
    soft_residual: float = 1.0,
    epsilon: float = 0.001,
    epsilon_min: float = 1e-06,
    linear_solver: Literal['cholmod', 'eigen'] = 'cholmod',
    threads: int = 0,
    monotone: bool = True,
    step_control: Literal['dogleg', 'damping'] = 'dogleg',
    min_angle: float = 5.0,
    edge_length: Optional[Sequence[float]] = None,
    allow_folds: bool = False,
    fix_boundary: bool = False,
    glide_boundary: bool = False,
    rounds: int = 8,
    frame_weight: float = 1.0,
    allow_not_simply_connected: bool = False,
    samples: int = 8,
    net: Literal['edges', 'diagonal'] = 'edges',
    diagonal_colour: Optional[int] = None,
    outputs: Sequence[str] = (),
    callback: Optional[Callable[[Dict[str, Any]], Optional[bool]]] = None,
) -> HnetResult:
    """H-net (004 §2-3): extend an A-net (running the A-net step first when needed) to smoothly joined rational bilinear patches: corner weights per patch, shape parameters propagated and scaled, vertices and weights alternated until the weights settle.

Arguments:
    V: the mesh: (n, 3) float vertex positions. Quad mesh roughly along asymptotic directions (simply connected, inner vertices of even valence).
    F: (m, k) integer faces, 0-based (a list of faces for mixed sizes).
    options: a HnetOptions; keyword arguments override its fields.
    reference: a mesh (V, F). Reference surface (polygon mesh) to stay close to; default: the input itself.
    fixed: 0-based vertex ids, a boolean mask over the vertices, or the path of a file of ids. Vertices that do not move at all (0-based ids; returned bit for bit).
    weld: merge the input meshes' coincident vertices (within 1e-9 of the bounding-box diagonal) first, as unwelded exports need; without it such a mesh is refused. Vertex ids (fixed, ...) then number the welded mesh; result.weld_map maps each input vertex to it.
    solver: (choice) gp: guided projection; ceres: Levenberg-Marquardt on the same rows (cross-check).
    star_form: (choice) Vertex-star planarity: normals (auxiliary normal per inner vertex) or quads (n-2 quads of each star).
    tolerance: (number, > 0) The A-net step stops when max star planarity (neighbour distance from the star plane / mean edge) is <= this.
    tangent: (number, >= 0) Weight of the distance to the reference's tangent planes.
    point: (number, >= 0) Weight of the distance to the reference's closest points.
    fairness_order: (int, >= 2, <= 3) 2: second differences, 3: third differences.
    max_iterations: (int, >= 0, <= 100000) Iterations at most.
    fairness: (number, >= 0) omega_f: weight of the fairness (second differences along polylines; at vertices of polygon meshes that no polyline passes, twice the offset from the neighbours' centroid).
    soft_decay: (number, >= 1e-12, <= 1) Closeness and fairness weights are multiplied by this each iteration ....
    soft_floor: (number, >= 0, <= 1) ... down to this fraction of their initial value.
    soft_residual: (number, >= 0) ... and, when > 0, also by this times the max constraint residual of the iteration (the soft weights vanish as the constraints converge).
    epsilon: (number, > 0) epsilon: weight of the proximal term eps^2 |x - x^k|^2.
    epsilon_min: (number, >= 0) When > 0, epsilon follows the constraint residual down to this (quadratic convergence near the solution).
    linear_solver: (choice) Sparse Cholesky backend for gp: cholmod (supernodal) or eigen.
    threads: (int, >= 0, <= 256) Threads for BLAS / Ceres (0: default).
    monotone: (bool) Monotone steps: keep a step only if it lowers the energy, else damp it (plain steps: take every Gauss-Newton step).
    step_control: (choice) How a monotone step that does not lower the energy is shortened: dogleg (a trust region on the iteration's factor: a rejected trial costs an evaluation) or damping (epsilon grows and the step is refactorised).
    min_angle: (number, deg, >= 0, <= 59.9) Every quad corner angle stays within [min_angle, 180 - min_angle] (a corner already outside in the input is kept from getting worse); 0 only keeps quads convex.
    edge_length: (numbers, input units, >= 0, 2 values) Every edge length ends within these, to the tolerance (an edge outside in the input is brought in; the run converges only when all are); without it no edge shrinks below 10% of its input length.
    allow_folds: (bool) No corner-angle or default edge bounds: quads may turn non-convex or fold.
    fix_boundary: (bool) Every boundary vertex stays where it is.
    glide_boundary: (bool) Boundary vertices slide along the input's boundary (they stay on it to rounding).
    rounds: (int, >= 1, <= 1000) Alternations of weight and vertex updates at most.
    frame_weight: (number, > 0) Weight of frame-point planarity.
    allow_not_simply_connected: (bool) Optimise meshes that are not simply connected (no exact extension exists in general): the vertices and the shape parameters are solved for together.
    samples: (int, >= 1, <= 200) Samples per patch edge of the surface_mesh output.
    net: (choice) Which net to extend: edges (the mesh itself) or diagonal (one of the mesh's two diagonal meshes, for meshes whose diagonals follow the asymptotic directions: its edges are the quads' diagonals, its faces the rings of the other vertices; the H-net's vertices are the input's of one colour).
    diagonal_colour: (int, >= 0, <= 1) With net diagonal: which diagonal mesh, by the colour of its vertices (0, the default: the one through vertex 0).
    outputs: optional outputs to make as well (surface_mesh, picture); each is an attribute of the result.
    callback: called with each iteration record (the keys of report.history's entries); returning False stops the run (status USER_ABORT). Ctrl-C stops it too and raises KeyboardInterrupt.

Returns a HnetResult: `report` (a Report: status, converged, iterations, history, initial and final measures, options), `output` (a dict): the H-net: vertices, quad faces, four corner weights per face, and
    surface_mesh: a triangle mesh sampling every patch on a (samples + 1)^2 grid (None unless asked in outputs=)
    picture: a shaded picture of the patchwork (None unless asked in outputs=)
When the run fails numerically, the result's mesh and outputs are None and report.status is FAILURE.

Raises TypeError or ValueError naming the argument for bad arguments; warns (GprojWarning) when the input is far from the asked net or the result needs attention.
"""
    ...

class DarbouxOptions:
    """The options of darboux()."""
    centre: Optional[Sequence[float]]
    """(numbers, 3 values) Centre of the inversion, off the H-net (default: half the H-net's bounding-box diagonal off its box's centre along the mean normal). Nearer the surface, the skin's curvature changes more (regions of K > 0 appear)."""
    radius: Optional[float]
    """(number, > 0) Radius of the inversion (default: the distance from the centre to the H-net's box centre, which then maps to itself)."""
    samples: int
    """(int, >= 2, <= 200) Samples per patch edge of the surface output, the measures and the picture (at most 6 there)."""
    def __init__(
        self,
        *,
        centre: Optional[Sequence[float]] = None,
        radius: Optional[float] = None,
        samples: int = 8,
    ) -> None: ...

class DarbouxResult(Result):
    """The result of darboux(): the skin: the inversion, the H-net, and per patch its rational biquadratic control points."""
    output: Optional[Dict[str, Any]]
    surface: Optional[Mesh]
    """a welded triangle mesh sampling the skin (None unless asked in outputs=)"""
    picture: Optional[str]
    """a shaded picture coloured by the sign of the Gaussian curvature (None unless asked in outputs=)"""

def darboux(
    hnet: Union[Mapping[str, Any], str, os.PathLike[str]],
    *,
    options: Optional[DarbouxOptions] = None,
    centre: Optional[Sequence[float]] = None,
    radius: Optional[float] = None,
    samples: int = 8,
    outputs: Sequence[str] = (),
    callback: Optional[Callable[[Dict[str, Any]], Optional[bool]]] = None,
) -> DarbouxResult:
    """A smooth skin of Darboux cyclide patches (004 §4): the image of an H-net under an inversion, each rational bilinear patch mapped exactly to a rational biquadratic one, its rulings to circles through the centre, the tangent-plane continuity kept; the Gaussian curvature may change sign (K > 0 regions from a K < 0 H-net).

Arguments:
    hnet: H-net (the JSON gproj hnet writes).
    options: a DarbouxOptions; keyword arguments override its fields.
    centre: (numbers, 3 values) Centre of the inversion, off the H-net (default: half the H-net's bounding-box diagonal off its box's centre along the mean normal). Nearer the surface, the skin's curvature changes more (regions of K > 0 appear).
    radius: (number, > 0) Radius of the inversion (default: the distance from the centre to the H-net's box centre, which then maps to itself).
    samples: (int, >= 2, <= 200) Samples per patch edge of the surface output, the measures and the picture (at most 6 there).
    outputs: optional outputs to make as well (surface, picture); each is an attribute of the result.
    callback: called with each iteration record (the keys of report.history's entries); returning False stops the run (status USER_ABORT). Ctrl-C stops it too and raises KeyboardInterrupt.

Returns a DarbouxResult: `report` (a Report: status, converged, iterations, history, initial and final measures, options), `output` (a dict): the skin: the inversion, the H-net, and per patch its rational biquadratic control points, and
    surface: a welded triangle mesh sampling the skin (None unless asked in outputs=)
    picture: a shaded picture coloured by the sign of the Gaussian curvature (None unless asked in outputs=)
When the run fails numerically, the result's mesh and outputs are None and report.status is FAILURE.

Raises TypeError or ValueError naming the argument for bad arguments; warns (GprojWarning) when the input is far from the asked net or the result needs attention.
"""
    ...

class FieldOptions:
    """The options of field()."""
    directions: Literal['asymptotic', 'principal']
    """(choice) asymptotic (where K < 0) or principal."""
    neighbours: int
    """(int, >= 10, <= 1000) Vertices per jet fit at least (rings are added until there are as many)."""
    smooth: Optional[float]
    """(number, > 0) Smooth the principal lines first, with this weight on the fitted ones against the smoothness (e.g. 1; for noisy meshes); not given: no smoothing."""
    def __init__(
        self,
        *,
        directions: Literal['asymptotic', 'principal'] = 'asymptotic',
        neighbours: int = 20,
        smooth: Optional[float] = None,
    ) -> None: ...

class FieldResult(Result):
    """The result of field(): the field as OBJ line segments, two per vertex."""
    output: Optional[str]
    picture: Optional[str]
    """a picture of the mesh coloured by the sign of K (None unless asked in outputs=)"""
    first: Optional[npt.NDArray[np.float64]]
    """#V x 3: the first line of the field at every vertex (0: no fit)"""
    second: Optional[npt.NDArray[np.float64]]
    """#V x 3: the second line (the asymptotic partner, or d2)"""

def field(
    V: ArrayLike,
    F: ArrayLike,
    *,
    options: Optional[FieldOptions] = None,
    weld: bool = False,
    directions: Literal['asymptotic', 'principal'] = 'asymptotic',
    neighbours: int = 20,
    smooth: Optional[float] = None,
    outputs: Sequence[str] = (),
    callback: Optional[Callable[[Dict[str, Any]], Optional[bool]]] = None,
) -> FieldResult:
    """Curvature direction field of a triangle mesh (004 §3.1): principal curvatures and directions per vertex by a 3rd-order jet fit (CGAL), the asymptotic pair where K < 0, and the singularities of the field with their indices (the asymptotic pair about the line d1, in halves; the principal cross, in quarters); smooth smooths the field first.

Arguments:
    V: the mesh: (n, 3) float vertex positions. Triangle mesh.
    F: (m, k) integer faces, 0-based (a list of faces for mixed sizes).
    options: a FieldOptions; keyword arguments override its fields.
    weld: merge the input meshes' coincident vertices (within 1e-9 of the bounding-box diagonal) first, as unwelded exports need; without it such a mesh is refused. Vertex ids (fixed, ...) then number the welded mesh; result.weld_map maps each input vertex to it.
    directions: (choice) asymptotic (where K < 0) or principal.
    neighbours: (int, >= 10, <= 1000) Vertices per jet fit at least (rings are added until there are as many).
    smooth: (number, > 0) Smooth the principal lines first, with this weight on the fitted ones against the smoothness (e.g. 1; for noisy meshes); not given: no smoothing.
    outputs: optional outputs to make as well (picture); each is an attribute of the result.
    callback: called with each iteration record (the keys of report.history's entries); returning False stops the run (status USER_ABORT). Ctrl-C stops it too and raises KeyboardInterrupt.

Returns a FieldResult: `report` (a Report: status, converged, iterations, history, initial and final measures, options), `output` (text): the field as OBJ line segments, two per vertex, and
    picture: a picture of the mesh coloured by the sign of K (None unless asked in outputs=)
    first: #V x 3: the first line of the field at every vertex (0: no fit)
    second: #V x 3: the second line (the asymptotic partner, or d2)
When the run fails numerically, the result's mesh and outputs are None and report.status is FAILURE.

Raises TypeError or ValueError naming the argument for bad arguments; warns (GprojWarning) when the input is far from the asked net or the result needs attention.
"""
    ...

class RemeshOptions:
    """The options of remesh()."""
    directions: Literal['asymptotic', 'principal']
    """(choice) asymptotic (where K < 0) or principal."""
    edge_length: Optional[float]
    """(number, input units, > 0) Edge length of the quads (not given: 3 mean triangle edges)."""
    smooth: float
    """(number, > 0) Weight of the fitted directions against the field's smoothness (smaller: smoother, fewer singularities)."""
    neighbours: int
    """(int, >= 10, <= 1000) Vertices per jet fit at least (rings are added until there are as many)."""
    min_net_angle: float
    """(number, deg, >= 1, <= 90) Asymptotic pairs closer than this are opened to it."""
    def __init__(
        self,
        *,
        directions: Literal['asymptotic', 'principal'] = 'asymptotic',
        edge_length: Optional[float] = None,
        smooth: float = 1.0,
        neighbours: int = 20,
        min_net_angle: float = 30.0,
    ) -> None: ...

class RemeshResult(Result):
    """The result of remesh(): the quad mesh."""
    output: Optional[Mesh]
    field: Optional[str]
    """the frame field the quads follow (OBJ segments, two per triangle) (None unless asked in outputs=)"""
    picture: Optional[str]
    """a picture of the quads coloured by their edges' deviation from the field, with the singularities (None unless asked in outputs=)"""

def remesh(
    V: ArrayLike,
    F: ArrayLike,
    *,
    options: Optional[RemeshOptions] = None,
    weld: bool = False,
    directions: Literal['asymptotic', 'principal'] = 'asymptotic',
    edge_length: Optional[float] = None,
    smooth: float = 1.0,
    neighbours: int = 20,
    min_net_angle: float = 30.0,
    outputs: Sequence[str] = (),
    callback: Optional[Callable[[Dict[str, Any]], Optional[bool]]] = None,
) -> RemeshResult:
    """Quad remeshing of a triangulated disk, or of a surface with holes and handles, along its asymptotic (K < 0) or principal directions (004 §3.1): jet-fitted, smoothed direction field, seamless integer-grid map cut through the holes, around the handles and from its singularities to the boundary (mixed-integer quadrangulation, integer transitions across every cut), quads extracted along the integer iso-lines. Converged (exit 0) when the quads are a valid net (inner valences above 2, quads convex, map unfolded, one piece with the surface's Euler characteristic and no pinched vertex, and for asymptotic directions even valences, 2-coloured vertices and K < 0 on 99% of the area); otherwise the quads are returned and the reasons named.

Arguments:
    V: the mesh: (n, 3) float vertex positions. Triangle mesh of a surface with a boundary: a disk, or with holes and handles.
    F: (m, k) integer faces, 0-based (a list of faces for mixed sizes).
    options: a RemeshOptions; keyword arguments override its fields.
    weld: merge the input meshes' coincident vertices (within 1e-9 of the bounding-box diagonal) first, as unwelded exports need; without it such a mesh is refused. Vertex ids (fixed, ...) then number the welded mesh; result.weld_map maps each input vertex to it.
    directions: (choice) asymptotic (where K < 0) or principal.
    edge_length: (number, input units, > 0) Edge length of the quads (not given: 3 mean triangle edges).
    smooth: (number, > 0) Weight of the fitted directions against the field's smoothness (smaller: smoother, fewer singularities).
    neighbours: (int, >= 10, <= 1000) Vertices per jet fit at least (rings are added until there are as many).
    min_net_angle: (number, deg, >= 1, <= 90) Asymptotic pairs closer than this are opened to it.
    outputs: optional outputs to make as well (field, picture); each is an attribute of the result.
    callback: called with each iteration record (the keys of report.history's entries); returning False stops the run (status USER_ABORT). Ctrl-C stops it too and raises KeyboardInterrupt.

Returns a RemeshResult: `report` (a Report: status, converged, iterations, history, initial and final measures, options), `vertices` and `faces` (the mesh): the quad mesh, and
    field: the frame field the quads follow (OBJ segments, two per triangle) (None unless asked in outputs=)
    picture: a picture of the quads coloured by their edges' deviation from the field, with the singularities (None unless asked in outputs=)
When the run fails numerically, the result's mesh and outputs are None and report.status is FAILURE.

Raises TypeError or ValueError naming the argument for bad arguments; warns (GprojWarning) when the input is far from the asked net or the result needs attention.
"""
    ...

class InvertOptions:
    """The options of invert()."""
    centre: Optional[Sequence[float]]
    """(numbers, 3 values) Centre of inversion."""
    ratio: float
    """(number) Ratio k of the inversion (non-zero)."""
    m_revolution: Optional[ArrayLike]
    """(points, 4 values) Four concyclic points whose image must be an isosceles trapezoid (the centre then solves 000 §5.1)."""
    t: float
    """(number, > 0) Ratio of the trapezoid's parallel sides."""
    root: int
    """(int, >= 0, <= 1) Which of the (up to) two centres to use: 0 or 1."""
    def __init__(
        self,
        *,
        centre: Optional[Sequence[float]] = None,
        ratio: float = 1.0,
        m_revolution: Optional[ArrayLike] = None,
        t: float = 1.0,
        root: int = 0,
    ) -> None: ...

class InvertResult(Result):
    """The result of invert(): the inverted mesh."""
    output: Optional[Mesh]
    picture: Optional[str]
    """a shaded picture of the result (None unless asked in outputs=)"""

def invert(
    V: ArrayLike,
    F: ArrayLike,
    *,
    options: Optional[InvertOptions] = None,
    weld: bool = False,
    centre: Optional[Sequence[float]] = None,
    ratio: float = 1.0,
    m_revolution: Optional[ArrayLike] = None,
    t: float = 1.0,
    root: int = 0,
    outputs: Sequence[str] = (),
    callback: Optional[Callable[[Dict[str, Any]], Optional[bool]]] = None,
) -> InvertResult:
    """Inversion (Moebius transformation, 000 eq. 1) of a mesh: CM' = k / |CM|^2 CM. Circular meshes stay circular. With m_revolution the centre solves 000 §5.1: it maps the concyclic quad P1 P2 P3 P4 to an isosceles trapezoid with P1'P2' = t P4'P3'.

Arguments:
    V: the mesh: (n, 3) float vertex positions. Mesh to invert.
    F: (m, k) integer faces, 0-based (a list of faces for mixed sizes).
    options: a InvertOptions; keyword arguments override its fields.
    weld: merge the input meshes' coincident vertices (within 1e-9 of the bounding-box diagonal) first, as unwelded exports need; without it such a mesh is refused. Vertex ids (fixed, ...) then number the welded mesh; result.weld_map maps each input vertex to it.
    centre: (numbers, 3 values) Centre of inversion.
    ratio: (number) Ratio k of the inversion (non-zero).
    m_revolution: (points, 4 values) Four concyclic points whose image must be an isosceles trapezoid (the centre then solves 000 §5.1).
    t: (number, > 0) Ratio of the trapezoid's parallel sides.
    root: (int, >= 0, <= 1) Which of the (up to) two centres to use: 0 or 1.
    outputs: optional outputs to make as well (picture); each is an attribute of the result.
    callback: called with each iteration record (the keys of report.history's entries); returning False stops the run (status USER_ABORT). Ctrl-C stops it too and raises KeyboardInterrupt.

Returns a InvertResult: `report` (a Report: status, converged, iterations, history, initial and final measures, options), `vertices` and `faces` (the mesh): the inverted mesh, and
    picture: a shaded picture of the result (None unless asked in outputs=)
When the run fails numerically, the result's mesh and outputs are None and report.status is FAILURE.

Raises TypeError or ValueError naming the argument for bad arguments; warns (GprojWarning) when the input is far from the asked net or the result needs attention.
"""
    ...

class CyclidicOptions:
    """The options of cyclidic()."""
    normal: Optional[Sequence[float]]
    """(numbers, 3 values) Normal of the frame at vertex 0 (not given: the frame minimising 000 eq. 5)."""
    psi: float
    """(number, rad) Turn of the frame's first tangent about the normal (the start of the minimisation without normal)."""
    segments: int
    """(int, >= 1, <= 1000) Fine quads along every arc."""
    max_iterations: int
    """(int, >= 1, <= 100000) BFGS iterations for the frame."""
    closure_tolerance: float
    """(number, deg, > 0) Largest angle by which frames carried around a face may miss themselves (0 for circular faces)."""
    tangent_tolerance: float
    """(number, deg, > 0) Largest angle between the tangent planes of two patches along their common arc for convergence."""
    def __init__(
        self,
        *,
        normal: Optional[Sequence[float]] = None,
        psi: float = 0.0,
        segments: int = 8,
        max_iterations: int = 200,
        closure_tolerance: float = 0.0001,
        tangent_tolerance: float = 0.0001,
    ) -> None: ...

class CyclidicResult(Result):
    """The result of cyclidic(): the fine mesh of the smooth surface."""
    output: Optional[Mesh]
    picture: Optional[str]
    """a shaded picture of the smooth surface (None unless asked in outputs=)"""

def cyclidic(
    V: ArrayLike,
    F: ArrayLike,
    *,
    options: Optional[CyclidicOptions] = None,
    weld: bool = False,
    normal: Optional[Sequence[float]] = None,
    psi: float = 0.0,
    segments: int = 8,
    max_iterations: int = 200,
    closure_tolerance: float = 0.0001,
    tangent_tolerance: float = 0.0001,
    outputs: Sequence[str] = (),
    callback: Optional[Callable[[Dict[str, Any]], Optional[bool]]] = None,
) -> CyclidicResult:
    """Smooth cyclidic surface of a circular quad mesh in grid order (000 §2.1-2.2): a frame at vertex 0, carried to every vertex by mirror images across the edges, makes the mesh a cyclidic net; every quad carries a Dupin cyclide patch (both families of curvature lines circles), the patches join with common tangent planes, and the surface is returned as a fine mesh along its curvature lines. The frame minimises 000 eq. 5 unless normal is given. Not converged when the surface folds or pinches, or the tangent planes disagree beyond tangent_tolerance (the result is returned).

Arguments:
    V: the mesh: (n, 3) float vertex positions. Circular quad mesh in grid order.
    F: (m, k) integer faces, 0-based (a list of faces for mixed sizes).
    options: a CyclidicOptions; keyword arguments override its fields.
    weld: merge the input meshes' coincident vertices (within 1e-9 of the bounding-box diagonal) first, as unwelded exports need; without it such a mesh is refused. Vertex ids (fixed, ...) then number the welded mesh; result.weld_map maps each input vertex to it.
    normal: (numbers, 3 values) Normal of the frame at vertex 0 (not given: the frame minimising 000 eq. 5).
    psi: (number, rad) Turn of the frame's first tangent about the normal (the start of the minimisation without normal).
    segments: (int, >= 1, <= 1000) Fine quads along every arc.
    max_iterations: (int, >= 1, <= 100000) BFGS iterations for the frame.
    closure_tolerance: (number, deg, > 0) Largest angle by which frames carried around a face may miss themselves (0 for circular faces).
    tangent_tolerance: (number, deg, > 0) Largest angle between the tangent planes of two patches along their common arc for convergence.
    outputs: optional outputs to make as well (picture); each is an attribute of the result.
    callback: called with each iteration record (the keys of report.history's entries); returning False stops the run (status USER_ABORT). Ctrl-C stops it too and raises KeyboardInterrupt.

Returns a CyclidicResult: `report` (a Report: status, converged, iterations, history, initial and final measures, options), `vertices` and `faces` (the mesh): the fine mesh of the smooth surface, and
    picture: a shaded picture of the smooth surface (None unless asked in outputs=)
When the run fails numerically, the result's mesh and outputs are None and report.status is FAILURE.

Raises TypeError or ValueError naming the argument for bad arguments; warns (GprojWarning) when the input is far from the asked net or the result needs attention.
"""
    ...

class CombescureOptions:
    """The options of combescure()."""
    solver: Literal['direct', 'gp', 'ceres']
    """(choice) direct: propagation (linear time); gp: guided projection on edge-parallelism rows; ceres: Levenberg-Marquardt on the same rows (the cross-check)."""
    row_lengths: Optional[Sequence[float]]
    """(numbers) Signed lengths of edges (0, j) -> (0, j+1) (not given: the reference's times row_scale)."""
    column_lengths: Optional[Sequence[float]]
    """(numbers) Signed lengths of edges (i, 0) -> (i+1, 0) (not given: the reference's times column_scale)."""
    row_scale: float
    """(number, > 0) Scale of the reference's row lengths."""
    column_scale: float
    """(number, > 0) Scale of the reference's column lengths."""
    origin: Optional[Sequence[float]]
    """(numbers, 3 values) Position of vertex (0, 0) (not given: unchanged)."""
    tolerance: float
    """(number, > 0) Largest reference planarity accepted (diagonal distance / mean edge)."""
    def __init__(
        self,
        *,
        solver: Literal['direct', 'gp', 'ceres'] = 'direct',
        row_lengths: Optional[Sequence[float]] = None,
        column_lengths: Optional[Sequence[float]] = None,
        row_scale: float = 1.0,
        column_scale: float = 1.0,
        origin: Optional[Sequence[float]] = None,
        tolerance: float = 1e-06,
    ) -> None: ...

class CombescureResult(Result):
    """The result of combescure(): the parallel mesh."""
    output: Optional[Mesh]
    picture: Optional[str]
    """a shaded picture of the result (None unless asked in outputs=)"""

def combescure(
    V: ArrayLike,
    F: ArrayLike,
    *,
    options: Optional[CombescureOptions] = None,
    weld: bool = False,
    solver: Literal['direct', 'gp', 'ceres'] = 'direct',
    row_lengths: Optional[Sequence[float]] = None,
    column_lengths: Optional[Sequence[float]] = None,
    row_scale: float = 1.0,
    column_scale: float = 1.0,
    origin: Optional[Sequence[float]] = None,
    tolerance: float = 1e-06,
    outputs: Sequence[str] = (),
    callback: Optional[Callable[[Dict[str, Any]], Optional[bool]]] = None,
) -> CombescureResult:
    """Combescure transformation (000 §2.4-2.5): a mesh with every edge parallel to a planar quad grid's (in `gproj grid` vertex order), from the edge lengths along row 0 and column 0. Circular meshes stay circular.

Arguments:
    V: the mesh: (n, 3) float vertex positions. Reference grid with planar quads.
    F: (m, k) integer faces, 0-based (a list of faces for mixed sizes).
    options: a CombescureOptions; keyword arguments override its fields.
    weld: merge the input meshes' coincident vertices (within 1e-9 of the bounding-box diagonal) first, as unwelded exports need; without it such a mesh is refused. Vertex ids (fixed, ...) then number the welded mesh; result.weld_map maps each input vertex to it.
    solver: (choice) direct: propagation (linear time); gp: guided projection on edge-parallelism rows; ceres: Levenberg-Marquardt on the same rows (the cross-check).
    row_lengths: (numbers) Signed lengths of edges (0, j) -> (0, j+1) (not given: the reference's times row_scale).
    column_lengths: (numbers) Signed lengths of edges (i, 0) -> (i+1, 0) (not given: the reference's times column_scale).
    row_scale: (number, > 0) Scale of the reference's row lengths.
    column_scale: (number, > 0) Scale of the reference's column lengths.
    origin: (numbers, 3 values) Position of vertex (0, 0) (not given: unchanged).
    tolerance: (number, > 0) Largest reference planarity accepted (diagonal distance / mean edge).
    outputs: optional outputs to make as well (picture); each is an attribute of the result.
    callback: called with each iteration record (the keys of report.history's entries); returning False stops the run (status USER_ABORT). Ctrl-C stops it too and raises KeyboardInterrupt.

Returns a CombescureResult: `report` (a Report: status, converged, iterations, history, initial and final measures, options), `vertices` and `faces` (the mesh): the parallel mesh, and
    picture: a shaded picture of the result (None unless asked in outputs=)
When the run fails numerically, the result's mesh and outputs are None and report.status is FAILURE.

Raises TypeError or ValueError naming the argument for bad arguments; warns (GprojWarning) when the input is far from the asked net or the result needs attention.
"""
    ...

class BeamsOptions:
    """The options of beams()."""
    height: float
    """(number, input units, > 0, required) Beam height, and the offset distance."""
    width: Optional[float]
    """(number, input units, > 0) Beam thickness across its plane (not given: 4% of the mean edge)."""
    axis_length: Optional[float]
    """(number, input units, > 0) Length of the axes output (not given: twice the height)."""
    optimise: bool
    """(bool) Choose the first axis to minimise the height gaps (off: keep it at the central node's mean face normal)."""
    gap_tolerance: Optional[float]
    """(number, > 0) Largest height gap at a node (in units of the height) for convergence (not given: none)."""
    circularity_tolerance: float
    """(number, rad, >= 1e-300, <= 0.01) Largest closing angle of the axes around a face, at most 0.01."""
    def __init__(
        self,
        *,
        height: float,
        width: Optional[float] = None,
        axis_length: Optional[float] = None,
        optimise: bool = True,
        gap_tolerance: Optional[float] = None,
        circularity_tolerance: float = 1e-06,
    ) -> None: ...

class BeamsResult(Result):
    """The result of beams(): the beams, one box per edge."""
    output: Optional[Mesh]
    axes: Optional[str]
    """the node axes as OBJ line segments (None unless asked in outputs=)"""
    offset: Optional[Mesh]
    """the offset mesh (parallel, at the height) (None unless asked in outputs=)"""
    picture: Optional[str]
    """a shaded picture of the beams (None unless asked in outputs=)"""

def beams(
    V: ArrayLike,
    F: ArrayLike,
    *,
    options: Optional[BeamsOptions] = None,
    weld: bool = False,
    height: float,
    width: Optional[float] = None,
    axis_length: Optional[float] = None,
    optimise: bool = True,
    gap_tolerance: Optional[float] = None,
    circularity_tolerance: float = 1e-06,
    outputs: Sequence[str] = (),
    callback: Optional[Callable[[Dict[str, Any]], Optional[bool]]] = None,
) -> BeamsResult:
    """Torsion-free beams on a circular mesh (000 §4.3): node axes by mirror images across the edges (they close around a face inscribed in a circle), so every beam is planar and the offset mesh at constant distance is parallel; beams of constant height as solids; the first axis chosen to minimise the height gaps at the nodes. Not converged when gap_tolerance is not met.

Arguments:
    V: the mesh: (n, 3) float vertex positions. Circular mesh (every face inscribed in a circle).
    F: (m, k) integer faces, 0-based (a list of faces for mixed sizes).
    options: a BeamsOptions; keyword arguments override its fields.
    weld: merge the input meshes' coincident vertices (within 1e-9 of the bounding-box diagonal) first, as unwelded exports need; without it such a mesh is refused. Vertex ids (fixed, ...) then number the welded mesh; result.weld_map maps each input vertex to it.
    height: (number, input units, > 0, required) Beam height, and the offset distance.
    width: (number, input units, > 0) Beam thickness across its plane (not given: 4% of the mean edge).
    axis_length: (number, input units, > 0) Length of the axes output (not given: twice the height).
    optimise: (bool) Choose the first axis to minimise the height gaps (off: keep it at the central node's mean face normal).
    gap_tolerance: (number, > 0) Largest height gap at a node (in units of the height) for convergence (not given: none).
    circularity_tolerance: (number, rad, >= 1e-300, <= 0.01) Largest closing angle of the axes around a face, at most 0.01.
    outputs: optional outputs to make as well (axes, offset, picture); each is an attribute of the result.
    callback: called with each iteration record (the keys of report.history's entries); returning False stops the run (status USER_ABORT). Ctrl-C stops it too and raises KeyboardInterrupt.

Returns a BeamsResult: `report` (a Report: status, converged, iterations, history, initial and final measures, options), `vertices` and `faces` (the mesh): the beams, one box per edge, and
    axes: the node axes as OBJ line segments (None unless asked in outputs=)
    offset: the offset mesh (parallel, at the height) (None unless asked in outputs=)
    picture: a shaded picture of the beams (None unless asked in outputs=)
When the run fails numerically, the result's mesh and outputs are None and report.status is FAILURE.

Raises TypeError or ValueError naming the argument for bad arguments; warns (GprojWarning) when the input is far from the asked net or the result needs attention.
"""
    ...

class MrevolutionOptions:
    """The options of mrevolution()."""
    p2: Sequence[float]
    """(numbers, 3 values, required) P2: on the circle through P1 and P4 (drawing plane)."""
    p3: Sequence[float]
    """(numbers, 3 values, required) P3: on the same circle."""
    t: float
    """(number, > 0) Ratio P1'P2' / P4'P3' of the trapezoid."""
    root: int
    """(int, >= 0, <= 1) Which of the (up to) two centres: 0 or 1."""
    arch_segments: int
    """(int, >= 2, <= 100000) Quads along each arch."""
    up: Optional[Sequence[float]]
    """(numbers, 3 values) The arches rise to this side of the drawing plane, which it must not lie in (not given: +z, or the side of (P2 - P1) x (P4 - P1) when +z lies in the plane)."""
    def __init__(
        self,
        *,
        p2: Sequence[float],
        p3: Sequence[float],
        t: float = 1.0,
        root: int = 0,
        arch_segments: int = 16,
        up: Optional[Sequence[float]] = None,
    ) -> None: ...

class MrevolutionResult(Result):
    """The result of mrevolution(): the M-revolution mesh."""
    output: Optional[Mesh]
    revolution: Optional[Mesh]
    """the surface of revolution it is the inversion of (None unless asked in outputs=)"""
    picture: Optional[str]
    """a shaded picture of the M-revolution mesh (None unless asked in outputs=)"""

def mrevolution(
    curve: Union[ArrayLike, str, os.PathLike[str]],
    *,
    options: Optional[MrevolutionOptions] = None,
    p2: Sequence[float],
    p3: Sequence[float],
    t: float = 1.0,
    root: int = 0,
    arch_segments: int = 16,
    up: Optional[Sequence[float]] = None,
    outputs: Sequence[str] = (),
    callback: Optional[Callable[[Dict[str, Any]], Optional[bool]]] = None,
) -> MrevolutionResult:
    """M-revolution surface in one step (000 §5.1): the inversion centre that maps P1 P2 P3 P4 (P1, P4 the curve's ends) to an isosceles trapezoid, the surface of revolution whose meridian is the curve's image, meshed by meridians and parallels, inverted back: a circular mesh through the curve's points and P2, P3, with planar arches.

Arguments:
    curve: Planar curve P1 .. P4.
    options: a MrevolutionOptions; keyword arguments override its fields.
    p2: (numbers, 3 values, required) P2: on the circle through P1 and P4 (drawing plane).
    p3: (numbers, 3 values, required) P3: on the same circle.
    t: (number, > 0) Ratio P1'P2' / P4'P3' of the trapezoid.
    root: (int, >= 0, <= 1) Which of the (up to) two centres: 0 or 1.
    arch_segments: (int, >= 2, <= 100000) Quads along each arch.
    up: (numbers, 3 values) The arches rise to this side of the drawing plane, which it must not lie in (not given: +z, or the side of (P2 - P1) x (P4 - P1) when +z lies in the plane).
    outputs: optional outputs to make as well (revolution, picture); each is an attribute of the result.
    callback: called with each iteration record (the keys of report.history's entries); returning False stops the run (status USER_ABORT). Ctrl-C stops it too and raises KeyboardInterrupt.

Returns a MrevolutionResult: `report` (a Report: status, converged, iterations, history, initial and final measures, options), `vertices` and `faces` (the mesh): the M-revolution mesh, and
    revolution: the surface of revolution it is the inversion of (None unless asked in outputs=)
    picture: a shaded picture of the M-revolution mesh (None unless asked in outputs=)
When the run fails numerically, the result's mesh and outputs are None and report.status is FAILURE.

Raises TypeError or ValueError naming the argument for bad arguments; warns (GprojWarning) when the input is far from the asked net or the result needs attention.
"""
    ...

class WeingartenOptions:
    """The options of weingarten()."""
    preset: Literal['fig1', 'fig2b', 'fig2c', 'fig2d', 'fig3', 'fig4b', 'fig4c', 'fig9b', 'fig9c', 'fig10']
    """(choice) Weights of 003 Table 1."""
    solver: Literal['gp', 'ceres']
    """(choice) gp: guided projection; ceres: Levenberg-Marquardt on the same rows (soft terms at their final weights)."""
    samples: Optional[Sequence[int]]
    """(ints, >= 5, <= 100000, 2 values) Samples NU,NV (not given: 2 per control point and direction, as in Table 2)."""
    relation: Optional[Literal['none', 'linear', 'bspline']]
    """(choice) Curvature relation: none, linear (fitted each iteration) or bspline (not given: the preset's)."""
    linear: Optional[Sequence[float]]
    """(numbers, 3 values) Fixed linear relation a,b,c: a H + b K + c = 0 in input units (e.g. 0,1,0: developable; 1,0,0: minimal; 1,0,-c: H = c)."""
    relation_on: Optional[Literal['surface', 'auxiliaries']]
    """(choice) A fixed relation on the surface's own H, K or on the auxiliaries (not given: the preset's)."""
    steps: Optional[Literal['plain', 'monotone', 'projected']]
    """(choice) plain: every step kept; monotone: only steps that lower the energy (else epsilon grows); projected: monotone, auxiliaries reset after each step (not given: the preset's)."""
    no_auxiliaries: bool
    """(bool) Control points are the only unknowns (needs linear on the surface)."""
    allow_folds: bool
    """(bool) Keep steps that fold the surface (by default a step is refused when neighbouring normals on a grid 4x as dense as the samples turn by more than 60 degrees)."""
    alignment: Optional[float]
    """(number, >= 0) Override omega_al (isoline alignment)."""
    closeness: Optional[float]
    """(number, >= 0) Override omega_cl (closeness to the input)."""
    shape: Optional[float]
    """(number, >= 0) Override omega_sh (control-net lengths)."""
    geodesic_parallel: Optional[float]
    """(number, >= 0) Override omega_gp (eq. 8)."""
    epsilon: Optional[float]
    """(number, > 0) Override epsilon of eq. 11 (proximal weight)."""
    soft_start: Optional[float]
    """(number, >= 1, <= 1000000000000) Soft terms start this much stronger."""
    fairness: Optional[float]
    """(number, >= 0) Override omega_f of eq. 11 (control-net fairness)."""
    definitions: Optional[float]
    """(number, > 0) Weight of the rows defining the auxiliaries (relative errors; default 1)."""
    boundary: Optional[float]
    """(number, >= 0) Weight of gliding along the input's boundary polygon."""
    refine: int
    """(int, >= 0, <= 4) Multiresolution levels: insert a knot in every span and re-optimise."""
    refine_method: Literal['insert', 'refit']
    """(choice) How refine refines: insert (a knot in every span: the same surface exactly) or refit (least squares on a net 1.4 times as dense, 003 §4.1.1)."""
    max_iterations: Optional[int]
    """(int, >= 1, <= 100000) Guided-projection iterations per level (not given: the preset's)."""
    tolerance: Optional[float]
    """(number, > 0) Converged when the misalignment (with linear: max relation residual, input units) is <= this, and the run stops there (not given: the preset's iterations are run; with a fixed linear relation they are converged when it holds to 1% of |a| k + |b| k^2, k the input's typical principal curvature; otherwise there is no tolerance)."""
    molds: int
    """(int, >= 0, <= 1000000) Cluster the samples into at most this many molds in the (H, sqrt K) plane (0: none)."""
    panels: Optional[Sequence[int]]
    """(ints, >= 1, <= 1000, 2 values) Panel the input and the result: NU,NV panels over the parameter domain, molds by clustering in the (H, sqrt K) plane, one cubic per mold (003 §4.2)."""
    mold_factor: float
    """(number, >= 0.01, <= 1000) With panels: k sqrt N molds for N panels."""
    panel_tolerance: Optional[Sequence[float]]
    """(numbers, > 0, 2 values) With panels: GAP,KINK (input units, degrees): report the molds the input and the result need for max gap <= GAP and max kink <= KINK."""
    def __init__(
        self,
        *,
        preset: Literal['fig1', 'fig2b', 'fig2c', 'fig2d', 'fig3', 'fig4b', 'fig4c', 'fig9b', 'fig9c', 'fig10'] = 'fig1',
        solver: Literal['gp', 'ceres'] = 'gp',
        samples: Optional[Sequence[int]] = None,
        relation: Optional[Literal['none', 'linear', 'bspline']] = None,
        linear: Optional[Sequence[float]] = None,
        relation_on: Optional[Literal['surface', 'auxiliaries']] = None,
        steps: Optional[Literal['plain', 'monotone', 'projected']] = None,
        no_auxiliaries: bool = False,
        allow_folds: bool = False,
        alignment: Optional[float] = None,
        closeness: Optional[float] = None,
        shape: Optional[float] = None,
        geodesic_parallel: Optional[float] = None,
        epsilon: Optional[float] = None,
        soft_start: Optional[float] = None,
        fairness: Optional[float] = None,
        definitions: Optional[float] = None,
        boundary: Optional[float] = None,
        refine: int = 0,
        refine_method: Literal['insert', 'refit'] = 'insert',
        max_iterations: Optional[int] = None,
        tolerance: Optional[float] = None,
        molds: int = 0,
        panels: Optional[Sequence[int]] = None,
        mold_factor: float = 3.0,
        panel_tolerance: Optional[Sequence[float]] = None,
    ) -> None: ...

class WeingartenResult(Result):
    """The result of weingarten(): the optimised B-spline."""
    output: Optional[Dict[str, Any]]
    diagram: Optional[str]
    """the curvature diagram before/after (None unless asked in outputs=)"""
    curvature: Optional[str]
    """H, K per sample before/after (and the mold of each) (None unless asked in outputs=)"""
    surface_mesh: Optional[Mesh]
    """the result sampled as a quad mesh (None unless asked in outputs=)"""
    picture: Optional[str]
    """a shaded picture of the result (None unless asked in outputs=)"""
    panel_picture: Optional[str]
    """with panels: the result's panels, one colour per mold (None unless asked in outputs=)"""
    seam_histograms: Optional[str]
    """with panels: gaps and kinks at the seams, input against result (None unless asked in outputs=)"""

def weingarten(
    surface: Union[Mapping[str, Any], str, os.PathLike[str]],
    *,
    options: Optional[WeingartenOptions] = None,
    preset: Literal['fig1', 'fig2b', 'fig2c', 'fig2d', 'fig3', 'fig4b', 'fig4c', 'fig9b', 'fig9c', 'fig10'] = 'fig1',
    solver: Literal['gp', 'ceres'] = 'gp',
    samples: Optional[Sequence[int]] = None,
    relation: Optional[Literal['none', 'linear', 'bspline']] = None,
    linear: Optional[Sequence[float]] = None,
    relation_on: Optional[Literal['surface', 'auxiliaries']] = None,
    steps: Optional[Literal['plain', 'monotone', 'projected']] = None,
    no_auxiliaries: bool = False,
    allow_folds: bool = False,
    alignment: Optional[float] = None,
    closeness: Optional[float] = None,
    shape: Optional[float] = None,
    geodesic_parallel: Optional[float] = None,
    epsilon: Optional[float] = None,
    soft_start: Optional[float] = None,
    fairness: Optional[float] = None,
    definitions: Optional[float] = None,
    boundary: Optional[float] = None,
    refine: int = 0,
    refine_method: Literal['insert', 'refit'] = 'insert',
    max_iterations: Optional[int] = None,
    tolerance: Optional[float] = None,
    molds: int = 0,
    panels: Optional[Sequence[int]] = None,
    mold_factor: float = 3.0,
    panel_tolerance: Optional[Sequence[float]] = None,
    outputs: Sequence[str] = (),
    callback: Optional[Callable[[Dict[str, Any]], Optional[bool]]] = None,
) -> WeingartenResult:
    """Weingarten surface (003): moves a B-spline's control points (JSON, docs/formats.md) so that the isolines of H and K align, close to the input; optionally a fixed or fitted curvature relation, multiresolution, mold clustering and paneling.

Arguments:
    surface: B-spline surface.
    options: a WeingartenOptions; keyword arguments override its fields.
    preset: (choice) Weights of 003 Table 1.
    solver: (choice) gp: guided projection; ceres: Levenberg-Marquardt on the same rows (soft terms at their final weights).
    samples: (ints, >= 5, <= 100000, 2 values) Samples NU,NV (not given: 2 per control point and direction, as in Table 2).
    relation: (choice) Curvature relation: none, linear (fitted each iteration) or bspline (not given: the preset's).
    linear: (numbers, 3 values) Fixed linear relation a,b,c: a H + b K + c = 0 in input units (e.g. 0,1,0: developable; 1,0,0: minimal; 1,0,-c: H = c).
    relation_on: (choice) A fixed relation on the surface's own H, K or on the auxiliaries (not given: the preset's).
    steps: (choice) plain: every step kept; monotone: only steps that lower the energy (else epsilon grows); projected: monotone, auxiliaries reset after each step (not given: the preset's).
    no_auxiliaries: (bool) Control points are the only unknowns (needs linear on the surface).
    allow_folds: (bool) Keep steps that fold the surface (by default a step is refused when neighbouring normals on a grid 4x as dense as the samples turn by more than 60 degrees).
    alignment: (number, >= 0) Override omega_al (isoline alignment).
    closeness: (number, >= 0) Override omega_cl (closeness to the input).
    shape: (number, >= 0) Override omega_sh (control-net lengths).
    geodesic_parallel: (number, >= 0) Override omega_gp (eq. 8).
    epsilon: (number, > 0) Override epsilon of eq. 11 (proximal weight).
    soft_start: (number, >= 1, <= 1000000000000) Soft terms start this much stronger.
    fairness: (number, >= 0) Override omega_f of eq. 11 (control-net fairness).
    definitions: (number, > 0) Weight of the rows defining the auxiliaries (relative errors; default 1).
    boundary: (number, >= 0) Weight of gliding along the input's boundary polygon.
    refine: (int, >= 0, <= 4) Multiresolution levels: insert a knot in every span and re-optimise.
    refine_method: (choice) How refine refines: insert (a knot in every span: the same surface exactly) or refit (least squares on a net 1.4 times as dense, 003 §4.1.1).
    max_iterations: (int, >= 1, <= 100000) Guided-projection iterations per level (not given: the preset's).
    tolerance: (number, > 0) Converged when the misalignment (with linear: max relation residual, input units) is <= this, and the run stops there (not given: the preset's iterations are run; with a fixed linear relation they are converged when it holds to 1% of |a| k + |b| k^2, k the input's typical principal curvature; otherwise there is no tolerance).
    molds: (int, >= 0, <= 1000000) Cluster the samples into at most this many molds in the (H, sqrt K) plane (0: none).
    panels: (ints, >= 1, <= 1000, 2 values) Panel the input and the result: NU,NV panels over the parameter domain, molds by clustering in the (H, sqrt K) plane, one cubic per mold (003 §4.2).
    mold_factor: (number, >= 0.01, <= 1000) With panels: k sqrt N molds for N panels.
    panel_tolerance: (numbers, > 0, 2 values) With panels: GAP,KINK (input units, degrees): report the molds the input and the result need for max gap <= GAP and max kink <= KINK.
    outputs: optional outputs to make as well (diagram, curvature, surface_mesh, picture, panel_picture, seam_histograms); each is an attribute of the result.
    callback: called with each iteration record (the keys of report.history's entries); returning False stops the run (status USER_ABORT). Ctrl-C stops it too and raises KeyboardInterrupt.

Returns a WeingartenResult: `report` (a Report: status, converged, iterations, history, initial and final measures, options), `output` (a dict): the optimised B-spline, and
    diagram: the curvature diagram before/after (None unless asked in outputs=)
    curvature: H, K per sample before/after (and the mold of each) (None unless asked in outputs=)
    surface_mesh: the result sampled as a quad mesh (None unless asked in outputs=)
    picture: a shaded picture of the result (None unless asked in outputs=)
    panel_picture: with panels: the result's panels, one colour per mold (None unless asked in outputs=)
    seam_histograms: with panels: gaps and kinks at the seams, input against result (None unless asked in outputs=)
When the run fails numerically, the result's mesh and outputs are None and report.status is FAILURE.

Raises TypeError or ValueError naming the argument for bad arguments; warns (GprojWarning) when the input is far from the asked net or the result needs attention.
"""
    ...

class MarionetteOptions:
    """The options of marionette()."""
    row: Optional[Sequence[float]]
    """(numbers) Guide values of vertices (0, j), j = 0..cols of a grid plan."""
    column: Optional[Sequence[float]]
    """(numbers) Guide values of vertices (i, 0), i = 0..rows; its first value must equal row's."""
    projection: Literal['vertical', 'cylindrical', 'central']
    """(choice) Lines of the vertices: vertical (values are heights), cylindrical (through the plan vertex, perpendicular to axis; values are distances from the axis) or central (through centre and the plan vertex; values are distances from it)."""
    axis: Sequence[float]
    """(numbers, 6 values) Cylindrical axis: a point and a direction."""
    centre: Sequence[float]
    """(numbers, 3 values) Centre of the central projection."""
    hold: Optional[Union[Mapping[int, float], Sequence[Tuple[int, float]]]]
    """(vertex_values) Hard constraint of a fit (002 §3.3), or the prescribed heights of a plan of polygons (002 §4.2): vertex heights met exactly (KKT system, solver direct)."""
    volume: Optional[float]
    """(number) Hard constraint of a fit: the volume under the mesh over its plan (z = 0 as the base), met exactly."""
    max_height: Optional[float]
    """(number) Hard constraint of a fit: no vertex above this height (active set)."""
    solver: Literal['direct', 'gp', 'ceres']
    """(choice) direct: propagation (linear time) or the normal equations of the fit; gp: guided projection (one iteration when vertical, several for other projections; the guides are first checked by propagation); ceres: Levenberg-Marquardt on the same rows (the cross-check)."""
    max_iterations: int
    """(int, >= 1, <= 100000) gp or ceres with a non-vertical projection: iterations at most."""
    tolerance: float
    """(number, > 0) The result's planarity to reach in every mode (with guides or a projection: max |det(p1-p0, p2-p0, p3-p0)| / (edge lengths) and the guide error; grid plans and closed strips: max planarity, diagonal distance / mean edge)."""
    outer_height: float
    """(number) closed_strip with a = 1: the height of the first outer vertex (free)."""
    allow_folded_plan: bool
    """(bool) Lift a plan view whose quads overlap or are not convex in x, y (refused by default), with a warning naming the faces."""
    def __init__(
        self,
        *,
        row: Optional[Sequence[float]] = None,
        column: Optional[Sequence[float]] = None,
        projection: Literal['vertical', 'cylindrical', 'central'] = 'vertical',
        axis: Sequence[float] = ...,
        centre: Sequence[float] = ...,
        hold: Optional[Union[Mapping[int, float], Sequence[Tuple[int, float]]]] = None,
        volume: Optional[float] = None,
        max_height: Optional[float] = None,
        solver: Literal['direct', 'gp', 'ceres'] = 'direct',
        max_iterations: int = 50,
        tolerance: float = 1e-09,
        outer_height: float = 0.0,
        allow_folded_plan: bool = False,
    ) -> None: ...

class MarionetteResult(Result):
    """The result of marionette(): the lifted mesh."""
    output: Optional[Mesh]

def marionette(
    V: Optional[ArrayLike] = None,
    F: Optional[ArrayLike] = None,
    *,
    options: Optional[MarionetteOptions] = None,
    guides: Union[str, os.PathLike[str], None] = None,
    fit: Optional[Tuple[ArrayLike, ArrayLike]] = None,
    fit_heights: Union[str, os.PathLike[str], None] = None,
    closed_strip: Union[str, os.PathLike[str], None] = None,
    weld: bool = False,
    row: Optional[Sequence[float]] = None,
    column: Optional[Sequence[float]] = None,
    projection: Literal['vertical', 'cylindrical', 'central'] = 'vertical',
    axis: Sequence[float] = ...,
    centre: Sequence[float] = ...,
    hold: Optional[Union[Mapping[int, float], Sequence[Tuple[int, float]]]] = None,
    volume: Optional[float] = None,
    max_height: Optional[float] = None,
    solver: Literal['direct', 'gp', 'ceres'] = 'direct',
    max_iterations: int = 50,
    tolerance: float = 1e-09,
    outer_height: float = 0.0,
    allow_folded_plan: bool = False,
    outputs: Sequence[str] = (),
    callback: Optional[Callable[[Dict[str, Any]], Optional[bool]]] = None,
) -> MarionetteResult:
    """Marionette mesh (002): planar quads over a fixed plan view. Every vertex moves on its own line (projection): vertically (the plan's z is ignored), perpendicular to an axis through it, or through a centre; guide values are heights, distances from the axis or distances from the centre. The plan is a regular grid in `grid` order with row and column or fit, or any disk-like quad mesh (singular vertices allowed, 002 §2.4) with guides: it is split into regular patches along the separatrices, and the guides must cross every strip of patches exactly once. A plan of any polygons (Kagome: triangles and hexagons, 002 §4.2), or a quad plan that is no grid, is lifted vertically from hold heights with the fairness of 002 eq. 17 fixing the rest. closed_strip lifts a closed strip instead (002 §2.5, eq. 8).

Arguments:
    V: the plan (optional): (n, 3) float vertex positions. Plan view: a quad mesh, or polygons with hold; vertex ids are 0-based in file order.
    F: (m, k) integer faces, 0-based (a list of faces for mixed sizes).
    options: a MarionetteOptions; keyword arguments override its fields.
    guides: a path (pathlib.Path or str naming a file) or the file's text. Guide file for a plan of any connectivity, one entry a line ('#' comments): 'guide START NEXT V0 V1 ...' gives values to the straight mesh polyline from vertex START through its neighbour NEXT (on through inner vertices of even valence), one per polyline vertex; 'vertex ID VALUE' gives one vertex.
    fit: a mesh (V, F). Target mesh with the plan's vertex order: least-squares fit of its heights (002 eq. 14) instead of guide curves (vertical grid plans).
    fit_heights: a path (pathlib.Path or str naming a file) or the file's text. A partial target: lines 'VERTEX HEIGHT'; the least-squares fit follows only these vertices (they must determine the lift; solver direct).
    closed_strip: a path (pathlib.Path or str naming a file) or the file's text. Closed strip instead of a plan (002 §2.5): one line per vertex pair 'XI YI ZI XO YO' (inner vertex with its prescribed height, outer vertex), quads (inner i, outer i, outer i+1, inner i+1) closing back to the first pair; several rings with more outer x y pairs per line. Reports a of eq. 8: a != 1 gives the one closing outer height; a = 1 projects the inner heights onto V.Z = 0.
    weld: merge the input meshes' coincident vertices (within 1e-9 of the bounding-box diagonal) first, as unwelded exports need; without it such a mesh is refused. Vertex ids (fixed, ...) then number the welded mesh; result.weld_map maps each input vertex to it.
    row: (numbers) Guide values of vertices (0, j), j = 0..cols of a grid plan.
    column: (numbers) Guide values of vertices (i, 0), i = 0..rows; its first value must equal row's.
    projection: (choice) Lines of the vertices: vertical (values are heights), cylindrical (through the plan vertex, perpendicular to axis; values are distances from the axis) or central (through centre and the plan vertex; values are distances from it).
    axis: (numbers, 6 values) Cylindrical axis: a point and a direction.
    centre: (numbers, 3 values) Centre of the central projection.
    hold: (vertex_values) Hard constraint of a fit (002 §3.3), or the prescribed heights of a plan of polygons (002 §4.2): vertex heights met exactly (KKT system, solver direct).
    volume: (number) Hard constraint of a fit: the volume under the mesh over its plan (z = 0 as the base), met exactly.
    max_height: (number) Hard constraint of a fit: no vertex above this height (active set).
    solver: (choice) direct: propagation (linear time) or the normal equations of the fit; gp: guided projection (one iteration when vertical, several for other projections; the guides are first checked by propagation); ceres: Levenberg-Marquardt on the same rows (the cross-check).
    max_iterations: (int, >= 1, <= 100000) gp or ceres with a non-vertical projection: iterations at most.
    tolerance: (number, > 0) The result's planarity to reach in every mode (with guides or a projection: max |det(p1-p0, p2-p0, p3-p0)| / (edge lengths) and the guide error; grid plans and closed strips: max planarity, diagonal distance / mean edge).
    outer_height: (number) closed_strip with a = 1: the height of the first outer vertex (free).
    allow_folded_plan: (bool) Lift a plan view whose quads overlap or are not convex in x, y (refused by default), with a warning naming the faces.
    outputs: optional outputs to make as well (none); each is an attribute of the result.
    callback: called with each iteration record (the keys of report.history's entries); returning False stops the run (status USER_ABORT). Ctrl-C stops it too and raises KeyboardInterrupt.

Returns a MarionetteResult: `report` (a Report: status, converged, iterations, history, initial and final measures, options), `vertices` and `faces` (the mesh): the lifted mesh, and
When the run fails numerically, the result's mesh and outputs are None and report.status is FAILURE.

Raises TypeError or ValueError naming the argument for bad arguments; warns (GprojWarning) when the input is far from the asked net or the result needs attention.
"""
    ...

class CanalOptions:
    """The options of canal()."""
    first_point: Optional[Sequence[float]]
    """(numbers, 3 values) The point that fixes the first circle (with P_0 and P_1)."""
    lengths: Optional[Sequence[float]]
    """(numbers, > 0) |P_k Q_k| for every curve point."""
    length: Optional[float]
    """(number, > 0) The same |P_k Q_k| for every curve point."""
    normal: Optional[Sequence[float]]
    """(numbers, 3 values) Normal of the cyclidic net at P_0 (not given: in the first quad's plane, across the curve; with second_curve: the surface normal at P_0, required)."""
    normal_angle: Optional[float]
    """(number, deg, >= -89, <= 89) The normal at P_0 at this angle to a reference plane (000 §3.3): the given or default normal is turned onto that cone (the nearest such normal), and smooth keeps it there, turning it about the plane's normal only."""
    reference_plane: Optional[Sequence[float]]
    """(numbers, 3 values) With normal_angle: the reference plane's normal (not given: 0,0,1, a horizontal plane)."""
    psi: float
    """(number, rad, >= -1000, <= 1000) Rotation of the frame's first tangent about the normal."""
    segments: int
    """(int, >= 1, <= 100000) Quads across the strip in the canal mesh."""
    section_scales: Optional[Sequence[float]]
    """(numbers, > 0) C-canal surface (000 §5.2): one factor per segment scaling the first arc's edges into a planar cross-section; the lengths are then the C-canal's."""
    closed: bool
    """(bool) Close the curve by the edge P_n -> P_0 (000 §4.2): the closing circle sets the last length (case 1) or also moves Q_0 (case 2); the frame is closed around the curve where it can be."""
    cospherical_tolerance: float
    """(number, >= 0) With closed: the end circles count as co-spherical (case 1) within this distance (per mean edge)."""
    frame_tolerance: float
    """(number, deg, >= 0) With closed: the frame closes around the curve when it misses itself by at most this."""
    smooth: bool
    """(bool) Minimise the smoothness energy of 000 eq. 5."""
    length_weight: float
    """(number, >= 0) Weight keeping the lengths near the input during smooth."""
    fixed_lengths: bool
    """(bool) With smooth: keep the lengths, smooth over the frame only."""
    max_iterations: int
    """(int, >= 1, <= 100000) BFGS iterations at most (smooth, C-canal)."""
    surface_segments: Optional[int]
    """(int, >= 1, <= 1000) Fine quads along every arc of the smooth surface (not given: 8)."""
    def __init__(
        self,
        *,
        first_point: Optional[Sequence[float]] = None,
        lengths: Optional[Sequence[float]] = None,
        length: Optional[float] = None,
        normal: Optional[Sequence[float]] = None,
        normal_angle: Optional[float] = None,
        reference_plane: Optional[Sequence[float]] = None,
        psi: float = 0.0,
        segments: int = 12,
        section_scales: Optional[Sequence[float]] = None,
        closed: bool = False,
        cospherical_tolerance: float = 1e-06,
        frame_tolerance: float = 0.001,
        smooth: bool = False,
        length_weight: float = 0.1,
        fixed_lengths: bool = False,
        max_iterations: int = 200,
        surface_segments: Optional[int] = None,
    ) -> None: ...

class CanalResult(Result):
    """The result of canal(): the canal mesh (circular quads)."""
    output: Optional[Mesh]
    strip: Optional[Mesh]
    """the circular strip (2 x (n+1) vertices) (None unless asked in outputs=)"""
    surface: Optional[Mesh]
    """the smooth cyclidic surface (000 §2.2): a Dupin cyclide patch on every quad of the strip's cyclidic net, meshed along its curvature lines (None unless asked in outputs=)"""
    surface_picture: Optional[str]
    """a shaded picture of the smooth cyclidic surface (None unless asked in outputs=)"""
    picture: Optional[str]
    """a shaded picture of the canal mesh (None unless asked in outputs=)"""

def canal(
    curve: Union[ArrayLike, str, os.PathLike[str]],
    *,
    options: Optional[CanalOptions] = None,
    second_curve: Union[ArrayLike, str, os.PathLike[str], None] = None,
    first_point: Optional[Sequence[float]] = None,
    lengths: Optional[Sequence[float]] = None,
    length: Optional[float] = None,
    normal: Optional[Sequence[float]] = None,
    normal_angle: Optional[float] = None,
    reference_plane: Optional[Sequence[float]] = None,
    psi: float = 0.0,
    segments: int = 12,
    section_scales: Optional[Sequence[float]] = None,
    closed: bool = False,
    cospherical_tolerance: float = 1e-06,
    frame_tolerance: float = 0.001,
    smooth: bool = False,
    length_weight: float = 0.1,
    fixed_lengths: bool = False,
    max_iterations: int = 200,
    surface_segments: Optional[int] = None,
    outputs: Sequence[str] = (),
    callback: Optional[Callable[[Dict[str, Any]], Optional[bool]]] = None,
) -> CanalResult:
    """Canal surface from a circular strip (000 §3.2-3.3, §4.1): points P_k on a curve, a first point fixing the first circle and the lengths |P_k Q_k| give a strip of circular quads by propagation; a frame at P_0 makes it a cyclidic net whose crossing arcs are the canal surface's circles; the surface is meshed by circular quads between them. smooth minimises 000 eq. 5 (Ceres line-search BFGS); closed closes the strip around a closed curve (§4.2); section_scales makes a C-canal surface (§5.2). With second_curve and normal instead: spheres equidistant from the curve and a second curve (§4.1, eq. 6), meshed by circular quads between their circles.

Arguments:
    curve: Curve points P_0..P_n.
    options: a CanalOptions; keyword arguments override its fields.
    second_curve: an (n, 3) array of points, or the path of a text file of x y z lines. Fit the canal surface to this second curve instead (000 §4.1): the curve is then a line of curvature and normal the surface normal at P_0.
    first_point: (numbers, 3 values) The point that fixes the first circle (with P_0 and P_1).
    lengths: (numbers, > 0) |P_k Q_k| for every curve point.
    length: (number, > 0) The same |P_k Q_k| for every curve point.
    normal: (numbers, 3 values) Normal of the cyclidic net at P_0 (not given: in the first quad's plane, across the curve; with second_curve: the surface normal at P_0, required).
    normal_angle: (number, deg, >= -89, <= 89) The normal at P_0 at this angle to a reference plane (000 §3.3): the given or default normal is turned onto that cone (the nearest such normal), and smooth keeps it there, turning it about the plane's normal only.
    reference_plane: (numbers, 3 values) With normal_angle: the reference plane's normal (not given: 0,0,1, a horizontal plane).
    psi: (number, rad, >= -1000, <= 1000) Rotation of the frame's first tangent about the normal.
    segments: (int, >= 1, <= 100000) Quads across the strip in the canal mesh.
    section_scales: (numbers, > 0) C-canal surface (000 §5.2): one factor per segment scaling the first arc's edges into a planar cross-section; the lengths are then the C-canal's.
    closed: (bool) Close the curve by the edge P_n -> P_0 (000 §4.2): the closing circle sets the last length (case 1) or also moves Q_0 (case 2); the frame is closed around the curve where it can be.
    cospherical_tolerance: (number, >= 0) With closed: the end circles count as co-spherical (case 1) within this distance (per mean edge).
    frame_tolerance: (number, deg, >= 0) With closed: the frame closes around the curve when it misses itself by at most this.
    smooth: (bool) Minimise the smoothness energy of 000 eq. 5.
    length_weight: (number, >= 0) Weight keeping the lengths near the input during smooth.
    fixed_lengths: (bool) With smooth: keep the lengths, smooth over the frame only.
    max_iterations: (int, >= 1, <= 100000) BFGS iterations at most (smooth, C-canal).
    surface_segments: (int, >= 1, <= 1000) Fine quads along every arc of the smooth surface (not given: 8).
    outputs: optional outputs to make as well (strip, surface, surface_picture, picture); each is an attribute of the result.
    callback: called with each iteration record (the keys of report.history's entries); returning False stops the run (status USER_ABORT). Ctrl-C stops it too and raises KeyboardInterrupt.

Returns a CanalResult: `report` (a Report: status, converged, iterations, history, initial and final measures, options), `vertices` and `faces` (the mesh): the canal mesh (circular quads), and
    strip: the circular strip (2 x (n+1) vertices) (None unless asked in outputs=)
    surface: the smooth cyclidic surface (000 §2.2): a Dupin cyclide patch on every quad of the strip's cyclidic net, meshed along its curvature lines (None unless asked in outputs=)
    surface_picture: a shaded picture of the smooth cyclidic surface (None unless asked in outputs=)
    picture: a shaded picture of the canal mesh (None unless asked in outputs=)
When the run fails numerically, the result's mesh and outputs are None and report.status is FAILURE.

Raises TypeError or ValueError naming the argument for bad arguments; warns (GprojWarning) when the input is far from the asked net or the result needs attention.
"""
    ...

def grid(
    *,
    surface: Literal['paraboloid', 'hypar', 'hyperboloid', 'enneper', 'revolution'] = 'paraboloid',
    nu: int = 21,
    nv: int = 21,
    a: float = 0.3,
    b: float = 0.2,
    c: float = 0.0,
    wave: float = 0.0,
    noise: float = 0.05,
    diagonal: bool = False,
    seed: int = 1,
) -> Mesh:
    """A quad grid over [-1,1]^2 with every vertex moved by uniform noise: on z = a x^2 + b y^2 + c x y + wave sin(pi x) sin(pi y) (a test input for planarize), or an asymptotic net (hypar, hyperboloid, enneper; for anet and hnet) or a circular net (revolution; for the circular constructions).

    surface: (choice) paraboloid (z = a x^2 + b y^2 + c x y + wave sin(pi x) sin(pi y) over [-1,1]^2), an asymptotic net: hypar, hyperboloid, enneper, or a circular net: revolution (meridians and parallels of a surface of revolution).
    nu: (int, >= 2, <= 100000) Vertices along u (vertex (i, j) is i * nv + j).
    nv: (int, >= 2, <= 100000) Vertices along v.
    a: (number, >= -1000000, <= 1000000) Coefficient of x^2 (paraboloid).
    b: (number, >= -1000000, <= 1000000) Coefficient of y^2 (paraboloid).
    c: (number, >= -1000000, <= 1000000) Coefficient of x y (paraboloid).
    wave: (number, >= -1000000, <= 1000000) Coefficient of sin(pi x) sin(pi y) (paraboloid).
    noise: (number, >= 0, <= 1000000) Noise amplitude as a fraction of the grid spacing (of the mean edge for the nets).
    diagonal: (bool) The lattice turned by 45 degrees, so that the quads' diagonals (not their edges) follow the asymptotic lines of the nets (an input for anet --net diagonal) or the x and y lines of the paraboloid (conjugate for c = wave = 0: an input for planarize --net diagonal); not for revolution.
    seed: (int, >= 0, <= 4294967295) Random seed.

Returns a Mesh (V, F): (n, 3) float64 vertices and (m, 4) int32 faces.
"""
    ...
