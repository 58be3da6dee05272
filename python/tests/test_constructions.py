"""combescure, invert, canal, cyclidic, weingarten, marionette against the command line."""
import json

import numpy as np
import pytest

import gproj
from conftest import ROOT, assert_close, assert_reports_equal

DATA = ROOT / "examples" / "data"


def test_combescure_equals_the_command_line(cli):
    V, F = gproj.read_mesh(str(DATA / "revolution_13x17.obj"))
    for method in ("propagation", "gp"):
        cli.run("combescure", DATA / "revolution_13x17.obj", "-o", cli.path("c.obj"),
                "--column-scale", 0.8, "--method", method, "--report", cli.path("r.json"))
        V_out, report = gproj.combescure(V, F, column_scale=0.8, method=method)
        assert_reports_equal(report, cli.read_report("r.json"))
        assert_close(V_out, gproj.read_mesh(cli.path("c.obj"))[0])


def test_combescure_refuses_a_non_grid():
    V, F = gproj.grid(nu=4, nv=4)
    with pytest.raises(ValueError):
        gproj.combescure(V, F[::-1].copy())


def test_invert_equals_the_command_line(cli):
    V, F = gproj.read_mesh(str(DATA / "revolution_13x17.obj"))
    cli.run("invert", DATA / "revolution_13x17.obj", "-o", cli.path("i.obj"), "--centre",
            "0.5,0.2,3", "--ratio", 2, "--report", cli.path("r.json"))
    V_out, report = gproj.invert(V, F, centre=[0.5, 0.2, 3], ratio=2.0)
    assert_reports_equal(report, cli.read_report("r.json"))
    assert_close(V_out, gproj.read_mesh(cli.path("i.obj"))[0])
    with pytest.raises(ValueError, match="centre"):
        gproj.invert(V, F, centre=[0, 0])


def test_invert_m_revolution_equals_the_command_line(cli):
    V, F = gproj.read_mesh(str(DATA / "revolution_13x17.obj"))
    quad = [[2, 0, 1], [0, 2, 1], [-2, 0, 1], [0, -2, 1]]
    cli.run("invert", DATA / "revolution_13x17.obj", "-o", cli.path("i.obj"), "--m-revolution",
            ",".join(str(x) for p in quad for x in p), "--t", 0.5, "--root", 1, "--report",
            cli.path("r.json"))
    V_out, report = gproj.invert(V, F, m_revolution=np.array(quad, float), t=0.5, root=1)
    assert_reports_equal(report, cli.read_report("r.json"))
    assert_close(V_out, gproj.read_mesh(cli.path("i.obj"))[0])
    m = report["m_revolution"]
    assert len(m["centres"]) == 2 and m["root"] == 1
    assert m["image_side_angle"] < 1e-9  # the image quad's sides P1'P2' and P4'P3' are parallel
    assert abs(m["image_diagonals"][0] - m["image_diagonals"][1]) < 1e-9
    with pytest.raises(ValueError, match="not both"):
        gproj.invert(V, F, centre=[0, 0, 5], m_revolution=quad)
    with pytest.raises(ValueError, match=r"give centre \(x, y, z\) or m_revolution"):
        gproj.invert(V, F)
    with pytest.raises(ValueError, match="4 points"):
        gproj.invert(V, F, m_revolution=quad[:3])
    with pytest.raises(ValueError, match="t: -1 is not > 0"):
        gproj.invert(V, F, m_revolution=quad, t=-1.0)
    with pytest.raises(ValueError, match="not coplanar"):
        gproj.invert(V, F, m_revolution=[[2, 0, 1], [0, 2, 1], [-2, 0, 1.3], [0, -2, 1]])


def test_canal_equals_the_command_line(cli):
    curve = np.loadtxt(DATA / "canal_curve.txt")
    cli.run("canal", DATA / "canal_curve.txt", "--first-point", "-0.5,0.5,2", "--length", 2,
            "--smooth", "-o", cli.path("c.obj"), "--report", cli.path("r.json"))
    records = []
    result, report = gproj.canal(curve, first_point=[-0.5, 0.5, 2], length=2.0, smooth=True,
                                 callback=records.append)
    V, F = result["output"]
    assert_reports_equal(report, cli.read_report("r.json"))
    Vc, Fc = gproj.read_mesh(cli.path("c.obj"))
    assert_close(V, Vc)
    assert (F == Fc).all()
    assert len(records) == len(report["history"])
    with pytest.raises(ValueError, match="lengths"):
        gproj.canal(curve, first_point=[-0.5, 0.5, 2])
    with pytest.raises(ValueError, match="^first_point x,y,z is needed"):
        gproj.canal(curve, length=2.0)


def test_closed_canal_equals_the_command_line(cli):
    source = DATA / "canal_closed_curve.txt"
    curve = np.loadtxt(source)
    cli.run("canal", source, "--closed", "--first-point", "3.2,-0.2,0.5", "--length", 0.5,
            "--normal", "1,0,0", "-o", cli.path("c.obj"), "--report", cli.path("r.json"))
    result, report = gproj.canal(curve, first_point=[3.2, -0.2, 0.5], length=0.5,
                                 normal=[1, 0, 0], closed=True, outputs=["strip"])
    V, F = result["output"]
    assert result["strip"][1].shape == (21, 4)
    assert_reports_equal(report, cli.read_report("r.json"))
    Vc, Fc = gproj.read_mesh(cli.path("c.obj"))
    assert_close(V, Vc)
    assert (F == Fc).all()
    assert report["converged"] and report["mesh"]["closed"]
    assert report["final"]["closing_case"] == 2
    with pytest.raises(ValueError, match="smooth"):
        gproj.canal(curve, first_point=[3.2, -0.2, 0.5], length=0.5, closed=True, smooth=True)


def test_cyclidic_equals_the_command_line(cli):
    V, F = gproj.read_mesh(str(DATA / "revolution_13x17.obj"))
    cli.run("cyclidic", DATA / "revolution_13x17.obj", "--segments", 3, "-o", cli.path("s.obj"),
            "--report", cli.path("r.json"))
    result, report = gproj.cyclidic(V, F, segments=3)
    Vs, Fs = result["output"]
    assert_reports_equal(report, cli.read_report("r.json"))
    Vc, Fc = gproj.read_mesh(cli.path("s.obj"))
    assert_close(Vs, Vc)
    assert (Fs == Fc).all()
    assert report["final"]["max_tangent_angle_deg"] < 1e-5
    V_noisy, F_noisy = gproj.read_mesh(str(DATA / "noisy_grid_21x21.obj"))
    with pytest.raises(ValueError, match="not circular"):
        gproj.cyclidic(V_noisy, F_noisy)
    with pytest.raises(ValueError, match="normal"):
        gproj.cyclidic(V, F, normal=[0, 0, 0])


def test_weingarten_equals_the_command_line(cli):
    source = DATA / "freeform_10x10.json"
    cli.run("weingarten", source, "-o", cli.path("w.json"), "--max-iterations", 2,
            "--report", cli.path("r.json"))
    with open(source) as f:
        surface = json.load(f)
    surface["control_points"] = np.array(surface["control_points"])  # arrays are accepted
    result, report = gproj.weingarten(surface, max_iterations=2)
    expected = cli.read_report("r.json")
    assert_reports_equal(report, expected)
    with open(cli.path("w.json")) as f:
        assert_reports_equal(result["output"], json.load(f))
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
        V_out, report = gproj.marionette(V, F, row=row, column=column, solver=solver)
        assert_reports_equal(report, cli.read_report("r.json"))
        assert_close(V_out, gproj.read_mesh(cli.path("m.obj"))[0])


def test_marionette_guides_and_fit(cli):
    plan = DATA / "marionette_plan_valence6.obj"
    guides = (DATA / "marionette_valence6_guides.txt").read_text()
    cli.run("marionette", plan, "--guides", DATA / "marionette_valence6_guides.txt",
            "-o", cli.path("m.obj"), "--report", cli.path("r.json"))
    V, F = gproj.read_mesh(str(plan))
    V_out, report = gproj.marionette(V, F, guides=guides)
    assert_close(V_out, gproj.read_mesh(cli.path("m.obj"))[0])
    assert report["converged"]
    expected = cli.read_report("r.json")
    expected["guides"] = None
    assert_reports_equal(report, expected)
    with pytest.raises(ValueError, match="guides:1: "):
        gproj.marionette(V, F, guides="guide 0 1 nonsense\n")
    Vp, Fp = gproj.read_mesh(str(DATA / "marionette_plan_21x21.obj"))
    target = Vp.copy()
    target[:, 2] = 0.1 * Vp[:, 0] ** 2 - 0.05 * Vp[:, 1] ** 2
    cli.write_mesh("target.obj", target, Fp)
    cli.run("marionette", DATA / "marionette_plan_21x21.obj", "--fit", cli.path("target.obj"),
            "-o", cli.path("f.obj"), "--report", cli.path("r.json"))
    V_fit, report = gproj.marionette(Vp, Fp, fit=(target, Fp))
    expected = cli.read_report("r.json")
    expected["fit"] = None
    assert_reports_equal(report, expected)
    assert_close(V_fit, gproj.read_mesh(cli.path("f.obj"))[0])


def test_marionette_closed_strip_and_polygon_plan_equal_the_command_line(cli):
    strip = DATA / "marionette_closed_strip.txt"
    cli.run("marionette", "--closed-strip", strip, "-o", cli.path("s.obj"),
            "--report", cli.path("r.json"))
    result, report = gproj.marionette(closed_strip=strip.read_text())
    V, F = result["output"]  # no plan: the strip's own connectivity comes back
    Vc, Fc = gproj.read_mesh(cli.path("s.obj"))
    assert_close(V, Vc)
    assert (F == Fc).all()
    expected = cli.read_report("r.json")
    assert expected["input"] == str(strip)
    assert_reports_equal(report, expected)
    with pytest.raises(TypeError, match="closed_strip: expected a str"):
        gproj.marionette(closed_strip=strip)
    with pytest.raises(ValueError, match="^closed_strip:1: "):
        gproj.marionette(closed_strip="1 2 3\n")
    # A plan of polygons lifted from held heights: a dict of vertex heights as --hold's words.
    plan = DATA / "marionette_kagome.obj"
    Vk, Fk = gproj.read_mesh(str(plan))
    cli.run("marionette", plan, "-o", cli.path("k.obj"), "--hold", "0:0.2,40:0.5,100:0.1")
    V_out, report = gproj.marionette(Vk, Fk, hold={0: 0.2, 40: 0.5, 100: 0.1})
    assert_close(V_out, gproj.read_mesh(cli.path("k.obj"))[0])
    assert report["options"]["hold"] == [[0, 0.2], [40, 0.5], [100, 0.1]]
    assert abs(V_out[40, 2] - 0.5) < 1e-9
    with pytest.raises(ValueError, match="hold: vertex 40 is given twice"):
        gproj.marionette(Vk, Fk, hold=[[40, 0.5], [40, 0.1]])


def test_canal_from_two_curves_equals_the_command_line(cli):
    first, second = DATA / "canal_curve_fine.txt", DATA / "canal_second_curve.txt"
    cli.run("canal", first, "--second-curve", second, "--normal", "0,0,1", "--segments", 6,
            "-o", cli.path("c.obj"), "--report", cli.path("r.json"))
    result, report = gproj.canal(np.loadtxt(first), second_curve=np.loadtxt(second),
                                 normal=[0, 0, 1], segments=6)
    assert_close(result["output"][0], gproj.read_mesh(cli.path("c.obj"))[0])
    expected = cli.read_report("r.json")
    assert expected["second_curve"] == str(second)
    assert_reports_equal(report, expected)
    assert len(report["spheres"]) == 49
    with pytest.raises(ValueError, match="^second_curve needs normal"):
        gproj.canal(np.loadtxt(first), second_curve=np.loadtxt(second))


def test_grid_returns_the_mesh_alone_as_the_command_line_writes_it(cli):
    cli.run("grid", "-o", cli.path("g.obj"), "--nu", 5, "--nv", 7, "--surface", "enneper",
            "--noise", 0.02, "--seed", 9)
    V, F = gproj.grid(nu=5, nv=7, surface="enneper", noise=0.02, seed=9)
    Vc, Fc = gproj.read_mesh(cli.path("g.obj"))
    assert V.shape == (35, 3) and F.shape == (24, 4)
    assert_close(V, Vc, tol=1e-9)  # the OBJ text rounds
    assert (F == Fc).all()
    assert gproj.grid.__doc__.startswith("grid(*, surface='paraboloid', nu=21, nv=21")
    with pytest.raises(ValueError, match="^nu: 1 is not in \\[2, 100000\\]"):
        gproj.grid(nu=1)
    with pytest.raises(TypeError, match="did you mean noise"):
        gproj.grid(nosie=0.1)
