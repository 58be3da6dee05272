"""Shared fixtures: the gproj command line (GPROJ_BINARY, set by ctest) to compare against."""
import json
import os
import pathlib
import subprocess

import numpy as np
import pytest

import gproj

ROOT = pathlib.Path(__file__).resolve().parents[2]


def gproj_binary():
    return os.environ.get("GPROJ_BINARY", str(ROOT / "build" / "gproj"))


class CommandLine:
    """Runs `gproj <command> ...` in a scratch directory."""

    def __init__(self, directory):
        self.dir = pathlib.Path(directory)

    def path(self, name):
        return str(self.dir / name)

    def run(self, *args, check=True):
        result = subprocess.run([gproj_binary(), *map(str, args)], capture_output=True, text=True)
        if check and result.returncode not in (0, 3):
            raise AssertionError(f"gproj {args[0]} failed ({result.returncode}):\n{result.stderr}")
        return result

    def write_mesh(self, name, V, F):
        gproj.write_mesh(self.path(name), V, F)
        return self.path(name)

    def write_text(self, name, text):
        with open(self.path(name), "w") as f:
            f.write(text)
        return self.path(name)

    def read_report(self, name):
        with open(self.path(name)) as f:
            return json.load(f)


@pytest.fixture
def cli(tmp_path):
    return CommandLine(tmp_path)


# Keys whose values are times: equal in name, not in value.
TIMES = {"seconds", "assembly_seconds", "factorization_seconds", "solve_seconds", "time_s"}
# Keys naming the files of a command-line run (its input, output and other inputs by name);
# None in a Python report.
FILES = {"input", "output"} | {i["name"] for p in gproj.schema()["problems"] for i in p["inputs"]}


def assert_reports_equal(python, command_line, tol=1e-12, path="report"):
    """Same keys everywhere; numbers equal to `tol` (relative), times and file names aside."""
    if isinstance(python, gproj.Report):  # a run's Report compares as its plain dict
        python = python.to_dict()
    if isinstance(command_line, dict):
        assert isinstance(python, dict), path
        assert sorted(python) == sorted(command_line), path
        for key in command_line:
            if key in TIMES:
                continue
            if key in FILES and path == "report" and isinstance(command_line[key], str):
                assert python[key] is None, path + "." + key
                continue
            assert_reports_equal(python[key], command_line[key], tol, path + "." + key)
    elif isinstance(command_line, list):
        assert isinstance(python, list) and len(python) == len(command_line), path
        for i, (a, b) in enumerate(zip(python, command_line)):
            assert_reports_equal(a, b, tol, f"{path}[{i}]")
    elif isinstance(command_line, float) or isinstance(python, float):
        assert python == pytest.approx(command_line, rel=tol, abs=tol), path
    else:
        assert python == command_line, path


def assert_close(a, b, tol=1e-12):
    a, b = np.asarray(a), np.asarray(b)
    assert a.shape == b.shape
    assert np.max(np.abs(a - b), initial=0.0) <= tol


def compare_with_command_line(cli, command, V, F, python_kwargs, args, output="out.obj"):
    """Runs `command` on (V, F) from the command line and from Python; the reports must agree.
    Returns the Python run's Result."""
    source = cli.write_mesh("in.obj", V, F)
    cli.run(command, source, "-o", cli.path(output), "--report", cli.path("r.json"), *args)
    result = getattr(gproj, command)(V, F, **python_kwargs)
    assert isinstance(result, gproj.Result) and isinstance(result.report, gproj.Report)
    assert_reports_equal(result.report, cli.read_report("r.json"))
    return result
