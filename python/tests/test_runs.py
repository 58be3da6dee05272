"""What every run shares: the callback's records and stop, Ctrl-C, errors naming the keyword."""
import os
import pathlib
import signal
import threading

import numpy as np
import pytest

import gproj

DATA = pathlib.Path(__file__).resolve().parents[2] / "examples" / "data"


def test_callback_gets_history_records_and_can_stop():
    V, F = gproj.grid(nu=9, nv=9, noise=0.05)
    records = []

    def callback(record):
        records.append(record)
        return len(records) < 3

    report = gproj.planarize(V, F, callback=callback).report
    assert len(records) == 3
    assert [r["iteration"] for r in records] == [0, 1, 2]
    assert sorted(records[0]) == sorted(report["history"][0])
    assert report["termination"].startswith("USER_ABORT")
    assert not report["converged"] and not report["failed"]
    assert report["iterations"] == 2


def test_callback_returning_none_continues():
    V, F = gproj.grid(nu=5, nv=5, noise=0.05)
    result = gproj.planarize(V, F, callback=lambda record: None)
    assert result.report["converged"] and result.converged


def test_ceres_callback_stops():
    V, F = gproj.grid(nu=5, nv=5, noise=0.05)
    report = gproj.planarize(V, F, solver="ceres", callback=lambda record: False).report
    assert len(report["history"]) == 1
    assert report["status"] == "USER_ABORT" and not report["converged"], report["termination"]
    assert report["termination"].startswith("USER_ABORT")


def test_a_smooth_canal_stopped_by_its_callback_is_a_user_abort():
    curve = np.loadtxt(DATA / "canal_curve.txt")
    result = gproj.canal(curve, first_point=[-0.5, 0.5, 2], length=2, smooth=True,
                         callback=lambda record: False)
    report = result.report
    assert report["status"] == "USER_ABORT", report["termination"]
    assert not report["converged"]
    assert result.status == "USER_ABORT" and not result.converged


def test_every_status_is_one_of_the_run_layers():
    V, F = gproj.grid(nu=5, nv=5, noise=0.05)
    statuses = {"CONVERGENCE", "DIRECT", "COMPLETED", "NO_CONVERGENCE", "STALLED",
                "USER_ABORT", "FAILURE"}
    for kwargs in ({}, {"max_iterations": 1, "tolerance": 1e-14}, {"solver": "ceres"}):
        result = gproj.planarize(V, F, **kwargs)
        report = result.report
        assert report["status"] in statuses
        assert report["termination"].startswith(report["status"])
        assert report["converged"] == (report["status"] in {"CONVERGENCE", "DIRECT", "COMPLETED"})
        assert (result.status, result.converged) == (report.status, report.converged)


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
            ({"tolerence": 1e-6}, TypeError, r"^planarize\(\) has no argument 'tolerence'; did you "
                                             r"mean 'tolerance'"),
            ({"fixed": 5}, TypeError, "fixed: expected a sequence of 0-based vertex ids"),
            ({"fixed": [0.5]}, TypeError, "fixed: expected .*an entry is float"),
            ({"reference": V}, TypeError, r"reference: expected a pair \(V, F\)")]:
        with pytest.raises(error, match=match):
            gproj.planarize(V, F, **kwargs)


def test_counts_and_element_ids_are_integers():
    V, F = gproj.grid(nu=6, nv=6, noise=0.05)
    report = gproj.planarize(V, F).report
    assert type(report["final"]["non_convex_quads"]) is int
    assert type(report["history"][-1]["non_convex_quads"]) is int
    assert type(report["final"]["max_planarity"]) is float
