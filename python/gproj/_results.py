"""What a run gives back: the result mesh, the other outputs, and a typed report."""

from __future__ import annotations

import copy
from typing import Any, Dict, Iterator, List, Mapping, NamedTuple, Optional, Union

import numpy as np
import numpy.typing as npt


class Mesh(NamedTuple):
    """A polygon mesh as arrays: `V, F = mesh` unpacks it."""

    vertices: npt.NDArray[np.float64]  # (n, 3)
    faces: Union[npt.NDArray[np.int32], List[List[int]]]  # (m, k) int32, or a list of faces of mixed sizes


class Report(Mapping[str, Any]):
    """The report of a run: the keys of the command line's `--report`, as attributes.

    `report.converged`, `report.status`, `report.final["max_planarity"]`, ...; `report["key"]`
    and `to_dict()` give the same values. Counts are integers.
    """

    def __init__(self, data: Mapping[str, Any]):
        self._data: Dict[str, Any] = dict(data)

    def __getattr__(self, name: str) -> Any:
        if name.startswith("_"):
            raise AttributeError(name)
        try:
            return self._data[name]
        except KeyError:
            raise AttributeError(
                f"the report has no '{name}' (it has: {', '.join(sorted(self._data))})"
            ) from None

    def __getitem__(self, key: str) -> Any:
        return self._data[key]

    def __iter__(self) -> Iterator[str]:
        return iter(self._data)

    def __len__(self) -> int:
        return len(self._data)

    def to_dict(self) -> Dict[str, Any]:
        """A deep copy of the report as plain dicts and lists (what `--report` writes)."""
        return copy.deepcopy(self._data)

    def __repr__(self) -> str:
        command = self._data.get("command", "?")
        status = self._data.get("status", "?")
        return f"<gproj.Report {command}: {status}, {self._data.get('iterations', 0)} iterations>"


class Result:
    """One run: `report`, the main output (`vertices` and `faces` when it is a mesh, else
    `output`), every other output by its name (None unless asked with `outputs=`), and the
    problem's arrays (e.g. `weights`) by name."""

    problem: str = ""
    report: Report
    output: Any
    vertices: Optional[npt.NDArray[np.float64]]
    faces: Union[npt.NDArray[np.int32], List[List[int]], None]

    def __init__(self, report: Report, output: Any, outputs: Mapping[str, Any],
                 arrays: Mapping[str, npt.NDArray[Any]]):
        self.report = report
        self.output = output
        self.vertices, self.faces = (output.vertices, output.faces) if isinstance(
            output, Mesh) else (None, None)
        self.outputs: Dict[str, Any] = dict(outputs)
        self.arrays: Dict[str, npt.NDArray[Any]] = dict(arrays)
        # With weld=True: input vertex -> vertex of the welded mesh (and of the result), for the
        # first mesh input, and per mesh input by name.
        self.weld_map: Optional[npt.NDArray[np.int32]] = None
        self.weld_maps: Dict[str, npt.NDArray[np.int32]] = {}
        self._warm: Any = None  # (the problem's function object, _core._WarmStart) or None
        for name, value in list(self.outputs.items()) + list(self.arrays.items()):
            setattr(self, name, value)

    @property
    def converged(self) -> bool:
        """Whether the problem's tolerance is met (the report's `converged`)."""
        return bool(self.report.converged)

    @property
    def status(self) -> str:
        """CONVERGENCE, DIRECT, COMPLETED (converged) or NO_CONVERGENCE, STALLED, USER_ABORT,
        FAILURE."""
        return str(self.report.status)

    def resolve(self, moved: Any = None, fixed: Any = None, *, soft_terms: bool = False,
                callback: Any = None, **options: Any) -> "Result":
        """A warm re-solve after an edit, for the problems whose result is a mesh of the
        input's connectivity (planarize, anet): starts from this result's vertices, puts the
        vertices in `moved` ({vertex: (x, y, z)}, or (ids, positions) arrays) where asked and
        holds them, holds the `fixed` ones (ids) too, beside those this run held, and re-runs
        with this run's inputs and options (`options` override them; None restores a default).
        Vertex ids are this result's (after any weld). The soft terms (closeness, fairness)
        start off unless soft_terms=True, so the re-solve pulls back to the tolerance only what
        the edit broke: one or two iterations after a small edit. Returns a new result; raises
        ValueError for a vertex out of range, moved twice or a non-finite position, and
        TypeError when the problem has no warm re-solve (or the result was pickled or copied,
        which drops what the re-solve starts from)."""
        warm = getattr(self, "_warm", None)
        if warm is None:
            raise TypeError(f"{self.problem}(): this result has no warm re-solve (planarize and "
                            "anet results have one, when their run ended with a result)")
        problem, state = warm
        assert self.vertices is not None
        return problem.resolve(state, len(self.vertices), moved, fixed,  # type: ignore[no-any-return]
                               soft_terms, callback, options)

    def __getstate__(self) -> Dict[str, Any]:
        # Pickled and deep-copied results drop what resolve starts from (a handle to the
        # library's copy of the run): they cannot re-solve.
        state = dict(self.__dict__)
        state["_warm"] = None
        return state

    @property
    def mesh(self) -> Optional[Mesh]:
        """The main output as a Mesh, when it is one."""
        return self.output if isinstance(self.output, Mesh) else None

    def __repr__(self) -> str:
        what = (f"{len(self.vertices)} vertices" if self.vertices is not None else
                type(self.output).__name__)
        return f"<gproj.{type(self).__name__}: {self.status}, {what}>"
