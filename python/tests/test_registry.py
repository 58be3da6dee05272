"""The Python functions of the registry's problems agree with the registry and the command line:
the same schema, every problem a function, every option a keyword with the schema's default."""
import json
import pathlib
import re
import warnings

import numpy as np
import pytest

import gproj


def test_schema_is_the_command_lines(cli):
    printed = json.loads(cli.run("schema").stdout)
    assert gproj.schema() == printed
    assert printed["version"] == gproj.__version__


def test_version_is_the_command_lines(cli):
    assert cli.run("--version").stdout.strip() == "gproj " + gproj.__version__


def python_literal(value):
    if isinstance(value, list):
        return "[" + ", ".join(python_literal(v) for v in value) + "]"
    return repr(value) if not isinstance(value, float) else "%g" % value


@pytest.mark.parametrize("problem", [p["name"] for p in gproj.schema()["problems"]])
def test_every_problem_is_a_function_whose_doc_gives_every_option(problem):
    spec = next(p for p in gproj.schema()["problems"] if p["name"] == problem)
    function = getattr(gproj, problem)
    signature = function.__doc__.splitlines()[0]
    for option in spec["options"]:
        default = option["default"]
        if option.get("required"):
            assert f", {option['name']}," in signature, option["name"]
            continue
        shown = "None" if default is None else python_literal(default)
        assert f"{option['name']}={shown}" in signature, option["name"]
        assert f"    {option['name']} ({option['type']}" in function.__doc__
        # The schema's range in the option's line of the docstring.
        line = next(l for l in function.__doc__.splitlines()
                    if l.startswith(f"    {option['name']} ({option['type']}"))
        shown_range = re.search(r"in ([\[(])([^,]+), ([^\])]+)([\])])", line.split(":")[0])
        if "minimum" in option and "maximum" in option:
            assert shown_range, (option["name"], line)
            assert float(shown_range.group(2)) == option["minimum"], line
            assert float(shown_range.group(3)) == option["maximum"], line
            assert (shown_range.group(1) == "(") == option["minimum_exclusive"], line
            assert (shown_range.group(4) == ")") == option["maximum_exclusive"], line
        elif "minimum" in option or "maximum" in option:
            bound = "minimum" if "minimum" in option else "maximum"
            one = re.search(r"([<>]=?) (\S+)\)", line.split(":")[0])
            assert one and float(one.group(2)) == option[bound], (option["name"], line)
    for item in spec["inputs"]:
        if not item["positional"]:
            assert f"{item['name']}=None" in signature


def test_python_defaults_run_like_the_command_lines(cli):
    # No keyword given: the schema's defaults, as on the command line without flags.
    V, F = gproj.grid(nu=6, nv=6, noise=0.05)
    source = cli.write_mesh("in.obj", V, F)
    cli.run("planarize", source, "-o", cli.path("out.obj"), "--report", cli.path("r.json"))
    V_out, report = gproj.planarize(V, F)
    assert report["options"] == cli.read_report("r.json")["options"]
    assert np.max(np.abs(V_out - gproj.read_mesh(cli.path("out.obj"))[0])) <= 1e-12


def test_far_from_input_warns():
    # A sheared grid of quads that are far from planar: planarizing changes many corner angles.
    V, F = gproj.grid(nu=6, nv=6, noise=0.6)
    with warnings.catch_warnings(record=True) as caught:
        warnings.simplefilter("always")
        gproj.planarize(V, F, allow_folds=True)
    assert any("the input is far from a PQ (conjugate) mesh" in str(w.message) for w in caught)


def test_field_is_the_command_lines_with_its_directions_as_arrays(cli):
    mesh = str(pathlib.Path(__file__).resolve().parents[2] / "examples/data/monkey_saddle_tri.obj")
    V, F = gproj.read_mesh(mesh)
    cli.run("field", mesh, "-o", cli.path("f.obj"), "--report", cli.path("r.json"))
    result, report = gproj.field(V, F)
    command_line = cli.read_report("r.json")
    assert report["singularities"] == command_line["singularities"]
    assert report["options"] == command_line["options"]
    with open(cli.path("f.obj")) as f:
        assert result["output"] == f.read()
    first, second = result["first"], result["second"]
    assert first.shape == second.shape == (len(V), 3)
    # unit lines, the two of a vertex distinct (the asymptotic pair of a saddle)
    fitted = np.linalg.norm(first, axis=1) > 0
    assert fitted.sum() == report["final"]["fitted_vertices"]
    assert np.allclose(np.linalg.norm(first[fitted], axis=1), 1.0)
    assert np.all(np.abs(np.einsum("ij,ij->i", first[fitted], second[fitted])) < 0.999)
    # the monkey saddle's flat point: one singularity of index -1/2
    assert [s["index"] for s in report["singularities"]] == [-0.5]


def test_remesh_is_the_command_lines(cli):
    mesh = str(pathlib.Path(__file__).resolve().parents[2] / "examples/data/monkey_saddle_tri.obj")
    V, F = gproj.read_mesh(mesh)
    cli.run("remesh", mesh, "--edge-length", 0.15, "-o", cli.path("q.obj"), "--report",
            cli.path("r.json"))
    result, report = gproj.remesh(V, F, edge_length=0.15)
    Vq, Fq = result["output"]
    Vc, Fc = gproj.read_mesh(cli.path("q.obj"))
    assert np.array_equal(np.asarray(Fq), np.asarray(Fc))
    assert np.max(np.abs(Vq - Vc)) <= 1e-12
    assert report["converged"] == cli.read_report("r.json")["converged"]
    assert report["inner_valences"] == cli.read_report("r.json")["inner_valences"]
    # 004 Theorem 6: the flat point of the monkey saddle becomes one vertex of valence 6
    assert report["inner_valences"].get("6") == 1
    assert np.asarray(Fq).shape[1] == 4


DATA = pathlib.Path(__file__).resolve().parents[2] / "examples" / "data"


def test_mrevolution_is_the_command_lines(cli):
    curve = np.loadtxt(DATA / "m_revolution_curve.txt")
    p2, p3 = [-0.6840402866513374, 1.8793852415718169, 0], [1, 1.7320508075688772, 0]
    cli.run("mrevolution", DATA / "m_revolution_curve.txt", "--p2=" + ",".join(map(repr, p2)),
            "--p3", ",".join(map(repr, p3)), "-o", cli.path("m.obj"), "--report",
            cli.path("r.json"))
    result, report = gproj.mrevolution(curve, p2=p2, p3=p3, outputs=["revolution"])
    V, F = result["output"]
    Vc, Fc = gproj.read_mesh(cli.path("m.obj"))
    assert np.max(np.abs(V - Vc)) <= 1e-12 and np.array_equal(np.asarray(F), np.asarray(Fc))
    assert report["final"]["max_concyclicity"] < 1e-9  # a circular mesh
    assert report["final"]["curve_roundtrip"] < 1e-9  # through the curve's own points
    assert "revolution" in result
    with pytest.raises(TypeError, match="p3: this option is required"):
        gproj.mrevolution(curve, p2=p2)
    with pytest.raises(ValueError, match="curve: a curve needs at least 2 points"):
        gproj.mrevolution(curve[:1], p2=p2, p3=p3)
    with pytest.raises(ValueError, match=r"curve must be an \(n, 3\) array of floats, got shape \(3, 21\)"):
        gproj.mrevolution(curve.T, p2=p2, p3=p3)  # (3, n): refused, not read in the wrong order


def test_beams_is_the_command_lines(cli):
    cli.run("invert", DATA / "revolution_13x17.obj", "--centre", "2,-1,3", "-o",
            cli.path("circular.obj"))
    V, F = gproj.read_mesh(cli.path("circular.obj"))
    cli.run("beams", cli.path("circular.obj"), "--height", 0.05, "-o", cli.path("b.obj"),
            "--report", cli.path("r.json"))
    result, report = gproj.beams(V, F, height=0.05, outputs=["offset", "axes"])
    Vb, Fb = result["output"]
    Vc, Fc = gproj.read_mesh(cli.path("b.obj"))
    assert np.max(np.abs(Vb - Vc)) <= 1e-12
    assert report["final"] == pytest.approx(cli.read_report("r.json")["final"], rel=1e-12)
    assert report["final"]["max_beam_planarity"] < 1e-10
    Vo, Fo = result["offset"]
    assert Vo.shape == V.shape  # the parallel offset, one vertex per node
    assert result["axes"].count("\nl ") == len(V)


def test_out_of_range_options_are_refused_by_both_front_ends_naming_the_option(cli):
    """Every bounded option of planarize, just outside its range: Python raises ValueError naming
    the keyword, the command line exits 1 naming the flag, and neither writes anything."""
    V, F = gproj.grid(nu=4, nv=4, noise=0.05)
    source = cli.write_mesh("in.obj", V, F)
    spec = next(p for p in gproj.schema()["problems"] if p["name"] == "planarize")
    checked = 0
    for option in spec["options"]:
        if option["type"] not in ("number", "int"):
            continue
        for bound, step in (("minimum", -1.0), ("maximum", 1.0)):
            if bound not in option:
                continue
            exclusive = option.get(bound + "_exclusive", False)
            value = option[bound] if exclusive else option[bound] + step
            if option["type"] == "int":
                value = int(value)
            with pytest.raises(ValueError, match=option["name"]):
                gproj.planarize(V, F, **{option["name"]: value})
            flag = "--" + option["name"].replace("_", "-")
            out = cli.path("out_%s.obj" % option["name"])
            result = cli.run("planarize", source, "-o", out, flag, value, check=False)
            assert result.returncode == 1 and flag in result.stderr, (flag, result.stderr)
            assert not pathlib.Path(out).exists()
            checked += 1
    assert checked >= 10
