"""The Python package as a user gets it: built by pip from the source tree into a fresh venv,
its version, its files, its stubs (current, and checked by mypy), its signatures."""

import inspect
import os
import pathlib
import shutil
import subprocess
import sys
import zipfile

import pytest

import gproj
from gproj import _stubgen

SOURCE = pathlib.Path(__file__).resolve().parents[2]
PACKAGE = SOURCE / "python" / "gproj"
BUILD_DIR = os.environ.get("GPROJ_TEST_BUILD_DIR")


def command_line_version():
    out = subprocess.run([os.environ["GPROJ_BINARY"], "--version"], check=True,
                         capture_output=True, text=True).stdout
    return out.split()[-1]


def test_version_is_the_command_lines():
    """gproj.__version__ is what `gproj --version` prints."""
    assert gproj.__version__ == command_line_version()


def test_every_problem_has_a_signature_options_and_result_class():
    """inspect.signature works on every function and lists the schema's options with their
    defaults; every problem has its options and result class."""
    for spec in gproj.schema()["problems"]:
        function = getattr(gproj, spec["name"])
        parameters = inspect.signature(function).parameters
        for option in spec["options"]:
            assert option["name"] in parameters, (spec["name"], option["name"])
            if not option.get("required"):
                assert parameters[option["name"]].default == option["default"]
        assert spec["summary"] in function.__doc__
        if spec["generator"]:
            continue
        assert "callback" in parameters and "outputs" in parameters and "options" in parameters
        name = _stubgen.camel(spec["name"])
        options_class = getattr(gproj, name + "Options")
        required = [o["name"] for o in spec["options"] if o.get("required")]
        if required:  # a required option has no default: leaving it out is refused, naming it
            with pytest.raises(TypeError, match=required[0]):
                options_class()
            continue
        options = options_class()
        for option in spec["options"]:
            if not option.get("required"):
                assert getattr(options, option["name"]) == option["default"]
        assert issubclass(getattr(gproj, name + "Result"), gproj.Result)


def test_shipped_stubs_are_current():
    """python/gproj/__init__.pyi is what `python3 -m gproj._stubgen` writes from the registry
    (regenerate it after changing a problem's options), and _core.pyi what mypy's stubgen
    writes from the extension."""
    assert (PACKAGE / "__init__.pyi").read_text(encoding="utf-8") == _stubgen.stubs(), (
        "run: PYTHONPATH=build/python python3 -m gproj._stubgen python/gproj/__init__.pyi")


def test_core_stubs_are_current(tmp_path):
    """python/gproj/_core.pyi is what mypy's stubgen writes from the built extension, completed
    by `python3 -m gproj._stubgen --core` (keyword-only signatures, which stubgen leaves as
    `(*args, **kwargs)`); none is left without its signature."""
    stubgen = shutil.which("stubgen")
    if stubgen is None:
        pytest.skip("mypy's stubgen is not installed")
    subprocess.run([stubgen, "-p", "gproj._core", "-o", str(tmp_path)], check=True,
                   capture_output=True, cwd=tmp_path,
                   env=dict(os.environ, PYTHONPATH=os.path.dirname(os.path.dirname(
                       gproj.__file__))))
    written = _stubgen.core_stubs((tmp_path / "gproj" / "_core.pyi").read_text(encoding="utf-8"))
    assert "*args" not in written
    assert (PACKAGE / "_core.pyi").read_text(encoding="utf-8") == written, (
        "run: PYTHONPATH=build/python stubgen -p gproj._core -o /tmp/s && PYTHONPATH=build/python "
        "python3 -m gproj._stubgen --core /tmp/s/gproj/_core.pyi python/gproj/_core.pyi")


SAMPLE = '''
import pathlib
import numpy as np
import numpy.typing as npt
import gproj

V, F = gproj.grid(nu=6, nv=6, surface="hypar")
options = gproj.PlanarizeOptions(tolerance=1e-8, min_angle=10.0)
result = gproj.planarize(V, F, options=options, fixed=[0, 1], outputs=["face_values"])
report: gproj.Report = result.report
converged: bool = result.converged
if result.vertices is not None:
    moved: npt.NDArray[np.float64] = result.vertices - V
csv = result.face_values
net: gproj.HnetResult = gproj.hnet(V, F, tolerance=1e-6)
patchwork = net.output
values = gproj.face_values(V, F, circular=True)
mesh = gproj.read_mesh(pathlib.Path("in.obj"))
problem = gproj.Problem()
block = problem.add_block("x", 2, 1)
problem.add_term("t", lambda x: x, 1, [[0], [1]], jac="cs", check_jac=False)
summary = problem.solve("gp", max_iterations=5, monotone=True)
'''


def mypy(tmp_path, script):
    (tmp_path / "sample.py").write_text(script, encoding="utf-8")
    (tmp_path / "mypy.ini").write_text(
        "[mypy]\nstrict = True\ncache_dir = /dev/null\n[mypy-gproj._core]\nignore_errors = True\n",
        encoding="utf-8")
    package_root = os.path.dirname(os.path.dirname(gproj.__file__))
    return subprocess.run(
        [sys.executable, "-m", "mypy", "--config-file", "mypy.ini", "sample.py"],
        capture_output=True, text=True, cwd=tmp_path, env=dict(os.environ, MYPYPATH=package_root))


def test_stubs_type_check_a_script(tmp_path):
    """mypy --strict accepts a script using the package (the package's own code included) and
    rejects the same script with a string tolerance, an unknown option and a misspelt field."""
    pytest.importorskip("mypy")
    good = mypy(tmp_path, SAMPLE)
    assert good.returncode == 0, good.stdout + good.stderr
    bad = mypy(tmp_path, SAMPLE + 'gproj.planarize(V, F, tolerance="tight")\n'
               'gproj.anet(V, F, tolerence=1e-3)\nresult.report_\n'
               'problem.solve(max_iteration=5)\n')
    assert bad.returncode == 1
    assert 'Argument "tolerance" to "planarize" has incompatible type "str"' in bad.stdout
    assert 'Unexpected keyword argument "tolerence" for "anet"' in bad.stdout
    assert '"PlanarizeResult" has no attribute "report_"' in bad.stdout
    assert 'Unexpected keyword argument "max_iteration" for "solve" of "Problem"' in bad.stdout


def copy_source(destination):
    """The source tree without build directories, as a clean clone has it."""
    ignore = shutil.ignore_patterns("build*", ".git", "out", "__pycache__", "*.egg-info")
    shutil.copytree(SOURCE, destination, ignore=ignore)


@pytest.mark.skipif(BUILD_DIR is None, reason="needs GPROJ_TEST_BUILD_DIR (set by ctest)")
def test_pip_install_and_wheel(tmp_path):
    """`pip install --no-build-isolation .` into a fresh venv (offline, the extension from the
    test suite's build) gives a package that imports from another directory with the command
    line's version; `python3 -m build --no-isolation --wheel` gives a wheel with the extension,
    the stubs, py.typed, the licence and numpy as a dependency."""
    source = tmp_path / "src"
    copy_source(source)
    env = dict(os.environ, GPROJ_BUILD_DIR=BUILD_DIR, PIP_NO_INDEX="1")
    env.pop("PYTHONPATH", None)
    venv = tmp_path / "venv"
    subprocess.run([sys.executable, "-m", "venv", "--system-site-packages", str(venv)],
                   check=True)
    python = str(venv / "bin" / "python")
    install = subprocess.run([python, "-m", "pip", "install", "--no-build-isolation", "--no-deps",
                              str(source)], capture_output=True, text=True, env=env)
    assert install.returncode == 0, install.stdout[-3000:] + install.stderr[-3000:]
    elsewhere = tmp_path / "elsewhere"
    elsewhere.mkdir()
    out = subprocess.run([python, "-c", "import gproj; print(gproj.__version__, gproj.__file__)"],
                         capture_output=True, text=True, env=env, cwd=elsewhere, check=True)
    version, location = out.stdout.split()
    assert version == command_line_version()
    assert location.startswith(str(venv))

    wheel = subprocess.run([python, "-m", "build", "--no-isolation", "--wheel", "--outdir",
                            str(tmp_path / "dist"), str(source)],
                           capture_output=True, text=True, env=env)
    assert wheel.returncode == 0, wheel.stdout[-3000:] + wheel.stderr[-3000:]
    [path] = (tmp_path / "dist").glob("gproj-*.whl")
    assert path.name.startswith(f"gproj-{version}-")
    names = zipfile.ZipFile(path).namelist()
    for name in ["gproj/__init__.py", "gproj/__init__.pyi", "gproj/_core.pyi", "gproj/py.typed",
                 "gproj/batch.py"]:
        assert name in names
    assert any(n.startswith("gproj/_core.") and n.endswith(".so") for n in names)
    assert any(n.endswith(".dist-info/LICENSE") for n in names)
    [metadata] = [n for n in names if n.endswith(".dist-info/METADATA")]
    text = zipfile.ZipFile(path).read(metadata).decode()
    assert "Requires-Dist: numpy" in text
    assert "License: GPL-3.0-or-later" in text
