"""marionette (gproj::marionette): lifts, guides, fits, closed strips against the command line."""
import numpy as np
import pytest

import gproj
from conftest import ROOT, assert_close, assert_reports_equal


DATA = ROOT / "examples" / "data"


def marionette_guides():
    row = [0.4 * np.sin(j / 4.0) for j in range(21)]
    column = [0.3 * (1 - np.cos(i / 5.0)) for i in range(21)]
    return row, column


def test_marionette_lift_equals_the_command_line(cli):
    plan = DATA / "marionette_plan_21x21.obj"
    V, F = gproj.read_mesh(str(plan))
    row, column = marionette_guides()
    for solver in ("direct", "gp"):
        cli.run("marionette", plan, "-o", cli.path("m.obj"), "--row", ",".join(map(repr, row)),
                "--column", ",".join(map(repr, column)), "--solver", solver,
                "--report", cli.path("r.json"))
        result = gproj.marionette(V, F, row=row, column=column, solver=solver)
        assert_reports_equal(result.report, cli.read_report("r.json"))
        assert_close(result.vertices, gproj.read_mesh(cli.path("m.obj"))[0])


def test_marionette_guides_and_fit(cli):
    plan = DATA / "marionette_plan_valence6.obj"
    guides = (DATA / "marionette_valence6_guides.txt").read_text()
    cli.run("marionette", plan, "--guides", DATA / "marionette_valence6_guides.txt",
            "-o", cli.path("m.obj"), "--report", cli.path("r.json"))
    V, F = gproj.read_mesh(str(plan))
    result = gproj.marionette(V, F, guides=guides)
    assert_close(result.vertices, gproj.read_mesh(cli.path("m.obj"))[0])
    assert result.report["converged"] and result.converged
    expected = cli.read_report("r.json")
    expected["guides"] = None
    assert_reports_equal(result.report, expected)
    with pytest.raises(ValueError, match="guides:1: "):
        gproj.marionette(V, F, guides="guide 0 1 nonsense\n")
    Vp, Fp = gproj.read_mesh(str(DATA / "marionette_plan_21x21.obj"))
    target = Vp.copy()
    target[:, 2] = 0.1 * Vp[:, 0] ** 2 - 0.05 * Vp[:, 1] ** 2
    cli.write_mesh("target.obj", target, Fp)
    cli.run("marionette", DATA / "marionette_plan_21x21.obj", "--fit", cli.path("target.obj"),
            "-o", cli.path("f.obj"), "--report", cli.path("r.json"))
    fitted = gproj.marionette(Vp, Fp, fit=(target, Fp))
    expected = cli.read_report("r.json")
    expected["fit"] = None
    assert_reports_equal(fitted.report, expected)
    assert_close(fitted.vertices, gproj.read_mesh(cli.path("f.obj"))[0])


def test_marionette_closed_strip_and_polygon_plan_equal_the_command_line(cli):
    strip = DATA / "marionette_closed_strip.txt"
    cli.run("marionette", "--closed-strip", strip, "-o", cli.path("s.obj"),
            "--report", cli.path("r.json"))
    result = gproj.marionette(closed_strip=strip.read_text())
    V, F = result.output  # no plan: the strip's own connectivity comes back
    Vc, Fc = gproj.read_mesh(cli.path("s.obj"))
    assert_close(V, Vc)
    assert (F == Fc).all()
    expected = cli.read_report("r.json")
    assert expected["input"] == str(strip)
    assert_reports_equal(result.report, expected)
    # A path is read as the file (the same run as its text); other types are refused.
    assert_close(gproj.marionette(closed_strip=strip).vertices, Vc)
    with pytest.raises(TypeError, match=r"closed_strip: expected a path or the file's text"):
        gproj.marionette(closed_strip=strip.read_bytes())
    with pytest.raises(ValueError, match="^closed_strip:1: "):
        gproj.marionette(closed_strip="1 2 3\n")
    # A plan of polygons lifted from held heights: a dict of vertex heights as --hold's words.
    plan = DATA / "marionette_kagome.obj"
    Vk, Fk = gproj.read_mesh(str(plan))
    cli.run("marionette", plan, "-o", cli.path("k.obj"), "--hold", "0:0.2,40:0.5,100:0.1")
    held = gproj.marionette(Vk, Fk, hold={0: 0.2, 40: 0.5, 100: 0.1})
    assert_close(held.vertices, gproj.read_mesh(cli.path("k.obj"))[0])
    assert held.report.options["hold"] == [[0, 0.2], [40, 0.5], [100, 0.1]]
    assert abs(held.vertices[40, 2] - 0.5) < 1e-9
    with pytest.raises(ValueError, match="hold: vertex 40 is given twice"):
        gproj.marionette(Vk, Fk, hold=[[40, 0.5], [40, 0.1]])
