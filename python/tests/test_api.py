"""Strict input of the package: shapes, unwelded meshes, edge-length ranges, options objects."""

import numpy as np
import pytest

import gproj


def unweld(V, F):
    """Each face with its own copies of its corners, as CAD exports often are."""
    F = np.asarray(F)
    return V[F.ravel()].copy(), np.arange(F.size, dtype=np.int32).reshape(F.shape)


def test_an_unwelded_mesh_is_refused_with_a_count_or_welded_with_its_map():
    """planarize refuses an unwelded mesh naming the count; weld=True merges it, returns the map
    and planarises the welded surface (no panel drifts apart)."""
    V, F = gproj.grid(nu=8, nv=8, noise=0.05)
    Vu, Fu = unweld(V, F)
    with pytest.raises(ValueError, match=r"vertex 4 coincides with vertex 3 \(132 of the 196 "
                                         r"vertices repeat an earlier one.*weld merges them"):
        gproj.planarize(Vu, Fu)
    r = gproj.planarize(Vu, Fu, weld=True, tolerance=1e-8)
    assert r.converged and len(r.vertices) == len(V)
    assert r.weld_map.shape == (len(Vu),) and r.weld_map.max() == len(V) - 1
    # Every input corner maps to the welded vertex at its position, and shared corners stay
    # shared in the result: the panels still meet.
    assert np.max(np.abs(r.vertices[r.weld_map] - r.vertices[r.weld_map])) == 0
    assert np.max(np.linalg.norm(Vu - V[F.ravel()], axis=1)) == 0
    assert r.report.welded["mesh"] == {"input_vertices": len(Vu), "vertices": len(V)}
    with pytest.raises(TypeError, match="weld: expected a bool"):
        gproj.planarize(Vu, Fu, weld=1)


def test_problem_arrays_are_checked_by_shape():
    """set_values and add_closeness refuse a transposed array; a Python term's transposed
    jacobian is refused."""
    V, _ = gproj.grid(nu=4, nv=5)
    p = gproj.Problem()
    b = p.add_block("v", len(V), 3)
    with pytest.raises(ValueError, match=r"values: shape \(3, 20\), expected \(20, 3\)"):
        p.set_values(b, V.T.copy())
    with pytest.raises(ValueError, match=r"targets: shape \(3, 20\), expected \(20, 3\)"):
        p.add_closeness(b, targets=V.T.copy())
    p.set_values(b, V)
    assert np.array_equal(p.values(b), V)

    def on_sphere(x, e):  # two rows per point so that a transposed jacobian has another shape
        return np.array([x @ x - 1.0, x[2]]), np.stack([2 * x, np.array([0.0, 0.0, 1.0])]).T

    p.add_term("sphere", on_sphere, 2, p.items(b)[:, None])
    with pytest.raises(ValueError, match=r"the jacobian must have shape \(2, 3\).*not \(3, 2\)"):
        p.solve()


def test_edge_length_maxima_are_enforced():
    """edge_length=(0, max) below many input edges: every edge ends under the maximum (to the
    tolerance) and the run converges; out_of_range_edges reports the count."""
    V, F = gproj.grid(nu=10, nv=10, noise=0.05, seed=3)
    E = {tuple(sorted((f[k], f[(k + 1) % 4]))) for f in F for k in range(4)}
    E = np.array(sorted(E))

    def lengths(X):
        return np.linalg.norm(X[E[:, 0]] - X[E[:, 1]], axis=1)

    top = float(np.percentile(lengths(V), 60))
    assert (lengths(V) > top * 1.01).sum() > 50
    r = gproj.planarize(V, F, edge_length=[0.0, top], tolerance=1e-6, max_iterations=200)
    assert r.converged, r.report.termination
    mean = lengths(r.vertices).mean()
    assert lengths(r.vertices).max() <= top + 1e-6 * mean
    assert r.report.final["out_of_range_edges"] == 0
    assert r.report.initial["out_of_range_edges"] > 50
    # The report names what its tolerance bounds, as the command line's and the service's do.
    assert r.report.tolerance_measure == "max_planarity"
    assert r.report.tolerance == 1e-6
    assert r.report.final["max_planarity"] <= r.report.tolerance


def test_required_options_can_come_from_an_options_object():
    """A required option (beams' height) may be given in options= instead of a keyword, and its
    absence is refused naming it."""
    V, F = gproj.grid(nu=5, nv=5)
    with pytest.raises(TypeError, match="missing the required option 'height'"):
        gproj.beams(V, F)
    with pytest.raises(TypeError, match="height"):
        gproj.BeamsOptions()


def test_curves_b_splines_and_vertex_ids_may_be_paths(tmp_path):
    """A path (str or pathlib.Path) is read as the command line reads the file; the result is
    the array's, and a bad file is named with its line."""
    import json
    import pathlib

    data = pathlib.Path(__file__).resolve().parents[2] / "examples" / "data"
    curve = data / "canal_curve.txt"
    canal = {"first_point": [-0.5, 0.5, 2], "length": 2}
    from_array = gproj.canal(np.loadtxt(curve), **canal)
    assert from_array.report.to_dict()["input"] is None
    for path in (curve, str(curve)):
        from_path = gproj.canal(path, **canal)
        assert np.array_equal(from_path.vertices, from_array.vertices)
        assert from_path.report.to_dict()["input"] == str(curve)

    surface = data / "freeform_10x10.json"
    options = {"max_iterations": 2}
    from_dict = gproj.weingarten(json.loads(surface.read_text()), **options)
    assert gproj.weingarten(surface, **options).output == from_dict.output

    V, F = gproj.grid(nu=6, nv=6, noise=0.05)
    ids = tmp_path / "fixed.txt"
    ids.write_text("# corners\n0 5\n30 35\n")
    from_file = gproj.planarize(V, F, fixed=ids)
    assert np.array_equal(from_file.vertices,
                          gproj.planarize(V, F, fixed=[0, 5, 30, 35]).vertices)
    assert from_file.report.to_dict()["fixed"] == str(ids)
    assert from_file.report.to_dict()["input"] is None

    bad = tmp_path / "bad_curve.txt"
    bad.write_text("0 0 0\n1 x 0\n")
    with pytest.raises(ValueError, match=r"bad_curve.txt:2: "):
        gproj.canal(bad, **canal)
    with pytest.raises(ValueError, match=r"nope.txt"):
        gproj.canal(tmp_path / "nope.txt", **canal)
    ids.write_text("0 99\n")
    with pytest.raises(ValueError, match=r"fixed.txt:1: .*99"):
        gproj.planarize(V, F, fixed=ids)
