"""Design sweeps: many gproj runs on Dask's distributed engine, described by a job file.

    python3 -m gproj.batch JOBS.json -o DIR [--scheduler ADDRESS | --workers N]
                           [--measures NAME,...] [--timeout SECONDS] [--overwrite] [--check]

JOBS.json lists jobs, or entries that expand to jobs (a "sweep" over options, a glob over input
files); docs/batch.md describes the format. The whole file is checked before anything runs.
Every job runs on a Dask cluster: a LocalCluster of N worker processes (default 2, one thread
each) or the scheduler at ADDRESS. The workers import gproj themselves and read the job's input
files (absolute paths: give the workers the same file system); the results come back to this
process, which writes into DIR a folder per job (the result, its other outputs, report.json,
job.json) and summary.csv / summary.json with one row per job.

Exit codes: 0 every job converged; 1 nothing ran (a bad job file or argument, no cluster);
2 some job failed with an error; 3 some job did not converge or was cancelled (its timeout);
130 interrupted (Ctrl-C: the remaining jobs are cancelled, the summary of the rest written).
"""

from __future__ import annotations

import argparse
import contextlib
import csv
import dataclasses
import difflib
import functools
import glob
import io
import itertools
import json
import logging
import math
import os
import pathlib
import re
import shutil
import signal
import string
import sys
import threading
import time
import traceback
import uuid
import warnings
from typing import Any, Dict, Iterator, List, Mapping, NoReturn, Optional, Sequence, TextIO, Tuple

import numpy as np

import gproj

EXIT_OK = 0
EXIT_NOTHING_RAN = 1
EXIT_FAILED = 2
EXIT_INCOMPLETE = 3
EXIT_INTERRUPTED = 130

ENTRY_KEYS = ("name", "problem", "inputs", "options", "outputs", "sweep", "timeout", "weld")
MESH_EXTENSIONS = (".obj", ".off", ".ply")
GLOB_CHARACTERS = "*?["
SUMMARY_FILES = ("summary.csv", "summary.json")
MAX_JOBS = 100_000  # per entry: a bigger product is more likely a mistake than a plan
STOP_POLL_SECONDS = 0.5  # how often a running job asks the scheduler whether Ctrl-C was pressed
CONNECT_TIMEOUT = "10s"
OUTCOMES = ("converged", "not_converged", "cancelled", "failed", "interrupted")
KIND_EXTENSIONS = {"mesh": ".obj", "json": ".json", "svg": ".svg", "csv": ".csv", "ply": ".ply",
                   "segments": ".obj"}


class JobFileError(ValueError):
    """A bad job file (or argument): one line naming the job, the key and the rule broken."""


class ClusterError(RuntimeError):
    """No cluster to run on: the scheduler is unreachable or its workers lack gproj."""


# --- The registry -----------------------------------------------------------------------------

@functools.lru_cache(maxsize=None)
def problem_specs() -> Dict[str, Dict[str, Any]]:
    """The registry's problems by name (generators included), as `gproj schema` gives them."""
    return {spec["name"]: spec for spec in gproj.schema()["problems"]}


def is_mesh_kind(kind: str) -> bool:
    """Whether an input of this kind is a mesh file."""
    return kind in ("mesh", "quad_mesh")


def options_class(problem: str) -> Any:
    """The problem's options class, e.g. gproj.PlanarizeOptions (checks the values when made)."""
    return getattr(gproj, "".join(p[:1].upper() + p[1:] for p in problem.split("_")) + "Options")


def dask_distributed() -> Any:
    """The module distributed, imported when first needed (checking a job file needs no Dask);
    typed Any, as its API is untyped."""
    import importlib
    return importlib.import_module("distributed")


def _hint(name: str, names: Sequence[str]) -> str:
    close = difflib.get_close_matches(name, list(names), n=2)
    return f"; did you mean {' or '.join(repr(c) for c in close)}?" if close else ""


def jobs_text(count: int) -> str:
    """'1 job', '12 jobs'."""
    return f"{count} job" if count == 1 else f"{count} jobs"


def _one_line(text: str) -> str:
    return " ".join(str(text).split())


# --- The job file -----------------------------------------------------------------------------

@dataclasses.dataclass
class Job:
    """One run of the batch, expanded from an entry of the job file."""

    entry: int  # the index of its entry in the job file
    name: str  # as given, or as filled in from the entry's name and its swept values
    folder: str  # its folder in DIR: the name made filesystem-safe and unique
    problem: str
    inputs: Dict[str, Any]  # by input name: absolute paths, or the data written inline
    options: Dict[str, Any]
    outputs: Tuple[str, ...]
    timeout: Optional[float]  # seconds the run may take; None: no limit
    swept: Dict[str, Any]  # what varies in its entry: swept options, globbed inputs (relative)
    base: str  # the job file's folder: input paths in the summary are relative to it
    weld: bool = False  # merge the input meshes' coincident vertices first (weld=True)

    def description(self) -> Dict[str, Any]:
        """The job as plain data (job.json)."""
        return {"name": self.name, "folder": self.folder, "problem": self.problem,
                "inputs": self.inputs, "options": self.options, "outputs": list(self.outputs),
                "timeout": self.timeout, "swept": self.swept, "weld": self.weld}


def _where(index: int, entry: Any) -> str:
    """How messages name an entry: jobs[2] or jobs[2] "name"."""
    name = entry.get("name") if isinstance(entry, dict) else None
    return f"jobs[{index}] {json.dumps(name)}" if isinstance(name, str) else f"jobs[{index}]"


def _fail(where: str, key: str, rule: str) -> NoReturn:
    raise JobFileError(f"{where}: {key}: {_one_line(rule)}" if key else f"{where}: {rule}")


def _no_duplicates(pairs: List[Tuple[str, Any]]) -> Dict[str, Any]:
    seen: Dict[str, Any] = {}
    for key, value in pairs:
        if key in seen:
            raise JobFileError(f"the key {json.dumps(key)} appears twice in one object")
        seen[key] = value
    return seen


def _no_constant(name: str) -> NoReturn:
    raise JobFileError(f"{name} is not JSON (numbers must be finite)")


def read_job_file(path: str) -> Any:
    """The job file's JSON; duplicate keys and NaN/Infinity refused."""
    try:
        with open(path, encoding="utf-8-sig") as f:
            text = f.read()
    except OSError as e:
        raise JobFileError(f"cannot read {path}: {e.strerror}") from None
    except UnicodeDecodeError:
        raise JobFileError(f"{path}: not a UTF-8 text file") from None
    try:
        return json.loads(text, object_pairs_hook=_no_duplicates, parse_constant=_no_constant)
    except json.JSONDecodeError as e:
        raise JobFileError(f"{path}: not valid JSON: {e.msg} (line {e.lineno}, column "
                           f"{e.colno})") from None
    except JobFileError as e:
        raise JobFileError(f"{path}: {e}") from None


def load_jobs(path: str, default_timeout: Optional[float] = None) -> List[Job]:
    """Every job of the job file at `path`, checked and expanded (sweeps, globs), with unique
    folders. Raises JobFileError naming the file, the job, the key and the rule broken."""
    data = read_job_file(path)
    entries = [data] if isinstance(data, dict) else data
    if not isinstance(entries, list):
        raise JobFileError(f"{path}: expected a list of jobs (or one job object), not "
                           f"{_json_type(data)}")
    if not entries:
        raise JobFileError(f"{path}: the list of jobs is empty")
    base = os.path.dirname(os.path.abspath(path))
    jobs: List[Job] = []
    try:
        for index, entry in enumerate(entries):
            jobs += expand_entry(index, entry, base, default_timeout)
    except JobFileError as e:
        raise JobFileError(f"{path}: {e}") from None
    assign_folders(jobs)
    return jobs


def _json_type(value: Any) -> str:
    if value is None:
        return "null"
    if isinstance(value, bool):
        return "a boolean"
    if isinstance(value, (int, float)):
        return "a number"
    if isinstance(value, str):
        return "a string"
    return "a list" if isinstance(value, list) else "an object"


def expand_entry(index: int, entry: Any, base: str,
                 default_timeout: Optional[float] = None) -> List[Job]:
    """The jobs of one entry: the cartesian product of its globbed inputs and swept options
    (one job when it has neither)."""
    where = _where(index, entry)
    if not isinstance(entry, dict):
        _fail(where, "", f"expected a job object, not {_json_type(entry)}")
    for key in entry:
        if key not in ENTRY_KEYS:
            _fail(where, key, f"not a key of a job{_hint(key, ENTRY_KEYS)} (the keys: "
                  f"{', '.join(ENTRY_KEYS)})")
    spec = _problem(where, entry.get("problem"))
    weld = _weld(where, spec, entry.get("weld", False))
    options = _mapping(where, "options", entry.get("options", {}))
    _check_option_names(where, "options", spec, options)
    _check_options(where, "options", spec, options)
    sweep = _sweep(where, spec, entry.get("sweep"), options)
    inputs, globs = _inputs(where, spec, _mapping(where, "inputs", entry.get("inputs", {})), base)
    outputs = _outputs(where, spec, entry.get("outputs", []))
    timeout = _timeout(where, entry["timeout"]) if "timeout" in entry else default_timeout
    path_inputs = [n for n, v in inputs.items() if isinstance(v, str)] + list(globs)
    template = _name_template(where, entry.get("name"), options, sweep, path_inputs)
    axes: List[List[Tuple[str, str, Any]]] = (
        [[("input", name, p) for p in paths] for name, paths in globs.items()] +
        [[("option", key, v) for v in values] for key, values in sweep.items()])
    if math.prod(len(axis) for axis in axes) > MAX_JOBS:
        _fail(where, "sweep", f"expands to {math.prod(len(a) for a in axes)} jobs, more than "
              f"{MAX_JOBS}: split it into several entries or files")
    jobs = []
    for position, combination in enumerate(itertools.product(*axes)):
        job_inputs, job_options, swept = dict(inputs), dict(options), {}
        for what, key, value in combination:
            if what == "input":
                job_inputs[key] = value
                swept[key] = os.path.relpath(value, base)
            else:
                job_options[key] = value
                swept[key] = value
        if len(sweep) > 1:
            _check_options(where, f"sweep ({_swept_text(swept, sweep)})", spec, job_options)
        name = _job_name(where, template, spec["name"], position, job_inputs, job_options, swept)
        jobs.append(Job(index, name, "", spec["name"], job_inputs, job_options, outputs, timeout,
                        swept, base, weld))
    return jobs


def _swept_text(swept: Mapping[str, Any], keys: Mapping[str, Any]) -> str:
    return ", ".join(f"{k}={_value_text(v)}" for k, v in swept.items() if k in keys)


def _problem(where: str, name: Any) -> Dict[str, Any]:
    specs = problem_specs()
    runnable = sorted(n for n, s in specs.items() if not s["generator"])
    if name is None:
        _fail(where, "problem", f"missing (one of: {', '.join(runnable)})")
    if not isinstance(name, str):
        _fail(where, "problem", f"expected a problem's name, not {_json_type(name)}")
    if name not in specs:
        _fail(where, "problem", f"no problem named {json.dumps(name)}{_hint(name, runnable)} "
              f"(the problems: {', '.join(runnable)})")
    if specs[name]["generator"]:
        _fail(where, "problem", f"{name} is a generator, not a problem to solve (write its mesh "
              f"with gproj.{name}() and gproj.write_mesh, then use it as an input)")
    return specs[name]


def _mapping(where: str, key: str, value: Any) -> Dict[str, Any]:
    if not isinstance(value, dict):
        _fail(where, key, f"expected an object, not {_json_type(value)}")
    return dict(value)


def _check_option_names(where: str, key: str, spec: Mapping[str, Any],
                        options: Mapping[str, Any]) -> None:
    names = [o["name"] for o in spec["options"]]
    for name in options:
        if name not in names:
            _fail(where, f"{key}.{name}", f"{spec['name']} has no option {json.dumps(name)}"
                  f"{_hint(name, names)}")


def _check_options(where: str, key: str, spec: Mapping[str, Any],
                   options: Mapping[str, Any]) -> None:
    """gproj's own check of the values (the options class); the message names the option."""
    try:
        options_class(spec["name"])(**options)
    except (TypeError, ValueError) as e:
        text = _one_line(str(e))
        option, _, rule = text.partition(": ")
        if key == "options" and option in options and rule:
            _fail(where, f"options.{option}", rule)
        _fail(where, key, text)


def _sweep(where: str, spec: Mapping[str, Any], sweep: Any,
           options: Mapping[str, Any]) -> Dict[str, List[Any]]:
    """The swept options, each a non-empty list of values, each value checked alone."""
    if sweep is None:
        return {}
    sweep = _mapping(where, "sweep", sweep)
    if not sweep:
        _fail(where, "sweep", "empty: name at least one option and its list of values")
    _check_option_names(where, "sweep", spec, sweep)
    for key, values in sweep.items():
        if key in options:
            _fail(where, f"sweep.{key}", "also given in options: give it in one place")
        if not isinstance(values, list) or not values:
            _fail(where, f"sweep.{key}", f"expected a non-empty list of values, not "
                  f"{_json_type(values) if values != [] else 'an empty list'}")
        for i, value in enumerate(values):
            _check_options(where, f"sweep.{key}[{i}]", spec, {**options, key: value})
    return dict(sweep)


def _inputs(where: str, spec: Mapping[str, Any], inputs: Mapping[str, Any],
            base: str) -> Tuple[Dict[str, Any], Dict[str, List[str]]]:
    """(the fixed inputs, the globbed inputs' matches), paths made absolute."""
    known = {i["name"]: i for i in spec["inputs"]}
    for name in inputs:
        if name not in known:
            _fail(where, f"inputs.{name}", f"{spec['name']} has no input {json.dumps(name)}"
                  f"{_hint(name, list(known))} (its inputs: {', '.join(known) or 'none'})")
    fixed: Dict[str, Any] = {}
    globs: Dict[str, List[str]] = {}
    for name, item in known.items():
        if name not in inputs or inputs[name] is None:
            if item["required"]:
                _fail(where, f"inputs.{name}", f"missing: {spec['name']} needs its "
                      f"{item['kind']} input (a {_input_form(item['kind'])})")
            continue
        value = _input(where, item, inputs[name], base)
        if isinstance(value, list) and isinstance(inputs[name], str):
            globs[name] = value
        else:
            fixed[name] = value
    return fixed, globs


def _input_form(kind: str) -> str:
    return {"mesh": "mesh file path (.obj, .off, .ply)",
            "quad_mesh": "quad mesh file path (.obj, .off, .ply)",
            "vertex_ids": "list of vertex ids or the path of a file of ids",
            "curve": "list of [x, y, z] points or the path of a curve file",
            "bspline": "B-spline object or the path of its JSON file",
            "text": "text file path",
            "json": "JSON object or the path of its .json file"}.get(kind, "path")


def _input(where: str, item: Mapping[str, Any], value: Any, base: str) -> Any:
    """An input's value: an absolute path, a list of paths (a glob), or inline data."""
    key, kind = f"inputs.{item['name']}", item["kind"]
    if isinstance(value, str):
        paths = _paths(where, key, value, base)
        if is_mesh_kind(kind):
            for path in paths:
                if not path.lower().endswith(MESH_EXTENSIONS):
                    _fail(where, key, f"{os.path.relpath(path, base)} is not a mesh file "
                          f"(.obj, .off or .ply)")
        return paths if any(c in value for c in GLOB_CHARACTERS) else paths[0]
    if kind == "vertex_ids" and isinstance(value, list):
        if not all(isinstance(v, int) and not isinstance(v, bool) and v >= 0 for v in value):
            _fail(where, key, "expected vertex ids: non-negative integers")
        return value
    if kind == "curve" and isinstance(value, list):
        if not value or not all(_is_point(p) for p in value):
            _fail(where, key, "expected a list of points [x, y, z]")
        return value
    if kind in ("bspline", "json") and isinstance(value, dict):
        return value
    _fail(where, key, f"expected a {_input_form(kind)}, not {_json_type(value)}")


def _is_point(value: Any) -> bool:
    return isinstance(value, list) and len(value) == 3 and all(
        isinstance(x, (int, float)) and not isinstance(x, bool) for x in value)


def _paths(where: str, key: str, value: str, base: str) -> List[str]:
    """The absolute path a string names, or the sorted files its glob pattern matches."""
    if not value.strip():
        _fail(where, key, "an empty path")
    pattern = os.path.expanduser(value)
    if not any(c in value for c in GLOB_CHARACTERS):
        return [os.path.normpath(os.path.join(base, pattern))]
    matches = sorted(os.path.normpath(os.path.join(base, m))
                     for m in glob.glob(pattern, root_dir=base, recursive=True))
    files = [m for m in matches if os.path.isfile(m)]
    if not files:
        _fail(where, key, f"the pattern {json.dumps(value)} matches no file (relative to "
              f"{base})")
    return files


def _outputs(where: str, spec: Mapping[str, Any], outputs: Any) -> Tuple[str, ...]:
    optional = [o["name"] for o in spec["outputs"][1:]]
    if not isinstance(outputs, list):
        _fail(where, "outputs", f"expected a list of output names, not {_json_type(outputs)}")
    for i, name in enumerate(outputs):
        if name == spec["outputs"][0]["name"]:
            _fail(where, f"outputs[{i}]", f"{json.dumps(name)} is the main output, always "
                  f"written")
        if not isinstance(name, str) or name not in optional:
            _fail(where, f"outputs[{i}]", f"{spec['name']} has no optional output "
                  f"{json.dumps(name)}{_hint(str(name), optional)} (its outputs: "
                  f"{', '.join(optional) or 'none'})")
        if name in outputs[:i]:
            _fail(where, f"outputs[{i}]", f"{json.dumps(name)} is listed twice")
    return tuple(outputs)


def _weld(where: str, spec: Mapping[str, Any], value: Any) -> bool:
    if not isinstance(value, bool):
        _fail(where, "weld", f"expected true or false, not {json.dumps(value)}")
    if value and not any(i["kind"] in ("mesh", "quad_mesh") for i in spec["inputs"]):
        _fail(where, "weld", f"{spec['name']} has no mesh input to weld")
    return value


def _timeout(where: str, value: Any) -> Optional[float]:
    if value is None:
        return None
    if isinstance(value, bool) or not isinstance(value, (int, float)) or not value > 0:
        _fail(where, "timeout", f"expected seconds, a number > 0, not {json.dumps(value)}")
    return float(value)


# --- Job names and folders --------------------------------------------------------------------

def _value_text(value: Any) -> str:
    """A value as names show it: 10, 1e-06, true, 0.1,1 (a list), the string itself."""
    if isinstance(value, str):
        return value
    if isinstance(value, list):
        return ",".join(_value_text(v) for v in value)
    return json.dumps(value)


def _name_template(where: str, name: Any, options: Mapping[str, Any], sweep: Mapping[str, Any],
                   path_inputs: Sequence[str]) -> Optional[str]:
    """The entry's name; its {fields} must name the problem, the index, an option it gives or
    sweeps or an input given as a path (its file's stem)."""
    if name is None:
        return None
    if not isinstance(name, str) or not name.strip():
        _fail(where, "name", f"expected a non-empty string, not {json.dumps(name)}")
    fields = ["problem", "index"] + list(options) + list(sweep) + list(path_inputs)
    try:
        parsed = list(string.Formatter().parse(name))
    except ValueError as e:
        _fail(where, "name", f"not a valid name template: {e}")
    for _, field, _, _ in parsed:
        if field is not None:
            head = re.split(r"[.\[]", field, maxsplit=1)[0]
            if head not in fields:
                _fail(where, "name", f"{{{field}}} names no field (the fields: "
                      f"{', '.join(fields)})")
    return name


def _job_name(where: str, template: Optional[str], problem: str, position: int,
              inputs: Mapping[str, Any], options: Mapping[str, Any],
              swept: Mapping[str, Any]) -> str:
    """The job's name: its template filled in, or the entry's name (default: the problem) with
    the swept values appended (input file stems, key=value)."""
    parts = [pathlib.Path(inputs[k]).stem if k in inputs and k not in options else
             f"{k}={_value_text(v)}" for k, v in swept.items()]
    if template is None:
        return "_".join([problem] + parts)
    if not any(field is not None for _, field, _, _ in string.Formatter().parse(template)):
        return "_".join([template] + parts)
    fields: Dict[str, Any] = {"problem": problem, "index": position}
    fields.update({k: pathlib.Path(v).stem for k, v in inputs.items() if isinstance(v, str)})
    fields.update(options)
    try:
        return template.format(**fields)
    except (KeyError, IndexError, ValueError, TypeError, AttributeError) as e:
        _fail(where, "name", f"cannot fill in {json.dumps(template)}: {type(e).__name__}: {e}")


def safe_folder(name: str) -> str:
    """A name as a folder name: letters, digits and . _ - = + , only; at most 120 characters."""
    text = re.sub(r"[^A-Za-z0-9._=+,-]+", "_", name).strip("._- ")[:120].rstrip("._- ")
    return text or "job"


def assign_folders(jobs: Sequence[Job]) -> None:
    """Gives every job a filesystem-safe folder, unique even on case-insensitive systems."""
    taken = {name.lower() for name in SUMMARY_FILES}
    for job in jobs:
        folder, count = safe_folder(job.name), 1
        while folder.lower() in taken:
            count += 1
            folder = f"{safe_folder(job.name)}-{count}"
        taken.add(folder.lower())
        job.folder = folder


# --- On a worker: one job ---------------------------------------------------------------------

@dataclasses.dataclass
class Outcome:
    """What a worker sends back for one job: the report and outputs, or the error."""

    report: Optional[Dict[str, Any]] = None
    main: Any = None  # the main output: a gproj.Mesh, a dict (JSON) or a str
    outputs: Dict[str, Any] = dataclasses.field(default_factory=dict)
    arrays: Dict[str, Any] = dataclasses.field(default_factory=dict)
    warnings: List[str] = dataclasses.field(default_factory=list)
    error: Optional[str] = None  # one line: "ValueError: mesh: face 0 has 3 vertices; ..."
    details: Optional[str] = None  # the traceback
    stopped: Optional[str] = None  # "timeout" or "interrupted" when the callback stopped it
    seconds: float = 0.0  # the worker's wall time for the job (reading included)


_capture = threading.local()
_capture_lock = threading.Lock()
_capture_installed = [False]


def _install_warning_capture() -> None:
    """Routes GprojWarnings into the running job's list (per thread: a worker may run several
    jobs at once), once per process."""
    with _capture_lock:
        if _capture_installed[0]:
            return
        previous = warnings.showwarning

        def show(message: Any, category: Any, filename: str, lineno: int, file: Any = None,
                 line: Optional[str] = None) -> None:
            sink = getattr(_capture, "messages", None)
            if sink is not None and issubclass(category, gproj.GprojWarning):
                sink.append(_one_line(str(message)))
            else:
                previous(message, category, filename, lineno, file, line)

        warnings.showwarning = show
        warnings.filterwarnings("always", category=gproj.GprojWarning)
        _capture_installed[0] = True


@contextlib.contextmanager
def captured_warnings(messages: List[str]) -> Iterator[None]:
    """Appends the GprojWarnings of the current thread to `messages` while the block runs."""
    _install_warning_capture()
    _capture.messages = messages
    try:
        yield
    finally:
        _capture.messages = None


class Guard:
    """A run's callback: False (stop the run: USER_ABORT) once the job's time is up or the
    batch's stop event (Ctrl-C) is set; the event is polled every STOP_POLL_SECONDS."""

    def __init__(self, timeout: Optional[float], stop: Optional[str]):
        self.deadline = None if timeout is None else time.monotonic() + timeout
        self.stop, self.next_poll = stop, 0.0
        self.event: Any = None
        self.reason: Optional[str] = None

    def __call__(self, record: Mapping[str, Any]) -> bool:
        now = time.monotonic()
        if self.deadline is not None and now >= self.deadline:
            self.reason = "timeout"
            return False
        if self.stop is not None and now >= self.next_poll:
            self.next_poll = now + STOP_POLL_SECONDS
            if self._stop_is_set():
                self.reason = "interrupted"
                return False
        return True

    def _stop_is_set(self) -> bool:
        try:
            if self.event is None:
                distributed = dask_distributed()
                self.event = distributed.Event(self.stop, client=distributed.get_client())
            return bool(self.event.is_set())
        except Exception:  # no scheduler to ask (e.g. run_job called directly): keep going
            self.stop = None
            return False


def run_job(job: Job, stop: Optional[str] = None) -> Outcome:
    """Runs one job (on a worker): reads its inputs, runs its problem, returns the Outcome. Never
    raises: errors come back as the Outcome's error. `stop` names the batch's stop Event."""
    start = time.monotonic()
    outcome = Outcome()
    try:
        with captured_warnings(outcome.warnings):
            arguments = load_inputs(job)
            guard = Guard(job.timeout, stop)
            if job.weld:
                arguments["weld"] = True
            result = gproj.run(job.problem, **arguments, options=job.options,
                               outputs=list(job.outputs), callback=guard)
        outcome.report = result.report.to_dict()
        outcome.main, outcome.outputs = result.output, dict(result.outputs)
        outcome.arrays = dict(result.arrays)
        if result.status == "USER_ABORT":
            outcome.stopped = guard.reason
    except Exception as e:
        outcome.error = f"{type(e).__name__}: {_one_line(str(e))}"
        outcome.details = traceback.format_exc()
    outcome.seconds = time.monotonic() - start
    return outcome


def load_inputs(job: Job) -> Dict[str, Any]:
    """The problem function's keyword arguments for the job's inputs: V and F for the positional
    mesh, (V, F) for other meshes, arrays, dicts and texts read from their files."""
    arguments: Dict[str, Any] = {}
    for item in problem_specs()[job.problem]["inputs"]:
        name = item["name"]
        if name not in job.inputs:
            continue
        try:
            value = load_input(item["kind"], job.inputs[name])
        except ValueError as e:
            raise ValueError(f"inputs.{name}: {e}") from None
        if is_mesh_kind(item["kind"]) and item["positional"]:
            arguments["V"], arguments["F"] = value
        else:
            arguments[name] = value
    return arguments


def load_input(kind: str, value: Any) -> Any:
    """One input's value from its path (or inline data, passed on as it is): meshes are read
    here (the functions take arrays); curves, B-splines, vertex ids and texts go to gproj as
    paths, read by the command line's readers (errors naming the file and line)."""
    if not isinstance(value, str):
        return np.asarray(value, dtype=np.float64) if kind == "curve" else value
    if is_mesh_kind(kind):
        return gproj.read_mesh(value)
    return pathlib.Path(value)


def gproj_version() -> str:
    """The version of gproj where this runs (asked of every worker before the batch)."""
    return gproj.__version__


# --- Writing the results ----------------------------------------------------------------------

def finite(value: Any) -> Any:
    """The value with non-finite floats as None (strict JSON)."""
    if isinstance(value, float):
        return value if math.isfinite(value) else None
    if isinstance(value, dict):
        return {k: finite(v) for k, v in value.items()}
    if isinstance(value, (list, tuple)):
        return [finite(v) for v in value]
    return value


def write_atomically(path: pathlib.Path, text: str) -> None:
    """Writes the text to a temporary name beside `path`, then renames it into place."""
    temporary = path.with_name(f".{path.name}.{os.getpid()}.tmp")
    try:
        with open(temporary, "w", encoding="utf-8", newline="") as f:
            f.write(text)
        os.replace(temporary, path)
    finally:
        with contextlib.suppress(FileNotFoundError):
            os.unlink(temporary)


def write_json(path: pathlib.Path, data: Any) -> None:
    """Strict JSON (non-finite numbers as null), written atomically."""
    write_atomically(path, json.dumps(finite(data), indent=1, allow_nan=False) + "\n")


def output_file(name: str, kind: str, extension: str, main: bool) -> str:
    """The file name of an output: result.obj for a main mesh, output<ext> for another main
    output, NAME<ext> for the others (the schema's extension, else the kind's)."""
    if main and kind == "mesh":
        return "result.obj"
    return ("output" if main else name) + (extension or KIND_EXTENSIONS.get(kind, ".txt"))


def write_value(path: pathlib.Path, value: Any) -> None:
    """A mesh, JSON output, text or array, written atomically."""
    if isinstance(value, gproj.Mesh):
        gproj.write_mesh(path, value.vertices, value.faces)
    elif isinstance(value, dict):
        write_json(path, value)
    elif isinstance(value, np.ndarray):
        buffer = io.StringIO()
        np.savetxt(buffer, value, fmt="%.17g", delimiter=",")
        write_atomically(path, buffer.getvalue())
    else:
        write_atomically(path, str(value))


def write_job(directory: pathlib.Path, job: Job, outcome: Outcome) -> List[str]:
    """The job's folder: job.json, its outputs, error.txt when it failed, report.json. Made
    under a temporary name, then renamed into place: a crash leaves no partial folder. Returns
    the files' names."""
    folder = directory / job.folder
    temporary = directory / f".{job.folder}.{os.getpid()}.tmp"
    if temporary.exists():
        shutil.rmtree(temporary)
    temporary.mkdir(parents=True)
    try:
        files = write_job_files(temporary, job, outcome)
        if folder.exists():
            shutil.rmtree(folder)  # a previous batch's (--overwrite)
        os.replace(temporary, folder)
    finally:
        if temporary.exists():
            shutil.rmtree(temporary, ignore_errors=True)
    return files


def write_job_files(folder: pathlib.Path, job: Job, outcome: Outcome) -> List[str]:
    """The files of write_job into `folder`."""
    write_json(folder / "job.json", job.description())
    files = ["job.json"]
    if outcome.error is not None:
        write_atomically(folder / "error.txt", f"{outcome.error}\n\n{outcome.details or ''}")
        files.append("error.txt")
    if outcome.report is None:
        return files
    spec = problem_specs()[job.problem]
    values = [(spec["outputs"][0], outcome.main)] + [
        (o, outcome.outputs.get(o["name"])) for o in spec["outputs"][1:]]
    for item, value in values:
        if value is not None:
            name = output_file(item["name"], item["kind"], item["extension"],
                               item is spec["outputs"][0])
            write_value(folder / name, value)
            files.append(name)
    for name, array in outcome.arrays.items():
        write_value(folder / f"{name}.csv", np.asarray(array))
        files.append(f"{name}.csv")
    write_json(folder / "report.json", outcome.report)
    return files + ["report.json"]


# --- The summary ------------------------------------------------------------------------------

@dataclasses.dataclass
class Record:
    """A finished (or not) job as the summary shows it."""

    job: Job
    outcome: str  # one of OUTCOMES
    report: Dict[str, Any] = dataclasses.field(default_factory=dict)
    warnings: List[str] = dataclasses.field(default_factory=list)
    error: Optional[str] = None


def make_record(job: Job, outcome: Optional[Outcome]) -> Record:
    """The job's outcome: failed (an error, or status FAILURE: a numerical failure, no result),
    cancelled (its timeout), interrupted, converged, or not_converged (NO_CONVERGENCE,
    STALLED)."""
    if outcome is None:
        return Record(job, "interrupted", error="the batch was interrupted before it finished")
    report = outcome.report or {}
    if outcome.error is None and report.get("status") == "FAILURE":
        outcome.error = _one_line(str(report.get("termination") or "FAILURE"))
    if outcome.error is not None:
        kind = "failed"
    elif outcome.stopped == "timeout":
        kind = "cancelled"
    elif outcome.stopped == "interrupted":
        kind = "interrupted"
    else:
        kind = "converged" if report.get("converged") else "not_converged"
    error = outcome.error
    if kind == "cancelled":
        error = f"cancelled: the timeout of {job.timeout:g} s was up"
    return Record(job, kind, report, list(outcome.warnings), error)


BASE_COLUMNS = ("name", "folder", "problem", "outcome", "status", "converged", "iterations",
                "seconds")
TAIL_COLUMNS = ("warnings", "error")


def _numeric(value: Any) -> bool:
    return isinstance(value, (int, float)) and not isinstance(value, bool)


def summary_columns(records: Sequence[Record],
                    measures: Optional[Sequence[str]]) -> List[Tuple[str, str, str]]:
    """(column, what, key): the base columns, the swept values, the measures, warnings, error.
    A swept key or measure whose name is taken gets the prefix sweep. or final."""
    columns = [(c, "base", c) for c in BASE_COLUMNS]
    taken = set(BASE_COLUMNS) | set(TAIL_COLUMNS)
    for key in dict.fromkeys(k for r in records for k in r.job.swept):
        columns.append((f"sweep.{key}" if key in taken else key, "sweep", key))
        taken.add(columns[-1][0])
    if measures is None:
        measures = list(dict.fromkeys(k for r in records for k, v in
                                      r.report.get("final", {}).items() if _numeric(v)))
    for key in measures:
        columns.append((f"final.{key}" if key in taken else key, "measure", key))
        taken.add(columns[-1][0])
    return columns + [(c, "base", c) for c in TAIL_COLUMNS]


def _swept_value(record: Record, key: str) -> Any:
    """A swept column's value: the job's swept or given value, else the report's option."""
    job = record.job
    if key in job.swept:
        return job.swept[key]
    if key in job.options:
        return job.options[key]
    if isinstance(job.inputs.get(key), str):
        return os.path.relpath(job.inputs[key], job.base)
    return record.report.get("options", {}).get(key)


def summary_row(record: Record, columns: Sequence[Tuple[str, str, str]]) -> Dict[str, Any]:
    """One job's row (plain JSON values; None for what it does not have)."""
    base = {"name": record.job.name, "folder": record.job.folder, "problem": record.job.problem,
            "outcome": record.outcome, "status": record.report.get("status"),
            "converged": record.report.get("converged"),
            "iterations": record.report.get("iterations"),
            "seconds": record.report.get("seconds"), "warnings": record.warnings,
            "error": record.error}
    row: Dict[str, Any] = {}
    for column, what, key in columns:
        if what == "base":
            row[column] = base[key]
        elif what == "sweep":
            row[column] = _swept_value(record, key)
        else:
            value = record.report.get("final", {}).get(key)
            row[column] = value if _numeric(value) else None
    cleaned: Dict[str, Any] = finite(row)
    return cleaned


def _cell(value: Any) -> str:
    """A CSV cell: empty for None, true/false, exact floats (repr), JSON for lists."""
    if value is None:
        return ""
    if isinstance(value, bool):
        return "true" if value else "false"
    if isinstance(value, float):
        return repr(value)
    if isinstance(value, (list, dict)):
        return json.dumps(value)
    return str(value)


def write_summary(directory: pathlib.Path, records: Sequence[Record],
                  measures: Optional[Sequence[str]]) -> None:
    """DIR/summary.csv and DIR/summary.json: one row per job, in the job file's order."""
    columns = summary_columns(records, measures)
    rows = [summary_row(r, columns) for r in records]
    buffer = io.StringIO()
    writer = csv.writer(buffer, lineterminator="\n")
    writer.writerow([c for c, _, _ in columns])
    for row in rows:
        writer.writerow([" | ".join(row[c]) if c == "warnings" else _cell(row[c])
                         for c, _, _ in columns])
    write_atomically(directory / "summary.csv", buffer.getvalue())
    write_json(directory / "summary.json", rows)


def exit_code(records: Sequence[Record], interrupted: bool) -> int:
    """130 interrupted, 2 some job failed, 3 some did not converge or was cancelled, else 0."""
    outcomes = {r.outcome for r in records}
    if interrupted:
        return EXIT_INTERRUPTED
    if "failed" in outcomes:
        return EXIT_FAILED
    return EXIT_INCOMPLETE if outcomes - {"converged"} else EXIT_OK


# --- Running the batch ------------------------------------------------------------------------

class Progress:
    """One line on stderr per finished job: 'gproj batch: 7/12 done, 1 failed: NAME: ...'."""

    def __init__(self, total: int, stream: TextIO):
        self.total, self.stream, self.done = total, stream, 0
        self.counts = dict.fromkeys(OUTCOMES, 0)

    def say(self, text: str) -> None:
        self.stream.write(f"gproj batch: {text}\n")
        self.stream.flush()

    def finished(self, record: Record) -> None:
        self.done += 1
        self.counts[record.outcome] += 1
        counts = "".join(f", {n} {o.replace('_', ' ')}" for o, n in self.counts.items()
                         if n and o != "converged")
        self.say(f"{self.done}/{self.total} done{counts}: {record.job.name}: {describe(record)}")


def describe(record: Record) -> str:
    """'CONVERGENCE, 6 iterations, 0.01 s', or the error."""
    if record.outcome == "failed":
        return f"FAILED: {record.error}"
    report = record.report
    iterations = report.get("iterations")
    text = (f"{report.get('status')}, {iterations} iteration{'' if iterations == 1 else 's'}, "
            f"{report.get('seconds') or 0.0:.3g} s")
    if record.outcome == "cancelled" and record.job.timeout is not None:
        return f"CANCELLED (its timeout of {record.job.timeout:g} s): {text}"
    return text


def collect(future: Any) -> Outcome:
    """A finished future's Outcome; a task lost on the cluster (its worker died, ...) comes
    back as an error."""
    try:
        value: Any = future.result()
    except Exception as e:
        return Outcome(error=f"{type(e).__name__}: {_one_line(str(e))}",
                       details=traceback.format_exc())
    if isinstance(value, Outcome):
        return value
    return Outcome(error=f"the worker sent back {type(value).__name__}, not an Outcome")


def finish(directory: pathlib.Path, job: Job, outcome: Outcome) -> Record:
    """Writes the job's folder and makes its record; a file that cannot be written fails it."""
    try:
        write_job(directory, job, outcome)
    except (OSError, ValueError, TypeError) as e:
        outcome.error = f"cannot write the results: {type(e).__name__}: {_one_line(str(e))}"
        outcome.details = traceback.format_exc()
    return make_record(job, outcome)


def run_batch(client: Any, jobs: Sequence[Job], directory: pathlib.Path,
              progress: Progress) -> Tuple[List[Record], bool]:
    """Submits every job, writes each as it finishes; on Ctrl-C stops the running jobs and
    cancels the rest. Returns (the records in the jobs' order, whether it was interrupted)."""
    distributed = dask_distributed()
    stop = f"gproj-batch-stop-{uuid.uuid4().hex}"
    futures: Dict[Any, int] = {}
    records: Dict[int, Record] = {}
    interrupted = False
    try:
        for i, job in enumerate(jobs):
            futures[client.submit(run_job, job, stop, pure=False,
                                  key=f"gproj-{job.folder}-{uuid.uuid4().hex}")] = i
        for future in distributed.as_completed(list(futures)):
            i = futures[future]
            records[i] = finish(directory, jobs[i], collect(future))
            progress.finished(records[i])
    except KeyboardInterrupt:
        interrupted = True
        progress.say("interrupted: stopping the running jobs, cancelling the rest")
        interrupt(client, stop, futures, records, jobs, directory)
    return [records.get(i) or make_record(job, None) for i, job in enumerate(jobs)], interrupted


def interrupt(client: Any, stop: str, futures: Mapping[Any, int],
              records: Dict[int, Record], jobs: Sequence[Job], directory: pathlib.Path) -> None:
    """Ctrl-C: sets the stop event (running jobs stop at their next iteration), cancels what has
    not finished and writes what has."""
    distributed = dask_distributed()
    with contextlib.suppress(Exception):
        distributed.Event(stop, client=client).set()
    pending = [f for f, i in futures.items() if i not in records and not f.done()]
    with contextlib.suppress(Exception):
        client.cancel(pending)
    for future, i in futures.items():
        if i not in records and future.done() and future.status == "finished":
            records[i] = finish(directory, jobs[i], collect(future))


@contextlib.contextmanager
def open_client(scheduler: Optional[str], workers: int) -> Iterator[Tuple[Any, str]]:
    """A Client of the scheduler at `scheduler`, or of a LocalCluster of `workers` processes
    with one thread each (closed afterwards). Yields (client, where the jobs run)."""
    distributed = dask_distributed()
    logging.getLogger("distributed").setLevel(logging.ERROR)
    if scheduler is not None:
        try:
            client = distributed.Client(scheduler, timeout=CONNECT_TIMEOUT)
        except Exception as e:
            raise ClusterError(f"cannot reach the scheduler at {scheduler}: "
                               f"{_one_line(str(e)) or type(e).__name__}") from None
        try:
            yield client, f"the scheduler at {scheduler}"
        finally:
            client.close()
        return
    cluster = start_local_cluster(distributed, workers)
    try:
        client = distributed.Client(cluster)
        try:
            yield client, f"a local cluster of {workers} worker processes"
        finally:
            client.close()
    finally:
        cluster.close()


def start_local_cluster(distributed: Any, workers: int) -> Any:
    """A LocalCluster on this machine. Its worker processes start with SIGINT ignored: Ctrl-C
    in a terminal reaches the whole process group, and this process, not each worker, handles it
    (it stops the running jobs and closes the cluster)."""
    interrupt_handler = None
    if threading.current_thread() is threading.main_thread():
        interrupt_handler = signal.signal(signal.SIGINT, signal.SIG_IGN)
    try:
        return distributed.LocalCluster(n_workers=workers, threads_per_worker=1, processes=True,
                                        host="127.0.0.1", dashboard_address="127.0.0.1:0",
                                        silence_logs=logging.ERROR)
    except Exception as e:
        raise ClusterError(f"cannot start a local cluster: {type(e).__name__}: "
                           f"{_one_line(str(e))}") from None
    finally:
        if interrupt_handler is not None:
            signal.signal(signal.SIGINT, interrupt_handler)


def check_workers(client: Any, progress: Progress) -> None:
    """Every worker must import gproj (the same version as here, else a warning)."""
    try:
        versions = client.run(gproj_version)
    except Exception as e:
        raise ClusterError(f"the workers cannot run gproj ({type(e).__name__}: "
                           f"{_one_line(str(e))}): start them with gproj importable (its folder "
                           f"on their PYTHONPATH)") from None
    if not versions:
        progress.say("the scheduler has no workers yet: the jobs wait for some")
    for worker, version in sorted(versions.items()):
        if version != gproj.__version__:
            progress.say(f"warning: the worker {worker} has gproj {version}, this process "
                         f"{gproj.__version__}")


# --- The command line -------------------------------------------------------------------------

class _Parser(argparse.ArgumentParser):
    """Usage errors exit 1 (nothing ran), not argparse's 2 (a failed job here)."""

    def error(self, message: str) -> NoReturn:
        self.print_usage(sys.stderr)
        self.exit(EXIT_NOTHING_RAN, f"gproj batch: error: {message}\n")


def _positive(kind: type) -> Any:
    def parse(text: str) -> Any:
        try:
            value = kind(text)
        except ValueError:
            raise argparse.ArgumentTypeError(f"expected a number > 0, not {text!r}") from None
        if not value > 0 or not math.isfinite(value):
            raise argparse.ArgumentTypeError(f"expected a number > 0, not {text!r}")
        return value
    return parse


def parser() -> argparse.ArgumentParser:
    """The command line's arguments."""
    p = _Parser(prog="python3 -m gproj.batch",
                description="Run a job file's gproj jobs (sweeps, globs) on a Dask cluster and "
                            "write every result and a summary into a folder (docs/batch.md).")
    p.add_argument("jobs", metavar="JOBS.json", help="the job file (paths in it are relative to "
                   "its folder)")
    p.add_argument("-o", "--output", metavar="DIR",
                   help="the results: a folder per job, summary.csv and summary.json (required "
                        "unless --check)")
    where = p.add_mutually_exclusive_group()
    where.add_argument("--scheduler", metavar="ADDRESS",
                       help="an existing Dask scheduler (tcp://host:port) instead of a local "
                            "cluster")
    where.add_argument("--workers", metavar="N", type=_positive(int), default=2,
                       help="worker processes of the local cluster (one thread each; default 2)")
    p.add_argument("--measures", metavar="NAME,...",
                   help="the report.final keys in the summary (default: every numeric one)")
    p.add_argument("--timeout", metavar="SECONDS", type=_positive(float),
                   help="the timeout of the jobs that give none")
    p.add_argument("--overwrite", action="store_true",
                   help="DIR may hold a previous batch: its job folders of the same names and "
                        "its summary are replaced")
    p.add_argument("--check", action="store_true",
                   help="check the job file and list its jobs, run nothing")
    return p


def parse_measures(text: Optional[str]) -> Optional[List[str]]:
    """--measures a,b -> ['a', 'b'] (None: every numeric key of report.final)."""
    if text is None:
        return None
    names = [n.strip() for n in text.split(",")]
    for name in names:
        if not re.fullmatch(r"[A-Za-z_][A-Za-z0-9_]*", name):
            raise JobFileError(f"--measures: {name!r} is not a measure's name (e.g. "
                               f"max_planarity,max_displacement)")
    return list(dict.fromkeys(names))


def check_output_directory(path: str, overwrite: bool) -> pathlib.Path:
    """DIR must be a folder that is empty or missing (or, with --overwrite, a previous batch's);
    nothing is created here."""
    directory = pathlib.Path(path)
    if directory.exists() and not directory.is_dir():
        raise JobFileError(f"-o {path}: not a folder")
    if directory.is_dir() and any(directory.iterdir()) and not overwrite:
        raise JobFileError(f"-o {path}: the folder is not empty (a previous batch?): choose "
                           f"another or pass --overwrite")
    return directory


def list_jobs(jobs: Sequence[Job], stream: TextIO) -> None:
    """--check: one line per job (folder, problem, swept values)."""
    for job in jobs:
        swept = ", ".join(f"{k}={_value_text(v)}" for k, v in job.swept.items())
        stream.write(f"{job.folder}\t{job.problem}\t{swept}\n")
    stream.write(f"gproj batch: {jobs_text(len(jobs))}, the job file is fine\n")


def main(argv: Optional[Sequence[str]] = None) -> int:
    """The command line; returns the exit code."""
    options = parser()
    args = options.parse_args(argv)
    if args.output is None and not args.check:
        options.error("the following arguments are required: -o/--output")
    progress = Progress(0, sys.stderr)
    try:
        jobs = load_jobs(args.jobs, args.timeout)
        measures = parse_measures(args.measures)
        if args.check:
            list_jobs(jobs, sys.stdout)
            return EXIT_OK
        directory = check_output_directory(args.output, args.overwrite)
    except JobFileError as e:
        progress.say(f"error: {e}")
        return EXIT_NOTHING_RAN
    progress.total = len(jobs)
    try:
        with open_client(args.scheduler, args.workers) as (client, where):
            check_workers(client, progress)
            directory.mkdir(parents=True, exist_ok=True)
            progress.say(f"{jobs_text(len(jobs))} on {where}")
            records, interrupted = run_batch(client, jobs, directory, progress)
            write_summary(directory, records, measures)
            report_end(records, measures, directory, interrupted, progress)
    except ClusterError as e:
        progress.say(f"error: {e}")
        return EXIT_NOTHING_RAN
    except KeyboardInterrupt:
        progress.say("interrupted")
        return EXIT_INTERRUPTED
    return exit_code(records, interrupted)


def report_end(records: Sequence[Record], measures: Optional[Sequence[str]],
               directory: pathlib.Path, interrupted: bool, progress: Progress) -> None:
    """The closing lines: the count of each outcome and where the results are (stdout)."""
    for name in measures or []:
        if not any(name in r.report.get("final", {}) for r in records):
            progress.say(f"warning: --measures {name}: no job's report.final has it")
    counts = {o: sum(r.outcome == o for r in records) for o in OUTCOMES}
    text = ", ".join(f"{n} {o.replace('_', ' ')}" for o, n in counts.items() if n)
    what = "interrupted" if interrupted else "done"
    print(f"gproj batch: {what}: {jobs_text(len(records))} ({text}); results in {directory} "
          f"(summary.csv, summary.json)", flush=True)


if __name__ == "__main__":
    # Through the module gproj.batch (not __main__), so that the workers unpickle run_job and Job
    # from the module they import.
    from gproj.batch import main as _main
    sys.exit(_main())
