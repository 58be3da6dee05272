"""combescure, invert, canal and cyclidic (gproj::circular) against the command line."""
import numpy as np
import pytest

import gproj
from conftest import ROOT, assert_close, assert_reports_equal


DATA = ROOT / "examples" / "data"


def test_combescure_equals_the_command_line(cli):
    V, F = gproj.read_mesh(str(DATA / "revolution_13x17.obj"))
    for solver in ("direct", "gp"):
        cli.run("combescure", DATA / "revolution_13x17.obj", "-o", cli.path("c.obj"),
                "--column-scale", 0.8, "--solver", solver, "--report", cli.path("r.json"))
        result = gproj.combescure(V, F, column_scale=0.8, solver=solver)
        assert_reports_equal(result.report, cli.read_report("r.json"))
        assert_close(result.vertices, gproj.read_mesh(cli.path("c.obj"))[0])


def test_combescure_refuses_a_non_grid():
    V, F = gproj.grid(nu=4, nv=4)
    with pytest.raises(ValueError):
        gproj.combescure(V, F[::-1].copy())


def test_invert_equals_the_command_line(cli):
    V, F = gproj.read_mesh(str(DATA / "revolution_13x17.obj"))
    cli.run("invert", DATA / "revolution_13x17.obj", "-o", cli.path("i.obj"), "--centre",
            "0.5,0.2,3", "--ratio", 2, "--report", cli.path("r.json"))
    result = gproj.invert(V, F, centre=[0.5, 0.2, 3], ratio=2.0)
    assert_reports_equal(result.report, cli.read_report("r.json"))
    assert_close(result.vertices, gproj.read_mesh(cli.path("i.obj"))[0])
    with pytest.raises(ValueError, match="centre"):
        gproj.invert(V, F, centre=[0, 0])


def test_invert_m_revolution_equals_the_command_line(cli):
    V, F = gproj.read_mesh(str(DATA / "revolution_13x17.obj"))
    quad = [[2, 0, 1], [0, 2, 1], [-2, 0, 1], [0, -2, 1]]
    cli.run("invert", DATA / "revolution_13x17.obj", "-o", cli.path("i.obj"), "--m-revolution",
            ",".join(str(x) for p in quad for x in p), "--t", 0.5, "--root", 1, "--report",
            cli.path("r.json"))
    result = gproj.invert(V, F, m_revolution=np.array(quad, float), t=0.5, root=1)
    assert_reports_equal(result.report, cli.read_report("r.json"))
    assert_close(result.vertices, gproj.read_mesh(cli.path("i.obj"))[0])
    m = result.report.m_revolution
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
    result = gproj.canal(curve, first_point=[-0.5, 0.5, 2], length=2.0, smooth=True,
                         callback=records.append)
    V, F = result.output  # a Mesh
    assert V is result.vertices and F is result.faces
    assert_reports_equal(result.report, cli.read_report("r.json"))
    Vc, Fc = gproj.read_mesh(cli.path("c.obj"))
    assert_close(V, Vc)
    assert (F == Fc).all()
    assert len(records) == len(result.report.history)
    with pytest.raises(ValueError, match="lengths"):
        gproj.canal(curve, first_point=[-0.5, 0.5, 2])
    with pytest.raises(ValueError, match="^first_point x,y,z is needed"):
        gproj.canal(curve, length=2.0)


def test_closed_canal_equals_the_command_line(cli):
    source = DATA / "canal_closed_curve.txt"
    curve = np.loadtxt(source)
    cli.run("canal", source, "--closed", "--first-point", "3.2,-0.2,0.5", "--length", 0.5,
            "--normal", "1,0,0", "-o", cli.path("c.obj"), "--report", cli.path("r.json"))
    result = gproj.canal(curve, first_point=[3.2, -0.2, 0.5], length=0.5, normal=[1, 0, 0],
                         closed=True, outputs=["strip"])
    V, F = result.output
    assert result.strip.faces.shape == (21, 4)
    assert_reports_equal(result.report, cli.read_report("r.json"))
    report = result.report
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
    result = gproj.cyclidic(V, F, segments=3)
    Vs, Fs = result.output
    assert_reports_equal(result.report, cli.read_report("r.json"))
    report = result.report
    Vc, Fc = gproj.read_mesh(cli.path("s.obj"))
    assert_close(Vs, Vc)
    assert (Fs == Fc).all()
    assert report["final"]["max_tangent_angle_deg"] < 1e-5
    V_noisy, F_noisy = gproj.read_mesh(str(DATA / "noisy_grid_21x21.obj"))
    with pytest.raises(ValueError, match="not circular"):
        gproj.cyclidic(V_noisy, F_noisy)
    with pytest.raises(ValueError, match="normal"):
        gproj.cyclidic(V, F, normal=[0, 0, 0])


def test_cyclidic_calls_the_callback_and_stops_on_false():
    V, F = gproj.read_mesh(str(DATA / "revolution_13x17.obj"))
    records = []
    report = gproj.cyclidic(V, F, segments=2,
                            callback=lambda record: records.append(record) or True).report
    assert len(records) > 1 and len(records) == len(report["history"])
    assert records[-1]["smoothness_energy"] <= records[0]["smoothness_energy"]
    assert report["status"] == "CONVERGENCE"
    stopped = gproj.cyclidic(V, F, segments=2, callback=lambda record: False).report
    assert stopped["status"] == "USER_ABORT" and not stopped["converged"]
    assert len(stopped["history"]) == 1


def test_canal_from_two_curves_equals_the_command_line(cli):
    first, second = DATA / "canal_curve_fine.txt", DATA / "canal_second_curve.txt"
    cli.run("canal", first, "--second-curve", second, "--normal", "0,0,1", "--segments", 6,
            "-o", cli.path("c.obj"), "--report", cli.path("r.json"))
    result = gproj.canal(np.loadtxt(first), second_curve=np.loadtxt(second), normal=[0, 0, 1],
                         segments=6)
    assert_close(result.vertices, gproj.read_mesh(cli.path("c.obj"))[0])
    expected = cli.read_report("r.json")
    assert expected["second_curve"] == str(second)
    assert_reports_equal(result.report, expected)
    assert len(result.report["spheres"]) == 49
    with pytest.raises(ValueError, match="^second_curve needs normal"):
        gproj.canal(np.loadtxt(first), second_curve=np.loadtxt(second))
