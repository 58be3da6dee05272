"""python3 -m gproj.batch: job files (sweeps, globs), runs on a Dask cluster, per-job folders,
the summary, failures, timeouts, Ctrl-C and exit codes (docs/batch.md)."""
import csv
import json
import os
import signal
import subprocess
import sys
import time
import warnings

import numpy as np
import pytest

import gproj

distributed = pytest.importorskip("distributed")
psutil = pytest.importorskip("psutil")
from gproj import batch  # noqa: E402  (after the skip: batch runs on distributed)

pytestmark = pytest.mark.filterwarnings("ignore::DeprecationWarning:tornado")

PACKAGE_ROOT = os.path.dirname(os.path.dirname(os.path.abspath(gproj.__file__)))


@pytest.fixture(scope="module")
def scheduler():
    """One local cluster of 2 single-threaded workers for the module's batches (--scheduler);
    its worker processes must be gone once it is closed."""
    cluster = batch.start_local_cluster(distributed, 2)
    with distributed.Client(cluster) as client:
        pids = list(client.run(os.getpid).values())
    try:
        yield cluster.scheduler_address
    finally:
        cluster.close()
        assert_gone(pids)


def assert_gone(pids, wait=10.0):
    deadline = time.monotonic() + wait
    alive = pids
    while alive and time.monotonic() < deadline:
        time.sleep(0.1)
        alive = [p for p in alive if psutil.pid_exists(p) and
                 psutil.Process(p).status() != psutil.STATUS_ZOMBIE]
    assert not alive, f"processes left behind: {alive}"


def environment():
    return dict(os.environ, PYTHONPATH=PACKAGE_ROOT)


def command(jobs, out, *args):
    return [sys.executable, "-m", "gproj.batch", str(jobs), "-o", str(out), *map(str, args)]


def run_batch(jobs, out, *args, **kwargs):
    """The batch as a user runs it: a subprocess, gproj on its PYTHONPATH."""
    return subprocess.run(command(jobs, out, *args), capture_output=True, text=True,
                          env=environment(), timeout=120, **kwargs)


def write_jobs(directory, jobs):
    path = directory / "jobs.json"
    path.write_text(json.dumps(jobs, indent=1), encoding="utf-8")
    return path


def read_summary(out):
    with open(out / "summary.csv", newline="", encoding="utf-8") as f:
        rows = list(csv.DictReader(f))
    with open(out / "summary.json", encoding="utf-8") as f:
        assert [r["name"] for r in json.load(f)] == [r["name"] for r in rows]
    with open(out / "summary.json", encoding="utf-8") as f:
        return rows, json.load(f)


def quad_meshes(tmp_path):
    """Two small noisy grids in tmp_path/meshes and their (V, F) as read back."""
    (tmp_path / "meshes").mkdir()
    meshes = {}
    for name, nu, seed in [("a", 8, 1), ("b", 7, 2)]:
        V, F = gproj.grid(nu=nu, nv=8, noise=0.05, seed=seed)
        gproj.write_mesh(tmp_path / "meshes" / f"{name}.obj", V, F)
        meshes[f"meshes/{name}.obj"] = gproj.read_mesh(tmp_path / "meshes" / f"{name}.obj")
    return meshes


def assert_number(cell, expected):
    assert float(cell) == pytest.approx(expected, rel=1e-12, abs=1e-12)


def test_a_sweep_gives_the_direct_runs_results(tmp_path, scheduler):
    """12 jobs (2 meshes by glob x 3 closeness x 2 min_angle): exit 0, one folder per job with
    result.obj, face_values.csv, report.json and job.json, and summary rows whose statuses,
    iterations, measures and warnings are those of the same runs made directly."""
    meshes = quad_meshes(tmp_path)
    jobs = write_jobs(tmp_path, [{
        "name": "pq", "problem": "planarize", "inputs": {"mesh": "meshes/*.obj"},
        "options": {"tolerance": 1e-10, "max_iterations": 100}, "outputs": ["face_values"],
        "sweep": {"closeness": [1, 10, 100], "min_angle": [5, 10]}}])
    out = tmp_path / "results"
    done = run_batch(jobs, out, "--scheduler", scheduler)
    assert done.returncode == 0, done.stderr
    assert str(out) in done.stdout and "12 jobs (12 converged)" in done.stdout
    assert done.stderr.count("done") == 12 and "12/12 done" in done.stderr
    rows, data = read_summary(out)
    assert len(rows) == 12 == len({r["folder"] for r in rows})
    assert rows[0]["name"] == "pq_a_closeness=1_min_angle=5"
    assert list(rows[0])[:11] == ["name", "folder", "problem", "outcome", "status", "converged",
                                  "iterations", "seconds", "mesh", "closeness", "min_angle"]
    assert any(record["warnings"] for record in data)  # the workers' GprojWarnings
    for row, record in zip(rows, data):
        V, F = meshes[row["mesh"]]
        with warnings.catch_warnings(record=True) as caught:
            warnings.simplefilter("always")
            direct = gproj.planarize(V, F, tolerance=1e-10, max_iterations=100,
                                     closeness=record["closeness"], min_angle=record["min_angle"])
        assert record["warnings"] == [str(w.message) for w in caught
                                      if issubclass(w.category, gproj.GprojWarning)]
        assert row["warnings"] == " | ".join(record["warnings"])
        assert (row["outcome"], row["status"], row["converged"]) == (
            "converged", direct.status, "true")
        assert int(row["iterations"]) == record["iterations"] == direct.report.iterations
        for key, value in direct.report.final.items():
            assert_number(row[key], value)
            assert record[key] == pytest.approx(value, rel=1e-12, abs=1e-12)
        folder = out / row["folder"]
        assert sorted(p.name for p in folder.iterdir()) == [
            "face_values.csv", "job.json", "report.json", "result.obj"]
        assert np.max(np.abs(gproj.read_mesh(folder / "result.obj").vertices -
                             direct.vertices)) <= 1e-12
        report = json.loads((folder / "report.json").read_text())
        assert report["status"] == direct.status and report["options"] == direct.report.options
        assert json.loads((folder / "job.json").read_text())["options"]["closeness"] == \
            record["closeness"]


def test_failures_are_per_job_and_the_local_cluster_goes_away(tmp_path):
    """On its own local cluster (--workers 2): a missing mesh file and a triangle mesh for
    planarize fail (error text, error.txt, no report), a run capped at 1 iteration does not
    converge (still written), the others finish; exit 2; no process of the batch is left."""
    meshes = quad_meshes(tmp_path)
    V, F = meshes["meshes/a.obj"]
    gproj.write_mesh(tmp_path / "triangles.obj", V, np.concatenate([F[:, :3], F[:, [0, 2, 3]]]))
    jobs = write_jobs(tmp_path, [
        {"name": "good", "problem": "planarize", "inputs": {"mesh": "meshes/a.obj"}},
        {"name": "missing", "problem": "planarize", "inputs": {"mesh": "meshes/nope.obj"}},
        {"name": "triangles", "problem": "planarize", "inputs": {"mesh": "triangles.obj"}},
        {"name": "short", "problem": "planarize", "inputs": {"mesh": "meshes/b.obj"},
         "options": {"max_iterations": 1}},
        {"name": "anet", "problem": "anet", "inputs": {"mesh": "meshes/b.obj"},
         "options": {"tolerance": 1e-6}, "outputs": ["picture"]}])
    out = tmp_path / "out"
    process = subprocess.Popen(command(jobs, out, "--workers", 2), stdout=subprocess.PIPE,
                               stderr=subprocess.PIPE, text=True, env=environment(),
                               start_new_session=True)
    stdout, stderr = process.communicate(timeout=120)
    assert process.returncode == 2, stderr
    rows = {r["name"]: r for r in read_summary(out)[0]}
    assert [rows[n]["outcome"] for n in ["good", "missing", "triangles", "short"]] == [
        "converged", "failed", "failed", "not_converged"]
    assert "inputs.mesh" in rows["missing"]["error"] and "nope.obj" in rows["missing"]["error"]
    assert "every face is a triangle" in rows["triangles"]["error"]
    assert rows["short"]["status"] == "NO_CONVERGENCE" and rows["short"]["iterations"] == "1"
    assert rows["anet"]["outcome"] in ("converged", "not_converged")
    assert (out / "anet" / "picture.svg").read_text().lstrip().startswith("<")
    assert sorted(p.name for p in (out / "missing").iterdir()) == ["error.txt", "job.json"]
    assert (out / "short" / "result.obj").exists() and (out / "short" / "report.json").exists()
    assert "FAILED" in stderr and "5/5 done" in stderr and str(out) in stdout
    deadline = time.monotonic() + 10
    while time.monotonic() < deadline and in_session(process.pid):
        time.sleep(0.1)
    assert not in_session(process.pid)


def in_session(sid):
    """The live processes of a session (the batch's children are in it)."""
    left = []
    for p in psutil.process_iter(["status"]):
        try:
            if os.getsid(p.pid) == sid and p.info["status"] != psutil.STATUS_ZOMBIE:
                left.append(p.pid)
        except (ProcessLookupError, PermissionError):
            pass
    return left


def long_job(tmp_path, **extra):
    V, F = gproj.grid(nu=60, nv=60, noise=0.05)
    gproj.write_mesh(tmp_path / "big.obj", V, F)
    return dict({"problem": "planarize", "inputs": {"mesh": "big.obj"},
                 "options": {"tolerance": 1e-300, "max_iterations": 100000}}, **extra)


def test_a_timeout_cancels_the_job(tmp_path, scheduler):
    """A run that would go on for many seconds, with a timeout of 1 s: stopped by its callback
    (USER_ABORT), written, recorded as cancelled; exit 3."""
    quad_meshes(tmp_path)
    jobs = write_jobs(tmp_path, [
        long_job(tmp_path, name="long", timeout=1),
        {"name": "quick", "problem": "planarize", "inputs": {"mesh": "meshes/a.obj"}}])
    out = tmp_path / "out"
    start = time.monotonic()
    done = run_batch(jobs, out, "--scheduler", scheduler, "--measures", "max_planarity")
    assert done.returncode == 3, done.stderr
    assert time.monotonic() - start < 30
    long, quick = read_summary(out)[1]
    assert (long["outcome"], long["status"], long["converged"]) == ("cancelled", "USER_ABORT",
                                                                    False)
    # The summary's seconds are the report's: the solve alone. The timeout counts from the
    # job's start, the problem's setup included, so under load the solve gets a little less.
    assert 0.5 <= long["seconds"] < 10 and "timeout of 1 s" in long["error"]
    assert quick["outcome"] == "converged"
    assert list(quick)[-3:] == ["max_planarity", "warnings", "error"]
    assert json.loads((out / "long" / "report.json").read_text())["status"] == "USER_ABORT"
    assert "cancelled" in done.stdout and "CANCELLED" in done.stderr


@pytest.mark.parametrize("jobs, message", [
    ([{"name": "ok", "problem": "planarize", "inputs": {"mesh": "m.obj"}},
      {"name": "second", "problem": "planarize", "inputs": {"mesh": "m.obj"},
       "options": {"closenes": 1}}],
     'jobs[1] "second": options.closenes: planarize has no option "closenes"; did you mean '
     "'closeness'?"),
    ([{"problem": "planarise", "inputs": {"mesh": "m.obj"}}],
     'jobs[0]: problem: no problem named "planarise"; did you mean \'planarize\'?'),
    ([{"problem": "planarize", "inputs": {"mesh": "m.obj"}, "sweep": {"closeness": [1, -1]}}],
     "jobs[0]: sweep.closeness[1]: closeness: -1 is not >= 0"),
    ([{"problem": "planarize", "inputs": {"mesh": "m.obj"}, "options": {"min_angle": 89}}],
     "jobs[0]: options.min_angle: 89 is not in [0, 59.9]"),
    ([{"problem": "planarize", "inputs": {"mesh": "m.obj"}, "swep": {}}],
     "jobs[0]: swep: not a key of a job; did you mean 'sweep'?"),
    ([{"problem": "planarize", "inputs": {"mesh": "none/*.obj"}}],
     'jobs[0]: inputs.mesh: the pattern "none/*.obj" matches no file'),
    ([{"problem": "planarize", "inputs": {"mesh": "m.obj"}, "timeout": -1}],
     "jobs[0]: timeout: expected seconds, a number > 0, not -1"),
    ([{"problem": "planarize", "inputs": {"mesh": "m.obj"}, "outputs": ["pictures"]}],
     "jobs[0]: outputs[0]: planarize has no optional output \"pictures\"; did you mean "
     "'picture'?"),
    ([{"problem": "grid"}], "jobs[0]: problem: grid is a generator"),
    ([{"problem": "planarize", "inputs": {"mesh": "m.obj"}, "weld": "yes"}],
     'jobs[0]: weld: expected true or false, not "yes"'),
    ([{"problem": "canal", "weld": True}], "jobs[0]: weld: canal has no mesh input to weld"),
])
def test_a_bad_job_file_exits_1_naming_the_job_and_writes_nothing(tmp_path, jobs, message):
    path = write_jobs(tmp_path, jobs)
    done = run_batch(path, tmp_path / "out")
    assert done.returncode == 1
    [line] = done.stderr.splitlines()
    assert line.startswith(f"gproj batch: error: {path}: ") and message in line, line
    assert not (tmp_path / "out").exists()


def test_a_job_file_that_is_not_json_exits_1(tmp_path):
    path = tmp_path / "jobs.json"
    path.write_text('[{"problem": "planarize",\n', encoding="utf-8")
    done = run_batch(path, tmp_path / "out")
    assert done.returncode == 1 and "not valid JSON" in done.stderr and "line 2" in done.stderr
    assert not (tmp_path / "out").exists()


def test_entries_expand_into_named_jobs_with_unique_folders(tmp_path):
    """Globs and sweeps multiply, {fields} fill names, paths are relative to the job file, the
    folders are filesystem-safe and unique; --check lists the jobs and runs nothing."""
    quad_meshes(tmp_path)
    (tmp_path / "fixed.txt").write_text("0 1  # corners\n5\n", encoding="utf-8")
    jobs = write_jobs(tmp_path, [
        {"name": "{mesh}/c{closeness}", "problem": "planarize",
         "inputs": {"mesh": "meshes/*.obj", "fixed": "fixed.txt"},
         "sweep": {"closeness": [1, 10], "fairness": [0.5]}},
        {"name": "same", "problem": "planarize", "inputs": {"mesh": "meshes/a.obj",
                                                             "fixed": [0, 3]}},
        {"name": "same", "problem": "anet", "inputs": {"mesh": "meshes/b.obj"}, "timeout": 5}])
    expanded = batch.load_jobs(str(jobs), default_timeout=60)
    assert [j.name for j in expanded] == ["a/c1", "a/c10", "b/c1", "b/c10", "same", "same"]
    assert [j.folder for j in expanded] == ["a_c1", "a_c10", "b_c1", "b_c10", "same", "same-2"]
    assert expanded[1].inputs["mesh"] == str(tmp_path / "meshes" / "a.obj")
    assert expanded[1].swept == {"mesh": "meshes/a.obj", "closeness": 10, "fairness": 0.5}
    assert expanded[1].options == {"closeness": 10, "fairness": 0.5}
    assert [j.timeout for j in expanded[-2:]] == [60, 5]
    # Files other than meshes go to gproj as paths (its readers name the file and line).
    assert batch.load_inputs(expanded[0])["fixed"] == tmp_path / "fixed.txt"
    assert batch.load_inputs(expanded[4])["fixed"] == [0, 3]
    listed = subprocess.run([sys.executable, "-m", "gproj.batch", str(jobs), "--check"],
                            capture_output=True, text=True, env=environment())
    assert listed.returncode == 0 and listed.stdout.count("\n") == 7
    assert "6 jobs, the job file is fine" in listed.stdout


def test_ctrl_c_cancels_the_rest_and_writes_the_summary(tmp_path, scheduler):
    """SIGINT once a first job is done and two long ones run: exit 130, the summary has the
    finished job and the others as interrupted, and the workers are soon idle (the running
    jobs stop at their next iteration)."""
    quad_meshes(tmp_path)
    jobs = write_jobs(tmp_path, [
        {"name": "quick", "problem": "planarize", "inputs": {"mesh": "meshes/a.obj"}},
        long_job(tmp_path, name="long", timeout=60, sweep={"closeness": [1, 2, 3]})])
    out = tmp_path / "out"
    process = subprocess.Popen(command(jobs, out, "--scheduler", scheduler),
                               stdout=subprocess.PIPE, stderr=subprocess.PIPE, text=True,
                               env=environment())
    for line in process.stderr:
        if "1/4 done" in line:
            break
    time.sleep(1.0)
    process.send_signal(signal.SIGINT)
    stdout, stderr = process.communicate(timeout=30)
    assert process.returncode == 130, stderr
    rows = read_summary(out)[1]
    assert [r["outcome"] for r in rows] == ["converged"] + ["interrupted"] * 3
    assert "interrupted" in stdout and str(out) in stdout
    with distributed.Client(scheduler) as client:
        deadline = time.monotonic() + 15
        while any(client.run(executing).values()):
            assert time.monotonic() < deadline, "a worker still runs an interrupted job"
            time.sleep(0.1)


def executing(dask_worker):
    return dask_worker.state.executing_count


def test_weld_in_a_job_merges_an_unwelded_mesh(tmp_path):
    """An unwelded export (each quad with its own corners) fails its job unless the job says
    "weld": true; then it runs on the welded mesh."""
    V, F = gproj.grid(nu=6, nv=6, noise=0.05)
    gproj.write_mesh(tmp_path / "unwelded.obj", V[F.ravel()], np.arange(F.size).reshape(F.shape))
    entries = [{"name": "plain", "problem": "planarize", "inputs": {"mesh": "unwelded.obj"}},
               {"name": "welded", "problem": "planarize", "inputs": {"mesh": "unwelded.obj"},
                "weld": True, "options": {"tolerance": 1e-8}}]
    plain, welded = batch.load_jobs(str(write_jobs(tmp_path, entries)))
    assert (plain.weld, welded.weld) == (False, True) and welded.description()["weld"]
    failed = batch.run_job(plain)
    assert "coincides with vertex" in failed.error and "weld" in failed.error
    done = batch.run_job(welded)
    assert done.error is None, done.error
    assert done.report["converged"] and done.report["welded"]["mesh"] == {
        "input_vertices": F.size, "vertices": len(V)}
    assert len(done.main[0]) == len(V)
