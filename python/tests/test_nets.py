"""anet and hnet (gproj::nets) against the command line; hnet's callback stops both stages."""
import json
import pathlib

import numpy as np
import pytest

import gproj
from conftest import assert_close, assert_reports_equal, compare_with_command_line


def test_anet_and_hnet_hold_fixed_vertices_like_the_command_line(cli):
    V, F = gproj.grid(nu=9, nv=9, surface="hyperboloid", noise=0.05)
    result = compare_with_command_line(
        cli, "anet", V, F, {"fixed": [0, 8], "min_angle": 10.0},
        ["--fixed", cli.write_text("fixed.txt", "0 8\n"), "--min-angle", 10])
    assert result.report["converged"]
    assert np.array_equal(result.vertices[[0, 8]], V[[0, 8]])
    assert result.report.final["non_convex_quads"] == 0
    with pytest.raises(ValueError, match="out of range"):
        gproj.hnet(V, F, fixed=[81])


@pytest.mark.parametrize("star_form", ["normals", "quads"])
def test_anet_equals_the_command_line(cli, star_form):
    V, F = gproj.grid(nu=7, nv=7, surface="hypar", noise=0.05)
    result = compare_with_command_line(cli, "anet", V, F, {"star_form": star_form},
                                       ["--star-form", star_form])
    assert_close(result.vertices, gproj.read_mesh(cli.path("out.obj"))[0])


def test_anet_with_a_reference(cli):
    V, F = gproj.grid(nu=6, nv=6, surface="hypar", noise=0.05)
    Vr, Fr = gproj.grid(nu=12, nv=12, surface="hypar", noise=0.0)
    cli.write_mesh("ref.obj", Vr, Fr)
    result = compare_with_command_line(cli, "anet", V, F, {"reference": (Vr, Fr)},
                                       ["--reference", cli.path("ref.obj")])
    assert_close(result.vertices, gproj.read_mesh(cli.path("out.obj"))[0])


def test_anet_refuses_odd_valence():
    V = np.array([[0, 0, 0], [1, 0, 0], [1, 1, 0], [0, 1, 0], [2, 0, 0], [2, 1, 0]], float)
    with pytest.raises(ValueError):
        gproj.anet(V, [[0, 1, 2, 3], [1, 4, 5, 2], [0, 1, 4, 5]])


def test_hnet_equals_the_command_line(cli):
    V, F = gproj.grid(nu=6, nv=6, surface="hypar", noise=0.02)
    result = compare_with_command_line(cli, "hnet", V, F, {}, [], output="h.json")
    hnet = result.output  # a JSON output: a dict, no mesh
    assert isinstance(hnet, dict) and result.vertices is None
    with open(cli.path("h.json")) as f:
        expected = json.load(f)
    assert_reports_equal(hnet, expected)
    assert len(hnet["weights"]) == len(F)


def test_hnet_surface_equals_the_command_lines_surface_mesh(cli):
    V, F = gproj.grid(nu=5, nv=5, surface="hypar", noise=0.02)
    source = cli.write_mesh("in.obj", V, F)
    cli.run("hnet", source, "-o", cli.path("h.json"), "--surface-mesh", cli.path("s.obj"),
            "--samples", 3)
    result = gproj.hnet(V, F, outputs=["surface_mesh"], samples=3)
    Vs, Fs = result.surface_mesh
    assert isinstance(result.surface_mesh, gproj.Mesh)
    Ve, Fe = gproj.read_mesh(cli.path("s.obj"))
    # Welded across the patches: a 4 x 4 grid of patches sampled 3 x 3 has 13 x 13 vertices.
    assert Vs.shape == (13 * 13, 3) and Fs.shape == (len(F) * 18, 3)
    assert len({tuple(p) for p in Vs.tolist()}) == len(Vs)
    assert_close(Vs, Ve)
    assert (Fs == Fe).all()
    unasked = gproj.hnet(V, F, rounds=1)
    assert unasked.surface_mesh is None and "surface_mesh" not in unasked.outputs
    with pytest.raises(ValueError, match=r"samples: -1 is not in \[1, 200\]"):
        gproj.hnet(V, F, samples=-1)
    with pytest.raises(ValueError, match="outputs: hnet has no output 'surface'"):
        gproj.hnet(V, F, outputs=["surface"])


def test_hnet_callback_returning_false_stops_the_whole_run():
    V, F = gproj.grid(nu=7, nv=7, surface="hypar", noise=0.05)
    records = []

    def callback(record):
        records.append(record)
        return len(records) < 2

    result = gproj.hnet(V, F, callback=callback)
    report = result.report
    assert len(records) == 2
    assert report["termination"].startswith("USER_ABORT") and result.status == "USER_ABORT"
    assert not report["converged"] and not report["failed"] and not result.converged
    assert report["rounds"] == [] and result.output is None


def test_darboux_takes_an_hnet_result_its_json_or_its_file_like_the_command_line(cli):
    V, F = gproj.grid(nu=7, nv=7, surface="hyperboloid", noise=0.02)
    hnet = gproj.hnet(V, F).output
    path = cli.path("h.json")
    with open(path, "w") as f:
        json.dump(hnet, f)
    cli.run("darboux", path, "--centre", "0,0,0", "--radius", 1.1, "-o", cli.path("s.json"),
            "--report", cli.path("r.json"))
    for given in (hnet, json.dumps(hnet), path, pathlib.Path(path)):
        result = gproj.darboux(given, centre=[0, 0, 0], radius=1.1)
        assert result.converged and isinstance(result.output, dict)
        report = result.report.to_dict()
        expected = cli.read_report("r.json")
        assert_reports_equal(report["measures"], expected["measures"])
        assert report["inversion"] == expected["inversion"]
    with open(cli.path("s.json")) as f:
        assert_reports_equal(result.output, json.load(f))
    m = result.report["measures"]
    assert m["k_positive_samples"] > 0 and m["k_negative_samples"] > 0
    assert m["max_circle_deviation"] < 1e-10 and m["max_tangent_angle_change_deg"] < 1e-8
    surface = gproj.darboux(hnet, outputs=["surface"], samples=3).surface
    assert isinstance(surface, gproj.Mesh) and surface.vertices.shape == (
        49 + 84 * 2 + 36 * 4, 3)


def test_darboux_refuses_what_cannot_make_a_skin():
    V, F = gproj.grid(nu=5, nv=5, surface="hyperboloid", noise=0.0)
    hnet = gproj.hnet(V, F).output
    with pytest.raises(ValueError, match="centre: .* unbounded"):
        gproj.darboux(hnet, centre=hnet["vertices"][12])
    with pytest.raises(ValueError, match=r"radius: -2 is not > 0"):
        gproj.darboux(hnet, radius=-2)
    broken = dict(hnet, weights=hnet["weights"][1:])
    with pytest.raises(ValueError, match="hnet: \"weights\" has 15 rows for 16 faces"):
        gproj.darboux(broken)
    with pytest.raises(TypeError, match="hnet: expected a dict, its JSON text or a path, not int"):
        gproj.darboux(3)


def test_anet_on_the_diagonals_equals_the_command_line(cli):
    V, F = gproj.grid(nu=11, nv=11, surface="hyperboloid", noise=0.05, diagonal=True)
    result = compare_with_command_line(cli, "anet", V, F, {"net": "diagonal"},
                                       ["--net", "diagonal"])
    assert result.converged and result.report["net"] == "diagonal"
    assert result.report.final["max_star_planarity"] <= 1e-9
    assert result.report.final["non_convex_quads"] == 0
    with pytest.raises(ValueError, match="net: 'diagonals' is not one of"):
        gproj.anet(V, F, net="diagonals")


def test_hnet_of_a_diagonal_mesh_names_its_input_vertices():
    V, F = gproj.grid(nu=11, nv=11, surface="hyperboloid", noise=0.03, diagonal=True)
    result = gproj.hnet(V, F, net="diagonal", diagonal_colour=1)
    assert result.converged and result.report["net"] == "diagonal"
    ids = result.output["input_vertices"]
    assert len(ids) == len(result.output["vertices"]) and len(set(ids)) == len(ids)
    moved = np.linalg.norm(np.array(result.output["vertices"]) - V[ids], axis=1)
    assert moved.max() < 0.05
    skin = gproj.darboux(result.output)
    assert skin.converged and skin.report["measures"]["max_circle_deviation"] < 1e-10
