"""weingarten (gproj::weingarten) and B-spline curvatures against the command line."""
import json

import numpy as np
import pytest

import gproj
from conftest import ROOT, assert_reports_equal


DATA = ROOT / "examples" / "data"


def test_weingarten_equals_the_command_line(cli):
    source = DATA / "freeform_10x10.json"
    cli.run("weingarten", source, "-o", cli.path("w.json"), "--max-iterations", 2,
            "--report", cli.path("r.json"))
    with open(source) as f:
        surface = json.load(f)
    surface["control_points"] = np.array(surface["control_points"])  # arrays are accepted
    result = gproj.weingarten(surface, max_iterations=2)
    expected = cli.read_report("r.json")
    assert_reports_equal(result.report, expected)
    with open(cli.path("w.json")) as f:
        assert_reports_equal(result.output, json.load(f))  # a JSON output: a dict
    with pytest.raises(ValueError, match="preset: 'fig99' is not one of fig1, "):
        gproj.weingarten(surface, preset="fig99")
    with pytest.raises(TypeError, match="surface: expected a dict"):
        gproj.weingarten([surface])
    with pytest.raises(ValueError):
        gproj.weingarten({"degree": [3, 3]})


def test_bspline_curvature_equals_the_command_lines_curvature_csv(cli):
    source = DATA / "freeform_10x10.json"
    cli.run("weingarten", source, "-o", cli.path("w.json"), "--max-iterations", 2,
            "--curvature", cli.path("c.csv"), "--samples", 12, 9)
    csv = np.loadtxt(cli.path("c.csv"), delimiter=",", skiprows=1)
    with open(source) as f:
        before = gproj.bspline_curvature(json.load(f), samples=[12, 9])
    with open(cli.path("w.json")) as f:
        after = gproj.bspline_curvature(json.load(f), samples=[12, 9])
    assert before["H"].shape == (12, 9) and before["u"].shape == (12,)
    # CSV rows are the samples a * NV + b, with u, v, H_before, K_before, H_after, K_after.
    for column, values in ((1, np.repeat(before["u"], 9)), (2, np.tile(before["v"], 12)),
                           (3, before["H"].ravel()), (4, before["K"].ravel()),
                           (5, after["H"].ravel()), (6, after["K"].ravel())):
        assert np.allclose(csv[:, column], values, rtol=1e-8, atol=1e-10)
    default = gproj.bspline_curvature({"degree": [3, 3], "knots_u": [0, 0, 0, 0, 1, 1, 1, 1],
                                       "knots_v": [0, 0, 0, 0, 1, 1, 1, 1],
                                       "control_points": [[[i / 3, j / 3, 0.0] for j in range(4)]
                                                          for i in range(4)]})
    assert default["H"].shape == (8, 8)  # 2 per control point and direction
    assert np.abs(default["H"]).max() < 1e-12 and np.abs(default["K"]).max() < 1e-12  # a plane
    with pytest.raises(ValueError, match="samples"):
        gproj.bspline_curvature(json.load(open(source)), samples=[0, 4])
