"""The Python functions of the registry's problems agree with the registry and the command line:
the same schema, every problem a function, every option a keyword with the schema's default."""
import inspect
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


@pytest.mark.parametrize("problem", [p["name"] for p in gproj.schema()["problems"]])
def test_every_problem_is_a_function_whose_doc_gives_every_option(problem):
    spec = next(p for p in gproj.schema()["problems"] if p["name"] == problem)
    function = getattr(gproj, problem)
    parameters = inspect.signature(function).parameters
    for option in spec["options"]:
        # Every option a keyword-only parameter with the schema's default (none when required).
        parameter = parameters[option["name"]]
        assert parameter.kind is inspect.Parameter.KEYWORD_ONLY, option["name"]
        if option.get("required"):
            assert parameter.default is inspect.Parameter.empty, option["name"]
        else:
            assert parameter.default == option["default"], option["name"]
        # The option's line of the docstring: "    name: (type, unit, >= min, <= max) doc."
        line = next((l for l in function.__doc__.splitlines()
                     if l.startswith(f"    {option['name']}: ({option['type']}")), None)
        assert line, option["name"]
        shown = line.split(")")[0]
        assert (", required" in shown) == bool(option.get("required")), line
        # The schema's range, exact, with its exclusivity.
        for bound, exclusive, inclusive in (("minimum", ">", ">="), ("maximum", "<", "<=")):
            if bound not in option:
                continue
            sign = exclusive if option.get(bound + "_exclusive", False) else inclusive
            found = re.search(f", {sign} ([^,]+)", shown)
            assert found and float(found.group(1)) == option[bound], (option["name"], line)
    for item in spec["inputs"]:
        if not item["positional"]:
            parameter = parameters[item["name"]]
            assert parameter.kind is inspect.Parameter.KEYWORD_ONLY and parameter.default is None
            assert f"    {item['name']}: " in function.__doc__, item["name"]


def test_python_defaults_run_like_the_command_lines(cli):
    # No keyword given: the schema's defaults, as on the command line without flags.
    V, F = gproj.grid(nu=6, nv=6, noise=0.05)
    source = cli.write_mesh("in.obj", V, F)
    cli.run("planarize", source, "-o", cli.path("out.obj"), "--report", cli.path("r.json"))
    result = gproj.planarize(V, F)
    assert result.report["options"] == cli.read_report("r.json")["options"]
    assert np.max(np.abs(result.vertices - gproj.read_mesh(cli.path("out.obj"))[0])) <= 1e-12


def test_far_from_input_warns():
    # A sheared grid of quads that are far from planar: planarizing changes many corner angles.
    V, F = gproj.grid(nu=6, nv=6, noise=0.6)
    with warnings.catch_warnings(record=True) as caught:
        warnings.simplefilter("always")
        gproj.planarize(V, F, allow_folds=True)
    assert any("the input is far from a PQ (conjugate) mesh" in str(w.message) and
               issubclass(w.category, gproj.GprojWarning) for w in caught)
    assert issubclass(gproj.GprojWarning, UserWarning)


def test_field_is_the_command_lines_with_its_directions_as_arrays(cli):
    mesh = str(pathlib.Path(__file__).resolve().parents[2] / "examples/data/monkey_saddle_tri.obj")
    V, F = gproj.read_mesh(mesh)
    cli.run("field", mesh, "-o", cli.path("f.obj"), "--report", cli.path("r.json"))
    result = gproj.field(V, F)
    report = result.report
    command_line = cli.read_report("r.json")
    assert report["singularities"] == command_line["singularities"]
    assert report["options"] == command_line["options"]
    with open(cli.path("f.obj")) as f:
        assert result.output == f.read()  # a text output: the segments' OBJ text
    first, second = result.first, result.second
    assert first is result.arrays["first"] and second is result.arrays["second"]
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
    result = gproj.remesh(V, F, edge_length=0.15)
    report = result.report
    Vq, Fq = result.output
    Vc, Fc = gproj.read_mesh(cli.path("q.obj"))
    assert np.array_equal(np.asarray(Fq), np.asarray(Fc))
    assert np.max(np.abs(Vq - Vc)) <= 1e-12
    assert report["converged"] == cli.read_report("r.json")["converged"]
    assert report["inner_valences"] == cli.read_report("r.json")["inner_valences"]
    # 004 Theorem 6: the flat point of the monkey saddle becomes one vertex of valence 6
    assert report["inner_valences"].get("6") == 1
    assert np.asarray(Fq).shape[1] == 4


def test_remesh_cuts_through_holes(cli):
    """A catenoid's neck (an annulus) built in numpy: the quads close up around it."""
    nu, nv = 72, 24
    u, v = np.meshgrid(2 * np.pi * np.arange(nu) / nu, np.linspace(-0.8, 0.8, nv + 1),
                       indexing="ij")
    V = np.stack([np.cosh(v) * np.cos(u), np.cosh(v) * np.sin(u), v], axis=-1).reshape(-1, 3)
    at = lambda i, j: (i % nu) * (nv + 1) + j  # noqa: E731
    F = [[at(i, j), at(i + 1, j), at(i + 1, j + 1)] for i in range(nu) for j in range(nv)]
    F += [[at(i, j), at(i + 1, j + 1), at(i, j + 1)] for i in range(nu) for j in range(nv)]
    result = gproj.remesh(V, np.array(F), edge_length=0.1)
    assert result.report["converged"]
    assert result.report["boundary_loops"] == 2
    Vq, Fq = result.output
    Fq = np.asarray(Fq)
    edges = {tuple(sorted((f[k], f[(k + 1) % 4]))) for f in Fq for k in range(4)}
    assert len(np.unique(Fq)) - len(edges) + len(Fq) == 0  # an annulus: closed around the neck
    # every edge along an asymptotic line, at 45 degrees to the meridian and the parallel
    a, b = Vq[Fq[:, 0]], Vq[Fq[:, 1]]
    d = b - a
    mid = 0.5 * (a + b)
    parallel = np.stack([-mid[:, 1], mid[:, 0], 0 * mid[:, 0]], axis=1)
    cosine = np.abs(np.einsum("ij,ij->i", d, parallel)) / (
        np.linalg.norm(d, axis=1) * np.linalg.norm(parallel, axis=1))
    assert np.mean(np.abs(np.degrees(np.arccos(np.clip(cosine, 0, 1))) - 45)) < 3


def test_remesh_cuts_a_handle_open(cli):
    """A torus with a hole built in numpy (a handle): principal quads of Euler characteristic -1."""
    nu, nv = 90, 36
    a, b = np.meshgrid(2 * np.pi * np.arange(nu) / nu, 2 * np.pi * np.arange(nv) / nv,
                       indexing="ij")
    V = np.stack([(2 + np.cos(b)) * np.cos(a), (2 + np.cos(b)) * np.sin(a), np.sin(b)],
                 axis=-1).reshape(-1, 3)
    at = lambda i, j: (i % nu) * nv + j % nv  # noqa: E731
    F = [[at(i, j), at(i + 1, j), at(i + 1, j + 1)] for i in range(nu) for j in range(nv)]
    F += [[at(i, j), at(i + 1, j + 1), at(i, j + 1)] for i in range(nu) for j in range(nv)]
    F = np.array(F)
    hole = np.array([3 * np.cos(1.0), 3 * np.sin(1.0), 0.0])
    F = F[np.linalg.norm(V[F].mean(axis=1) - hole, axis=1) > 0.45]
    result = gproj.remesh(V, F, directions="principal", edge_length=0.2)
    assert result.report["converged"], result.report["termination"]
    assert result.report["handles"] == 1 and result.report["boundary_loops"] == 1
    Vq, Fq = result.output
    Fq = np.asarray(Fq)
    edges = {tuple(sorted((f[k], f[(k + 1) % 4]))) for f in Fq for k in range(4)}
    assert len(np.unique(Fq)) - len(edges) + len(Fq) == -1  # closed around both cycles


DATA = pathlib.Path(__file__).resolve().parents[2] / "examples" / "data"


def test_mrevolution_is_the_command_lines(cli):
    curve = np.loadtxt(DATA / "m_revolution_curve.txt")
    p2, p3 = [-0.6840402866513374, 1.8793852415718169, 0], [1, 1.7320508075688772, 0]
    cli.run("mrevolution", DATA / "m_revolution_curve.txt", "--p2=" + ",".join(map(repr, p2)),
            "--p3", ",".join(map(repr, p3)), "-o", cli.path("m.obj"), "--report",
            cli.path("r.json"))
    result = gproj.mrevolution(curve, p2=p2, p3=p3, outputs=["revolution"])
    report = result.report
    V, F = result.output
    Vc, Fc = gproj.read_mesh(cli.path("m.obj"))
    assert np.max(np.abs(V - Vc)) <= 1e-12 and np.array_equal(np.asarray(F), np.asarray(Fc))
    assert report["final"]["max_concyclicity"] < 1e-9  # a circular mesh
    assert report["final"]["curve_roundtrip"] < 1e-9  # through the curve's own points
    assert "revolution" in result.outputs and isinstance(result.revolution, gproj.Mesh)
    with pytest.raises(TypeError, match=r"^mrevolution\(\): missing the required option 'p3'"):
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
    result = gproj.beams(V, F, height=0.05, outputs=["offset", "axes"])
    report = result.report
    Vb, Fb = result.output
    Vc, Fc = gproj.read_mesh(cli.path("b.obj"))
    assert np.max(np.abs(Vb - Vc)) <= 1e-12
    assert report["final"] == pytest.approx(cli.read_report("r.json")["final"], rel=1e-12)
    assert report["final"]["max_beam_planarity"] < 1e-10
    Vo, Fo = result.offset
    assert Vo.shape == V.shape  # the parallel offset, one vertex per node
    assert result.axes.count("\nl ") == len(V)


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
