"""The build step of the Python package: setuptools drives the project's CMake.

`pip install --no-build-isolation .` (and `python3 -m build --no-isolation --wheel`) configure
this CMake project in setuptools' build directory for the running interpreter, build the
extension gproj._core (and the libraries it links) in Release, and put it beside the package's
pure-Python files. Metadata are in pyproject.toml; the version is the CMake project's.

    GPROJ_CMAKE_ARGS   extra arguments of the configure step (e.g. "-DCMAKE_CXX_COMPILER=clang++")
    GPROJ_BUILD_DIR    an existing, configured CMake build directory to build the extension in
                       instead (the extension is copied from it); the test suite uses its own
    CMAKE_BUILD_PARALLEL_LEVEL  parallel jobs (default: the number of processors)
"""

import os
import re
import shlex
import shutil
import subprocess
import sys
from pathlib import Path

from setuptools import Extension, setup
from setuptools.command.build_ext import build_ext

ROOT = Path(__file__).resolve().parent


def version() -> str:
    text = (ROOT / "CMakeLists.txt").read_text(encoding="utf-8")
    match = re.search(r"project\(gproj VERSION ([0-9.]+)", text)
    if not match:
        raise RuntimeError("CMakeLists.txt: no `project(gproj VERSION x.y.z)`")
    return match.group(1)


class CMakeExtension(Extension):
    def __init__(self, name: str):
        super().__init__(name, sources=[])


class CMakeBuild(build_ext):
    def build_extension(self, ext: Extension) -> None:
        if shutil.which("cmake") is None:
            raise RuntimeError("gproj: cmake is not installed (sh .ci/install-deps installs it)")
        target = Path(self.get_ext_fullpath(ext.name)).resolve()
        target.parent.mkdir(parents=True, exist_ok=True)
        jobs = os.environ.get("CMAKE_BUILD_PARALLEL_LEVEL", str(os.cpu_count() or 1))
        existing = os.environ.get("GPROJ_BUILD_DIR")
        if existing:
            build_dir = Path(existing).resolve()
            self.spawn(["cmake", "--build", str(build_dir), "--target", "gproj_python", "-j", jobs])
            cache = (build_dir / "CMakeCache.txt").read_text(encoding="utf-8")
            match = re.search(r"^GPROJ_PYTHON_PACKAGE_DIR:PATH=(.*)$", cache, re.M)
            if not match:
                raise RuntimeError(f"gproj: {build_dir} has no Python package (GPROJ_PYTHON_PACKAGE_DIR)")
            built = Path(match.group(1)) / target.name
            if not built.is_file():
                raise RuntimeError(f"gproj: {built} was not built for this interpreter "
                                   f"({sys.executable})")
            shutil.copy2(built, target)
            return
        build_dir = Path(self.build_temp).resolve() / "cmake"
        configure = [
            "cmake", "-S", str(ROOT), "-B", str(build_dir), "-DCMAKE_BUILD_TYPE=Release",
            f"-DPython3_EXECUTABLE={sys.executable}", "-DGPROJ_BUILD_TESTS=OFF",
            "-DGPROJ_BUILD_BENCH=OFF", "-DGPROJ_PYTHON=ON",
            f"-DGPROJ_PYTHON_PACKAGE_DIR={target.parent}",
        ] + shlex.split(os.environ.get("GPROJ_CMAKE_ARGS", ""))
        print(f"gproj: configuring in {build_dir}", flush=True)
        self.spawn(configure)
        print(f"gproj: building the extension with {jobs} jobs (a few minutes)", flush=True)
        self.spawn(["cmake", "--build", str(build_dir), "--target", "gproj_python", "-j", jobs])
        if not target.is_file():
            raise RuntimeError(f"gproj: the build did not make {target}")


setup(
    version=version(),
    ext_modules=[CMakeExtension("gproj._core")],
    cmdclass={"build_ext": CMakeBuild},
    zip_safe=False,
)
