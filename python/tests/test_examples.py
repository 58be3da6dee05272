"""The scripts of examples/python run end to end and draw their pictures."""
import os
import pathlib
import subprocess
import sys

import pytest

pytest.importorskip("matplotlib")  # .ci/install-deps installs python3-matplotlib

EXAMPLES = pathlib.Path(__file__).resolve().parents[2] / "examples" / "python"


def run_example(name, tmp_path, *args):
    picture = tmp_path / (name + ".png")
    done = subprocess.run([sys.executable, str(EXAMPLES / (name + ".py")), *args, "-o",
                           str(picture)], cwd=tmp_path, capture_output=True, text=True,
                          env=dict(os.environ), timeout=300)
    assert done.returncode == 0, done.stdout + done.stderr
    assert picture.read_bytes()[:8] == b"\x89PNG\r\n\x1a\n"
    assert picture.stat().st_size > 10000  # a drawing, not an empty canvas
    return done.stdout


def test_planarize_plot(tmp_path):
    out = run_example("planarize_plot", tmp_path, "--tolerance", "1e-6")
    final = [line for line in out.splitlines() if line.startswith("max planarity")]
    assert len(final) == 1, out
    before, after = (float(w) for w in final[0].split()[2:5:2])
    assert before > 1e-2 and after <= 1e-6


def test_weingarten_diagram(tmp_path):
    out = run_example("weingarten_diagram", tmp_path, "--max-iterations", "3")
    final = [line for line in out.splitlines() if line.startswith("misalignment")]
    assert len(final) == 1, out
    before, after = float(final[0].split()[1]), float(final[0].split()[3].rstrip(","))
    assert after < before
