"""Meshes in and out (paths as str or os.PathLike), per-face measures, B-spline curvature."""

from __future__ import annotations

import os
from typing import Any, Dict, Mapping, Optional, Sequence, Union

import numpy as np
import numpy.typing as npt

from gproj import _core
from gproj._results import Mesh


def _path(value: Any) -> str:
    if isinstance(value, (str, os.PathLike)):
        path = os.fspath(value)
        if isinstance(path, str):
            return path
    raise TypeError(f"path: expected a str or os.PathLike, not {type(value).__name__}")


def read_mesh(path: Union[str, "os.PathLike[str]"]) -> Mesh:
    """read_mesh(path) -> Mesh (V, F)

    Reads an .obj, .off or .ply polygon mesh, checked like the command line's inputs: V (n, 3)
    float64, F (m, k) int32 (a list of faces when their sizes differ). Raises ValueError naming
    the file, line and rule broken."""
    return Mesh(*_core.read_mesh(_path(path)))


def write_mesh(path: Union[str, "os.PathLike[str]"], V: Any, F: Any) -> None:
    """write_mesh(path, V, F)

    Writes a mesh atomically (temporary file, then rename) with exact double coordinates; the
    format from the extension (.obj, .off, .ply). Non-finite coordinates are refused."""
    _core.write_mesh(_path(path), V, F)


def face_values(V: Any, F: Any, *, circular: bool = False) -> Dict[str, npt.NDArray[Any]]:
    """The per-quad measures of `--face-values` (and of the report's maxima), as arrays of
    shape (m,).

        V: (n, 3) float vertex positions, F: (m, 4) integer quads.
        circular: also give each quad's concyclicity.

    Returns {"planarity": distance between the diagonals / the mesh's mean edge length,
    "planarity_abs": that distance in the mesh's units, "kink_deg": the larger angle between the
    two triangles of either diagonal split, "min_angle_deg": the smallest corner angle,
    "convex": bool, and with circular "concyclicity": distance of the corners to their fitted
    circle / mean edge}."""
    if not isinstance(circular, (bool, np.bool_)):
        raise TypeError(f"circular: expected a bool, not {type(circular).__name__}")
    return dict(_core.face_values(V, F, circular=bool(circular)))


def bspline_curvature(surface: Mapping[str, Any], *,
                      samples: Optional[Sequence[int]] = None) -> Dict[str, npt.NDArray[Any]]:
    """Mean and Gaussian curvature of a B-spline (exact, from its derivatives) at the samples
    `gproj weingarten` uses: the centres of a uniform NU x NV subdivision of the parameter
    domain.

        surface: the B-spline as a dict (as for weingarten).
        samples: [NU, NV] (default: 2 per control point and direction, weingarten's default).

    Returns {"u": (NU,), "v": (NV,), "H": (NU, NV), "K": (NU, NV)} float64 arrays; H[a, b] and
    K[a, b] are at (u[a], v[b]), in the surface's units (H = (k1 + k2) / 2, K = k1 k2)."""
    if samples is None:
        return dict(_core.bspline_curvature(surface))
    if isinstance(samples, (str, bytes)) or not hasattr(samples, "__iter__"):
        raise TypeError(f"samples: expected [NU, NV], two integers, not {type(samples).__name__}")
    return dict(_core.bspline_curvature(surface, samples=[_count("samples", s) for s in samples]))


def _count(name: str, value: Any) -> int:
    if isinstance(value, (bool, np.bool_)) or not isinstance(value, (int, np.integer)):
        raise TypeError(f"{name}: expected integers, not {type(value).__name__}")
    return int(value)
