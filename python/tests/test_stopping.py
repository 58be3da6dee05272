"""A callback returning False (or Ctrl-C) stops every stage of a run: H-nets in their A-net step,
their rounds and their joint solve, Weingarten levels and paneling, canal smoothing, ..."""
import functools
import json
import os
import signal

import numpy as np
import pytest

import gproj
from conftest import ROOT

DATA = ROOT / "examples" / "data"


class Stopper:
    """A callback that returns False from its `stop_at`-th record on (0: never), counting."""

    def __init__(self, stop_at=0):
        self.stop_at = stop_at
        self.records = 0
        self.after_stop = 0

    def __call__(self, record):
        if self.stop_at and self.records >= self.stop_at:
            self.after_stop += 1
        self.records += 1
        return not self.stop_at or self.records < self.stop_at


def run(function, args, kwargs, stop_at=0):
    stopper = Stopper(stop_at)
    result = function(*args, callback=stopper, **kwargs)
    return result, stopper


def expect_user_abort(result, stopper, where=""):
    report = result.report
    assert report.status == "USER_ABORT", (where, report.termination)
    assert report.termination.startswith("USER_ABORT")
    assert not report.converged and not report.failed
    assert result.status == "USER_ABORT" and not result.converged
    assert stopper.after_stop <= 1, where
    assert stopper.records == stopper.stop_at, (where, "the run went on past the stop")


def hnet_stages(result, stopper):
    """The first record of every round's vertex update (the A-net step's records come first)."""
    first = len(result.report["history"]) + 1
    starts = []
    for r in result.report["rounds"]:
        starts.append((first, r["solver_iterations"]))
        first += r["solver_iterations"]
    assert first - 1 == stopper.records  # every iterate is a record
    return starts


def enneper():
    V, F = gproj.read_mesh(str(DATA / "enneper_41x41_jitter3.obj"))
    reference = gproj.read_mesh(str(DATA / "enneper_41x41.obj"))
    return (V, F), {"reference": reference}


@functools.lru_cache(maxsize=None)
def enneper_unstopped():
    """The shipped Enneper H-net run to its end with a callback that never stops (seconds)."""
    args, kwargs = enneper()
    return run(gproj.hnet, args, kwargs)


def test_hnet_stops_in_its_a_net_step():
    V, F = gproj.grid(nu=7, nv=7, surface="hypar", noise=0.05)
    result, stopper = run(gproj.hnet, (V, F), {}, stop_at=2)
    expect_user_abort(result, stopper)
    assert result.report["rounds"] == [] and result.output is None


def test_hnet_stops_in_its_rounds_and_in_its_joint_solve():
    # The shipped demo of issue 32: after a stop the rounds ran on for seconds and ended
    # "maximum number of rounds reached".
    args, kwargs = enneper()
    full, stopper = enneper_unstopped()
    assert full.report.status == "CONVERGENCE", full.report.termination
    assert "joint solve" in full.report.termination
    stages = hnet_stages(full, stopper)
    (round0, steps0), (joint, steps_joint) = stages[0], stages[-1]
    assert steps0 >= 2 and steps_joint >= 2
    result, stopper = run(gproj.hnet, args, kwargs, stop_at=round0 + 1)
    expect_user_abort(result, stopper, "round 0")
    assert "round 0" in result.report.termination
    assert len(result.report["rounds"]) == 1
    assert result.output is not None  # the last iterate, with the round's weights
    result, stopper = run(gproj.hnet, args, kwargs, stop_at=joint + 1)
    expect_user_abort(result, stopper, "joint solve")
    assert "joint solve" in result.report.termination
    assert len(result.report["rounds"]) == len(stages)
    assert result.report["rounds"][-1]["solver_iterations"] == 2


def test_hnet_with_ceres_stops_in_its_joint_solve():
    V, F = gproj.grid(nu=7, nv=7, surface="hypar", noise=0.05)
    kwargs = {"solver": "ceres"}
    full, stopper = run(gproj.hnet, (V, F), kwargs)
    stages = hnet_stages(full, stopper)
    assert len(stages) >= 2
    first, steps = stages[-1] if stages[-1][1] > 0 else stages[0]
    assert steps >= 2
    result, stopper = run(gproj.hnet, (V, F), kwargs, stop_at=first + 1)
    expect_user_abort(result, stopper)


def test_hnet_of_an_annulus_stops_in_its_joint_solve():
    V, F = gproj.read_mesh(str(DATA / "enneper_41x41_jitter3.obj"))
    reference = gproj.read_mesh(str(DATA / "enneper_41x41.obj"))
    F = np.delete(F, 20 * 40 + 20, axis=0)  # an inner quad: not simply connected
    kwargs = {"reference": reference, "allow_not_simply_connected": True}
    full, stopper = run(gproj.hnet, (V, F), kwargs)
    stages = hnet_stages(full, stopper)
    assert len(stages) == 2 and stages[1][1] >= 2, full.report.termination
    result, stopper = run(gproj.hnet, (V, F), kwargs, stop_at=stages[1][0] + 1)
    expect_user_abort(result, stopper)
    assert len(result.report["rounds"]) == 2


def test_ctrl_c_in_the_hnet_rounds_raises_keyboard_interrupt_at_once():
    args, kwargs = enneper()
    full, stopper = enneper_unstopped()
    first_round_record = hnet_stages(full, stopper)[0][0]
    records = []

    def callback(record):
        records.append(record)
        if len(records) == first_round_record:
            os.kill(os.getpid(), signal.SIGINT)
        return True

    with pytest.raises(KeyboardInterrupt):
        gproj.hnet(*args, callback=callback, **kwargs)
    assert len(records) <= first_round_record + 1


def freeform():
    with open(DATA / "freeform_10x10.json") as f:
        return json.load(f)


def test_weingarten_stops_in_a_later_level_and_skips_its_paneling():
    surface = freeform()
    kwargs = {"refine": 1, "max_iterations": 4, "panels": [3, 3],
              "outputs": ["panel_picture", "seam_histograms"]}
    full, stopper = run(gproj.weingarten, (surface,), kwargs)
    levels = [r["level"] for r in full.report["history"]]
    assert levels[-1] == 1 and "panels" in full.report
    first_of_level_1 = levels.index(1) + 1
    result, stopper = run(gproj.weingarten, (surface,), kwargs, stop_at=first_of_level_1 + 1)
    expect_user_abort(result, stopper)
    assert [r["level"] for r in result.report["history"]][-1] == 1
    assert "panels" not in result.report and result.panel_picture is None
    assert result.output is not None  # the B-spline of the last iterate


def test_canal_smoothing_stopped_at_its_last_record_is_a_user_abort():
    curve = np.loadtxt(DATA / "canal_curve.txt")
    kwargs = {"first_point": [-0.5, 0.5, 2], "length": 2, "smooth": True}
    full, stopper = run(gproj.canal, (curve,), kwargs)
    assert full.report.status == "CONVERGENCE"
    # The last record is BFGS' final iterate, met by its tolerance: a stop there still counts.
    result, stopper = run(gproj.canal, (curve,), kwargs, stop_at=stopper.records)
    expect_user_abort(result, stopper)


def sweep_cases():
    V, F = gproj.grid(nu=9, nv=9, noise=0.05)
    H, HF = gproj.grid(nu=15, nv=15, surface="hypar", noise=0.05)
    R, RF = gproj.read_mesh(str(DATA / "revolution_13x17.obj"))
    lengths = [0.09 + 0.05 * np.sin(j / 5.0) for j in range(16)]
    P, PF = gproj.read_mesh(str(DATA / "marionette_plan_21x21.obj"))
    row = [0.4 * np.sin(j / 4.0) for j in range(21)]
    column = [0.3 * (1 - np.cos(i / 5.0)) for i in range(21)]
    curve = np.loadtxt(DATA / "canal_curve.txt")
    return [
        ("planarize", gproj.planarize, (V, F), {}),
        ("planarize_ceres", gproj.planarize, (V, F), {"solver": "ceres"}),
        ("anet", gproj.anet, (H, HF), {}),
        ("hnet", gproj.hnet, (H, HF), {}),
        ("cyclidic", gproj.cyclidic, (R, RF), {"segments": 2}),
        ("combescure", gproj.combescure, (R, RF), {"row_lengths": lengths, "solver": "gp"}),
        ("combescure_ceres", gproj.combescure, (R, RF),
         {"row_lengths": lengths, "solver": "ceres"}),
        ("canal", gproj.canal, (curve,), {"first_point": [-0.5, 0.5, 2], "length": 2,
                                          "smooth": True}),
        ("weingarten", gproj.weingarten, (freeform(),), {"refine": 1, "max_iterations": 3}),
        ("marionette", gproj.marionette, (P, PF), {"row": row, "column": column, "solver": "gp"}),
    ]


@pytest.mark.parametrize("name,function,args,kwargs", sweep_cases(),
                         ids=[case[0] for case in sweep_cases()])
def test_every_iterating_run_stops_at_any_record(name, function, args, kwargs):
    full, stopper = run(function, args, kwargs)
    n = stopper.records
    assert n >= 2 and not full.report.failed, full.report.termination
    for stop_at in sorted({1, 2, 3, (n + 1) // 2, n}):
        if stop_at > n:
            continue
        result, stopper = run(function, args, kwargs, stop_at=stop_at)
        expect_user_abort(result, stopper, f"{name} stopped at record {stop_at} of {n}")


def without_seconds(rounds):
    return [{k: v for k, v in r.items() if k != "seconds"} for r in rounds]


def test_a_callback_that_never_stops_changes_nothing():
    args, kwargs = enneper()
    quiet = gproj.hnet(*args, **kwargs)
    watched, stopper = enneper_unstopped()
    assert stopper.records > len(watched.report["history"])  # the rounds' records too
    assert without_seconds(quiet.report["rounds"]) == without_seconds(watched.report["rounds"])
    assert quiet.report["final"] == watched.report["final"]
    assert quiet.output == watched.output


def test_ctrl_c_during_weingarten_paneling_raises_keyboard_interrupt_within_a_fraction():
    """Paneling sends no records (7 s here unstopped, trying mold counts down for a tolerance):
    the run polls for signals between its steps."""
    import threading
    import time

    sent = []

    def interrupt():
        sent.append(time.monotonic())
        os.kill(os.getpid(), signal.SIGINT)

    timer = threading.Timer(1.0, interrupt)  # the optimisation takes ~0.1 s, the paneling 7 s
    records = []

    def callback(record):
        if not records:
            timer.start()
        records.append(record)
        return True

    with pytest.raises(KeyboardInterrupt):
        try:
            gproj.weingarten(freeform(), max_iterations=2, panels=[10, 10],
                             panel_tolerance=[0.01, 10], callback=callback)
        finally:
            timer.cancel()
    raised = time.monotonic()
    assert sent, "the run ended before the signal"
    assert raised - sent[0] < 2.0, raised - sent[0]


def triangulated_hypar(n):
    V, F = gproj.grid(nu=n, nv=n, surface="hypar")
    return V, np.vstack([F[:, [0, 1, 2]], F[:, [0, 2, 3]]])


@pytest.mark.parametrize("name", ["field", "remesh"])
def test_ctrl_c_during_a_jet_fit_or_an_integer_grid_map_raises_within_a_fraction(name):
    """A 40,000-vertex triangulation: the field's jet fit takes ~3 s and sends no records, nor
    does the remeshing's map; both poll for signals between their steps."""
    import threading
    import time

    V, T = triangulated_hypar(200)
    sent = []

    def interrupt():
        sent.append(time.monotonic())
        os.kill(os.getpid(), signal.SIGINT)

    timer = threading.Timer(0.5, interrupt)
    kwargs = {"edge_length": 0.02} if name == "remesh" else {}
    timer.start()
    with pytest.raises(KeyboardInterrupt):
        try:
            getattr(gproj, name)(V, T, **kwargs)
        finally:
            timer.cancel()
    raised = time.monotonic()
    assert sent, "the run ended before the signal"
    assert raised - sent[0] < 1.0, raised - sent[0]
