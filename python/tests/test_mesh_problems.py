"""planarize, anet and hnet: results and reports equal to the command line's; callbacks, stop,
Ctrl-C."""
import os
import signal
import threading

import numpy as np
import pytest

import gproj
from conftest import assert_close, assert_reports_equal


def compare_with_command_line(cli, command, V, F, python_kwargs, args, output="out.obj"):
    source = cli.write_mesh("in.obj", V, F)
    cli.run(command, source, "-o", cli.path(output), "--report", cli.path("r.json"), *args)
    result, report = getattr(gproj, command)(V, F, **python_kwargs)
    assert_reports_equal(report, cli.read_report("r.json"))
    return result, report


@pytest.mark.parametrize("variant", ["gp", "ceres", "circular", "options", "control", "schedule"])
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
    }[variant]
    V_out, report = compare_with_command_line(cli, "planarize", V, F, kwargs, args)
    Vc, _ = gproj.read_mesh(cli.path("out.obj"))
    assert_close(V_out, Vc)
    assert V_out.shape == V.shape and V_out.dtype == np.float64
    if variant in ("gp", "circular", "control", "schedule"):
        assert report["converged"]
    if variant == "schedule":  # the fixed schedule: more iterations than the residual-tied one
        assert report["iterations"] > gproj.planarize(V, F)[1]["iterations"]
    if variant == "control":
        assert np.array_equal(V_out[[0, 41]], V[[0, 41]])  # held bit for bit
        assert report["final"]["max_glide_distance"] <= 1e-9
        assert report["final"]["non_convex_quads"] == 0


def test_anet_and_hnet_hold_fixed_vertices_like_the_command_line(cli):
    V, F = gproj.grid(nu=9, nv=9, surface="hyperboloid", noise=0.05)
    V_out, report = compare_with_command_line(
        cli, "anet", V, F, {"fixed": [0, 8], "min_angle": 10.0},
        ["--fixed", cli.write_text("fixed.txt", "0 8\n"), "--min-angle", 10])
    assert report["converged"]
    assert np.array_equal(V_out[[0, 8]], V[[0, 8]])
    assert report["final"]["non_convex_quads"] == 0
    with pytest.raises(ValueError, match="out of range"):
        gproj.hnet(V, F, fixed=[81])


def test_planarize_refuses_bad_vertex_control():
    V, F = gproj.grid(nu=4, nv=4, noise=0.05)
    with pytest.raises(ValueError, match="out of range"):
        gproj.planarize(V, F, fixed=[0, 16])
    with pytest.raises(ValueError, match="both fixed and gliding"):
        gproj.planarize(V, F, fix_boundary=True, glide_boundary=True)


def test_planarize_accepts_lists_and_int_vertices():
    V, F = gproj.grid(nu=4, nv=4, noise=0.0)
    V_out, report = gproj.planarize(np.round(V * 10).astype(int) / 10, F.tolist())
    assert report["converged"]


def test_callback_gets_history_records_and_can_stop():
    V, F = gproj.grid(nu=9, nv=9, noise=0.05)
    records = []

    def callback(record):
        records.append(record)
        return len(records) < 3

    _, report = gproj.planarize(V, F, callback=callback)
    assert len(records) == 3
    assert [r["iteration"] for r in records] == [0, 1, 2]
    assert sorted(records[0]) == sorted(report["history"][0])
    assert report["termination"].startswith("USER_ABORT")
    assert not report["converged"] and not report["failed"]
    assert report["iterations"] == 2


def test_callback_returning_none_continues():
    V, F = gproj.grid(nu=5, nv=5, noise=0.05)
    _, report = gproj.planarize(V, F, callback=lambda record: None)
    assert report["converged"]


def test_ceres_callback_stops():
    V, F = gproj.grid(nu=5, nv=5, noise=0.05)
    _, report = gproj.planarize(V, F, solver="ceres", callback=lambda record: False)
    assert len(report["history"]) == 1


def test_callback_exception_propagates():
    V, F = gproj.grid(nu=5, nv=5, noise=0.05)

    def callback(record):
        raise RuntimeError("stop here")

    with pytest.raises(RuntimeError, match="stop here"):
        gproj.planarize(V, F, callback=callback)


def test_ctrl_c_stops_the_run():
    V, F = gproj.grid(nu=121, nv=121, noise=0.05)
    records = []
    timer = threading.Timer(0.5, lambda: os.kill(os.getpid(), signal.SIGINT))
    timer.start()
    try:
        with pytest.raises(KeyboardInterrupt):
            # Fixed soft weights and an unreachable tolerance: runs until interrupted.
            gproj.planarize(V, F, tolerance=1e-300, soft_decay=1.0, max_iterations=100000,
                            callback=records.append)
    finally:
        timer.cancel()
    assert len(records) < 100000  # stopped (possibly at the very first record)


def test_bad_options_raise_errors_naming_the_keyword():
    V, F = gproj.grid(nu=3, nv=3)
    for kwargs, error, match in [
            ({"solver": "newton"}, ValueError, "solver: 'newton' is not one of gp, ceres"),
            ({"linear_solver": "mkl"}, ValueError,
             "linear_solver: 'mkl' is not one of cholmod, eigen"),
            ({"tolerance": -1.0}, ValueError, r"tolerance: -1 is not > 0"),
            ({"fairness_order": 4}, ValueError, r"fairness_order: 4 is not in \[2, 3\]"),
            ({"epsilon": 0.0}, ValueError, "epsilon: 0 is not > 0"),
            ({"tolerance": "small"}, TypeError, "tolerance: small is not a number"),
            ({"max_iterations": 2.5}, ValueError, "max_iterations: 2.5 is not an integer"),
            ({"max_iterations": 10**30}, ValueError,
             r"max_iterations: 1e\+30 is not in \[0, 100000\]"),
            ({"fixed": {1.5}}, TypeError, "fixed: expected .*an entry is float"),
            ({"circular": 1}, TypeError, "circular: 1 is not true or false"),
            ({"edge_length": 0.2}, TypeError, "edge_length: 0.2 is not a list of numbers"),
            ({"edge_length": (0.1, 0.2, 0.3)}, ValueError, r"edge_length: expects 2 numbers"),
            ({"tolerence": 1e-6}, TypeError, r"tolerence: there is no such option \(did you mean "
                                             r"tolerance\?\)"),
            ({"fixed": 5}, TypeError, "fixed: expected a sequence of 0-based vertex ids"),
            ({"fixed": [0.5]}, TypeError, "fixed: expected .*an entry is float"),
            ({"reference": V}, TypeError, r"reference: expected a pair \(V, F\)")]:
        with pytest.raises(error, match=match):
            gproj.planarize(V, F, **kwargs)


def test_a_boolean_mask_fixes_the_vertices_it_marks():
    V, F = gproj.grid(nu=5, nv=5, noise=0.05)
    mask = np.zeros(len(V), dtype=bool)
    mask[[3, 7, 11]] = True
    V_out, report = gproj.planarize(V, F, fixed=mask)
    assert report["fixed_vertices"] == 3
    assert np.array_equal(V_out[mask], V[mask])
    assert not np.array_equal(V_out[[0, 1]], V[[0, 1]])
    with pytest.raises(ValueError, match="the boolean mask has 4 entries; the mesh has 25"):
        gproj.planarize(V, F, fixed=mask[:4])


@pytest.mark.parametrize("star_form", ["normals", "quads"])
def test_anet_equals_the_command_line(cli, star_form):
    V, F = gproj.grid(nu=7, nv=7, surface="hypar", noise=0.05)
    V_out, _ = compare_with_command_line(cli, "anet", V, F, {"star_form": star_form},
                                         ["--star-form", star_form])
    assert_close(V_out, gproj.read_mesh(cli.path("out.obj"))[0])


def test_anet_with_a_reference(cli):
    V, F = gproj.grid(nu=6, nv=6, surface="hypar", noise=0.05)
    Vr, Fr = gproj.grid(nu=12, nv=12, surface="hypar", noise=0.0)
    cli.write_mesh("ref.obj", Vr, Fr)
    V_out, _ = compare_with_command_line(cli, "anet", V, F, {"reference": (Vr, Fr)},
                                         ["--reference", cli.path("ref.obj")])
    assert_close(V_out, gproj.read_mesh(cli.path("out.obj"))[0])


def test_anet_refuses_odd_valence():
    V = np.array([[0, 0, 0], [1, 0, 0], [1, 1, 0], [0, 1, 0], [2, 0, 0], [2, 1, 0]], float)
    with pytest.raises(ValueError):
        gproj.anet(V, [[0, 1, 2, 3], [1, 4, 5, 2], [0, 1, 4, 5]])


def test_hnet_equals_the_command_line(cli):
    V, F = gproj.grid(nu=6, nv=6, surface="hypar", noise=0.02)
    result, report = compare_with_command_line(cli, "hnet", V, F, {}, [], output="h.json")
    hnet = result["output"]
    import json
    with open(cli.path("h.json")) as f:
        expected = json.load(f)
    assert_reports_equal(hnet, expected)
    assert len(hnet["weights"]) == len(F)


def test_hnet_surface_equals_the_command_lines_surface_mesh(cli):
    V, F = gproj.grid(nu=5, nv=5, surface="hypar", noise=0.02)
    source = cli.write_mesh("in.obj", V, F)
    cli.run("hnet", source, "-o", cli.path("h.json"), "--surface-mesh", cli.path("s.obj"),
            "--samples", 3)
    result, report = gproj.hnet(V, F, outputs=["surface_mesh"], samples=3)
    Vs, Fs = result["surface_mesh"]
    Ve, Fe = gproj.read_mesh(cli.path("s.obj"))
    assert Vs.shape == (len(F) * 16, 3) and Fs.shape == (len(F) * 18, 3)
    assert_close(Vs, Ve)
    assert (Fs == Fe).all()
    assert "surface_mesh" not in gproj.hnet(V, F, rounds=1)[0]
    with pytest.raises(ValueError, match=r"samples: -1 is not in \[1, 200\]"):
        gproj.hnet(V, F, samples=-1)
    with pytest.raises(ValueError, match="outputs: hnet has no output 'surface'"):
        gproj.hnet(V, F, outputs=["surface"])


def test_hnet_callback_returning_false_stops_the_whole_run():
    V, F = gproj.grid(nu=7, nv=7, surface="hypar", noise=0.05)
    records = []

    def callback(record):
        records.append(record)
        return len(records) < 2

    result, report = gproj.hnet(V, F, callback=callback)
    assert len(records) == 2
    assert report["termination"].startswith("USER_ABORT")
    assert not report["converged"] and not report["failed"]
    assert report["rounds"] == [] and "output" not in result

