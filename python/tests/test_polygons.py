"""Polygon meshes from Python: gproj.dual of a triangle mesh, then gproj.planarize on faces of
mixed sizes (a list of lists), against an independent planarity measure and the command line."""
import math

import numpy as np
import pytest

import gproj
from conftest import assert_close


def lattice(n, height):
    """A triangular lattice of n x n vertices (valence 6 inside) of spacing 1/n over height."""
    V, F = [], []
    for j in range(n):
        for i in range(n):
            x, y = (i + 0.5 * j - 0.75 * n) / n, (j * math.sqrt(3) / 2 - 0.4 * n) / n
            V.append([x, y, height(x, y)])
    for j in range(n - 1):
        for i in range(n - 1):
            a = j * n + i
            F += [[a, a + 1, a + n], [a + 1, a + n + 1, a + n]]
    return np.array(V), np.array(F)


def max_plane_distance(V, F):
    """The largest distance of a face's corners from their least-squares plane / mean edge."""
    edges = [np.linalg.norm(V[f[k]] - V[f[(k + 1) % len(f)]]) for f in F for k in range(len(f))]
    worst = 0.0
    for f in F:
        P = V[list(f)] - V[list(f)].mean(axis=0)
        normal = np.linalg.svd(P)[2][-1]
        worst = max(worst, np.abs(P @ normal).max())
    return worst / np.mean(edges)


def test_dual_then_planarize_a_sphere_cap(cli):
    V, F = lattice(12, lambda x, y: math.sqrt(4 - x * x - y * y))
    dual = gproj.dual(V, F, boundary="keep")
    assert isinstance(dual.faces, list) and {len(f) for f in dual.faces} == {4, 5, 6}
    assert dual.report["faces_by_corners"][6] == 10 * 10
    before = max_plane_distance(dual.vertices, dual.faces)
    flat = gproj.planarize(dual.vertices, dual.faces, tolerance=1e-7)
    assert flat.converged
    assert before > 1e-4 and max_plane_distance(flat.vertices, dual.faces) < 1e-7
    assert flat.report.final["non_convex_quads"] == 0  # every face of 4 or more corners
    # The command line gives the same vertices.
    source = cli.write_mesh("hex.obj", dual.vertices, dual.faces)
    cli.run("planarize", source, "-o", cli.path("flat.obj"), "--tolerance", 1e-7)
    assert_close(flat.vertices, gproj.read_mesh(cli.path("flat.obj"))[0])
    with pytest.raises(ValueError, match="a circular mesh is made of quads"):
        gproj.planarize(dual.vertices, dual.faces, circular=True)
    with pytest.raises(ValueError, match="every face is a triangle"):
        gproj.planarize(V, F)
