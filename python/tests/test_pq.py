"""planarize (gproj::pq): results and reports equal to the command line's, vertex control."""
import pathlib
import pickle

import numpy as np
import pytest

import gproj
from conftest import assert_close, compare_with_command_line

DATA = pathlib.Path(__file__).resolve().parents[2] / "examples" / "data"


@pytest.mark.parametrize("variant", ["gp", "ceres", "circular", "options", "control", "schedule",
                                     "diagonal"])
def test_planarize_equals_the_command_line(cli, variant):
    V, F = gproj.grid(nu=7, nv=6, noise=0.05)
    kwargs, args = {
        "gp": ({}, []),
        "ceres": ({"solver": "ceres"}, ["--solver", "ceres"]),
        "circular": ({"circular": True, "tolerance": 1e-8}, ["--circular", "--tolerance", 1e-8]),
        "options": ({"closeness": 0.5, "fairness": 0.3, "fairness_order": 3, "epsilon": 1e-2,
                     "max_iterations": 7, "linear_solver": "eigen"},
                    ["--closeness", 0.5, "--fairness", 0.3, "--fairness-order", 3, "--epsilon",
                     1e-2, "--max-iterations", 7, "--linear-solver", "eigen"]),
        "control": ({"fixed": np.array([0, 41]), "glide_boundary": True, "min_angle": 10.0,
                     "edge_length": (0.01, 5.0), "reference": gproj.grid(nu=15, nv=15, noise=0.0)},
                    ["--fixed", cli.write_text("fixed.txt", "0 41\n"), "--glide-boundary",
                     "--min-angle", 10, "--edge-length", "0.01,5", "--reference",
                     cli.write_mesh("ref.obj", *gproj.grid(nu=15, nv=15, noise=0.0))]),
        "schedule": ({"soft_residual": 0.0, "epsilon_min": 0.0},
                     ["--soft-residual", 0, "--epsilon-min", 0]),
        "diagonal": ({"net": "diagonal"}, ["--net", "diagonal"]),
    }[variant]
    result = compare_with_command_line(cli, "planarize", V, F, kwargs, args)
    V_out, report = result.vertices, result.report
    Vc, _ = gproj.read_mesh(cli.path("out.obj"))
    assert_close(V_out, Vc)
    assert V_out.shape == V.shape and V_out.dtype == np.float64
    assert np.array_equal(result.faces, F)  # the input's connectivity
    if variant in ("gp", "circular", "control", "schedule"):
        assert report["converged"]
    if variant == "schedule":  # the fixed schedule: more iterations than the residual-tied one
        assert report["iterations"] > gproj.planarize(V, F).report.iterations
    if variant == "control":
        assert np.array_equal(V_out[[0, 41]], V[[0, 41]])  # held bit for bit
        assert report["final"]["max_glide_distance"] <= 1e-9
        assert report["final"]["non_convex_quads"] == 0


def test_planarize_refuses_bad_vertex_control():
    V, F = gproj.grid(nu=4, nv=4, noise=0.05)
    with pytest.raises(ValueError, match="out of range"):
        gproj.planarize(V, F, fixed=[0, 16])
    with pytest.raises(ValueError, match="both fixed and gliding"):
        gproj.planarize(V, F, fix_boundary=True, glide_boundary=True)


def test_planarize_accepts_lists_and_int_vertices():
    V, F = gproj.grid(nu=4, nv=4, noise=0.0)
    result = gproj.planarize(np.round(V * 10).astype(int) / 10, F.tolist())
    assert result.report["converged"] and result.converged


def test_a_boolean_mask_fixes_the_vertices_it_marks():
    V, F = gproj.grid(nu=5, nv=5, noise=0.05)
    mask = np.zeros(len(V), dtype=bool)
    mask[[3, 7, 11]] = True
    result = gproj.planarize(V, F, fixed=mask)
    V_out = result.vertices
    assert result.report["fixed_vertices"] == 3
    assert np.array_equal(V_out[mask], V[mask])
    assert not np.array_equal(V_out[[0, 1]], V[[0, 1]])
    with pytest.raises(ValueError, match="the boolean mask has 4 entries; the mesh has 25"):
        gproj.planarize(V, F, fixed=mask[:4])


def test_planarize_diagonal_keeps_the_quads():
    V, F = gproj.grid(nu=9, nv=9, a=0.3, b=-0.2, noise=0.05, diagonal=True)
    result = gproj.planarize(V, F, net="diagonal", outputs=["diagonal_mesh"])
    assert result.report["converged"] and result.report["net"] == "diagonal"
    assert np.array_equal(np.asarray(result.faces), np.asarray(F))  # the input's quads
    Vd, Fd = result.diagonal_mesh
    assert np.array_equal(Vd, result.vertices)  # the rings on the same vertices
    assert len(Fd) == len(result.report["diagonal_face_centres"]) == 7 * 7
    for ring in np.asarray(Fd):  # each ring planar
        p = Vd[ring]
        n = np.cross(p[2] - p[0], p[3] - p[1])
        assert abs(np.dot(p[1] - p[0], n)) / np.linalg.norm(n) < 1e-8


def test_a_result_resolves_warm_after_an_edit():
    """Result.resolve: one vertex of a planarised 41 x 41 grid moved by 5% of an edge is held
    exactly where it was put, and the quads are planar again within a few iterations, none
    folded; a second edit holds the first vertex too; bad edits raise naming the vertex."""
    V, F = gproj.grid(nu=41, nv=41, noise=0.05, seed=3)
    first = gproj.planarize(V, F, fixed=[0])
    assert first.converged
    edge = np.linalg.norm(first.vertices[F[0][0]] - first.vertices[F[0][1]])
    v = 20 * 41 + 20
    target = first.vertices[v] + [0.0, 0.0, 0.05 * edge]
    second = first.resolve({v: target})
    assert second.converged, second.report.termination
    assert second.report.iterations <= 3
    assert second.report.soft_free_start is True
    np.testing.assert_array_equal(second.vertices[v], target)
    np.testing.assert_array_equal(second.vertices[0], first.vertices[0])  # still held
    assert second.report.final["max_planarity"] <= 1e-6
    assert second.report.final["non_convex_quads"] == 0
    # Local: vertices more than 5 rows or columns away move by well under the edit.
    moved = np.linalg.norm(second.vertices - first.vertices, axis=1) / (0.05 * edge)
    i, j = np.divmod(np.arange(len(moved)), 41)
    far = (np.abs(i - 20) > 5) | (np.abs(j - 20) > 5)
    print(f"resolve: {second.report.iterations} iterations, nearby vertices up to "
          f"{moved[~far].max():.2f}, far ones up to {moved[far].max():.2f} (95%: "
          f"{np.percentile(moved[far], 95):.3f}) of the edit")
    assert moved[far].max() < 0.75 and np.percentile(moved[far], 95) < 0.2
    third = second.resolve(([v + 1], [first.vertices[v + 1] + [0.0, 0.0, 0.03 * edge]]),
                           tolerance=1e-3)
    assert third.converged and third.report.options["tolerance"] == 1e-3
    np.testing.assert_array_equal(third.vertices[v], target)
    with pytest.raises(ValueError, match="moved: vertex 99999 is out of range"):
        first.resolve({99999: [0.0, 0.0, 0.0]})
    with pytest.raises(ValueError, match="moved: the position of vertex 1 is not finite"):
        first.resolve({1: [0.0, 0.0, np.inf]})
    with pytest.raises(TypeError, match="did you mean 'tolerance'"):
        first.resolve(tolerence=1e-3)
    with pytest.raises(ValueError, match=r"moved: 1 ids but positions of shape \(2, 3\)"):
        first.resolve(([v], [target, target]))
    with pytest.raises(ValueError, match="fixed: vertex -1 is out of range"):
        first.resolve(fixed=[-1])
    # A pickled result keeps everything but what the re-solve starts from.
    copied = pickle.loads(pickle.dumps(first))
    np.testing.assert_array_equal(copied.vertices, first.vertices)
    with pytest.raises(TypeError, match="no warm re-solve"):
        copied.resolve({v: target})
    remeshed = gproj.remesh(*gproj.read_mesh(DATA / "monkey_saddle_tri.obj"), edge_length=0.15)
    with pytest.raises(TypeError, match="no warm re-solve"):
        remeshed.resolve({1: [0.0, 0.0, 0.0]})
