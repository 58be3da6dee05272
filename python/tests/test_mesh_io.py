"""read_mesh, write_mesh, grid and face_values against the command line, and every bad-array
case."""
import re

import numpy as np
import pytest

import gproj
from conftest import assert_close


def test_grid_equals_the_command_line(cli):
    for surface in ["paraboloid", "hypar", "revolution"]:
        cli.run("grid", "-o", cli.path("g.obj"), "--nu", 5, "--nv", 7, "--noise", 0.05,
                "--surface", surface, "--seed", 3)
        V, F = gproj.grid(nu=5, nv=7, noise=0.05, surface=surface, seed=3)
        Vc, Fc = gproj.read_mesh(cli.path("g.obj"))
        assert V.dtype == np.float64 and V.shape == (35, 3)
        assert F.dtype == np.int32 and F.shape == (24, 4)
        assert_close(V, Vc, 0.0)
        assert (F == Fc).all()


@pytest.mark.parametrize("circular", [False, True])
def test_face_values_equal_the_command_lines_face_values(cli, circular):
    V, F = gproj.grid(nu=6, nv=5, noise=0.1, seed=4)
    source = cli.write_mesh("in.obj", V, F)
    cli.run("planarize", source, "-o", cli.path("out.obj"), "--max-iterations", 2,
            "--face-values", cli.path("f.csv"), "--report", cli.path("r.json"),
            *(["--circular"] if circular else []))
    csv = np.loadtxt(cli.path("f.csv"), delimiter=",", skiprows=1)
    values = gproj.face_values(*gproj.read_mesh(cli.path("out.obj")), circular=circular)
    # planarize makes the same CSV itself when asked for its optional output face_values.
    result = gproj.planarize(V, F, max_iterations=2, circular=circular, outputs=["face_values"])
    with open(cli.path("f.csv")) as f:
        assert result.face_values == f.read()
    assert result.outputs == {"face_values": result.face_values} and result.picture is None
    columns = ["planarity", "planarity_abs", "kink_deg", "min_angle_deg"]
    columns += ["concyclicity"] if circular else []
    assert np.array_equal(csv[:, 0], np.arange(len(F)))
    for k, name in enumerate(columns):
        assert values[name].shape == (len(F),)
        assert np.allclose(values[name], csv[:, k + 1], rtol=1e-5, atol=1e-12), name
    assert values["convex"].dtype == bool and values["convex"].all()
    assert values["planarity"].max() == pytest.approx(
        cli.read_report("r.json")["final"]["max_planarity"], rel=1e-12)
    with pytest.raises(ValueError, match="4 vertices|quad"):
        gproj.face_values(V, F[:, :3])


@pytest.mark.parametrize("extension", ["obj", "off", "ply"])
def test_write_then_read_is_exact(tmp_path, extension):
    V, F = gproj.grid(nu=4, nv=3, noise=0.1)
    path = str(tmp_path / f"m.{extension}")
    gproj.write_mesh(path, V, F)
    mesh = gproj.read_mesh(path)
    assert isinstance(mesh, gproj.Mesh)
    V2, F2 = mesh
    assert V2 is mesh.vertices and F2 is mesh.faces
    # PLY is read through OpenMesh, in single precision.
    assert_close(V, V2, 1e-6 if extension == "ply" else 0.0)
    assert (F == F2).all()


def test_mixed_faces_are_lists(tmp_path):
    V = np.array([[0, 0, 0], [1, 0, 0], [1, 1, 0], [0, 1, 0], [2, 0.5, 0]], dtype=float)
    F = [[0, 1, 2, 3], [1, 4, 2]]
    gproj.write_mesh(str(tmp_path / "m.obj"), V, F)
    V2, F2 = gproj.read_mesh(str(tmp_path / "m.obj"))
    assert F2 == F
    assert_close(V, V2, 0.0)


def test_triangles_are_an_array(tmp_path):
    V = np.array([[0, 0, 0], [1, 0, 0], [0, 1, 0]], dtype=np.float32)
    gproj.write_mesh(str(tmp_path / "t.off"), V, np.array([[0, 1, 2]], dtype=np.int64))
    _, F = gproj.read_mesh(str(tmp_path / "t.off"))
    assert F.shape == (1, 3) and F.dtype == np.int32


def test_read_errors_are_the_command_lines(cli):
    with open(cli.path("bad.obj"), "w") as f:
        f.write("v 0 0 0\nv 1 0 0\nv 1 1 0\nf 1 2 7\n")
    with pytest.raises(ValueError) as error:
        gproj.read_mesh(cli.path("bad.obj"))
    result = cli.run("planarize", cli.path("bad.obj"), "-o", cli.path("o.obj"), check=False)
    assert result.returncode == 1
    assert result.stderr.strip() == "gproj planarize: " + str(error.value)
    with pytest.raises(ValueError, match="cannot open"):
        gproj.read_mesh(cli.path("missing.obj"))


def quad_obj(V, F):
    lines = ["v %r %r %r" % tuple(v) for v in V] + [
        "f " + " ".join(str(i + 1) for i in face) for face in F]
    return "\n".join(lines) + "\n"


BAD_MESHES = {
    "nan": (lambda V, F: (np.where(np.arange(V.size).reshape(V.shape) == 4, np.nan, V), F)),
    "index out of range": (lambda V, F: (V, np.where(F == 5, 99, F))),
    "negative index": (lambda V, F: (V, np.where(F == 5, -7, F))),
    "repeated vertex": (lambda V, F: (V, np.where(F == 5, 4, F))),
    "no faces": (lambda V, F: (V, np.zeros((0, 4), dtype=np.int32))),
    "degenerate": (lambda V, F: (np.where(np.isin(np.arange(9), F[0])[:, None], 0.0, V), F)),
    "inconsistent orientation": (lambda V, F: (V, np.vstack([F, F[:1]]))),
    "non-manifold edge": (lambda V, F: (np.vstack([V, [[5, 5, 5], [6, 5, 5]]]),
                                        np.vstack([F, [[F[0][0], F[0][1], 10, 9]]]))),
}
# Defects the command line's file readers find first, in their own words (naming the file's
# line and numbering); the arrays get the mesh check's wording.
READER_WORDED = {"nan", "negative index", "index out of range", "no faces"}


@pytest.mark.parametrize("case", sorted(BAD_MESHES))
def test_bad_meshes_raise_the_command_lines_message(cli, case):
    V, F = gproj.grid(nu=3, nv=3, noise=0.0)
    V, F = BAD_MESHES[case](V, F)
    with pytest.raises(ValueError) as error:
        gproj.planarize(V, F)
    message = str(error.value)
    assert message.startswith("mesh: ")
    if case in READER_WORDED:
        return
    with open(cli.path("bad.obj"), "w") as f:
        f.write(quad_obj(V, F))
    result = cli.run("planarize", cli.path("bad.obj"), "-o", cli.path("o.obj"), check=False)
    assert result.returncode == 1
    # "gproj planarize: <file>:<line>: <rule>" against "mesh: <rule>"
    rule = re.sub(r"^gproj planarize: [^:]*:\d+: ", "", result.stderr.strip())
    assert rule == message[len("mesh: "):]


BAD_ARRAYS = {
    "V complex": (lambda V, F: (V.astype(complex), F), "dtype complex128"),
    "V strings": (lambda V, F: (V.astype(str), F), "dtype <U"),
    "V 2 columns": (lambda V, F: (V[:, :2], F), "shape (9, 2)"),
    "V flat": (lambda V, F: (V.ravel(), F), "shape (27,)"),
    "V not an array": (lambda V, F: (object(), F), "(n, 3) array"),
    "F floats": (lambda V, F: (V, F.astype(float)), "integer vertex indices, got dtype float64"),
    "F flat": (lambda V, F: (V, F.ravel()), "shape (16,)"),
    "F face of floats": (lambda V, F: (V, [[0, 1, 4.0, 3]]), "4.0, not an integer"),
    "F not faces": (lambda V, F: (V, [1, 2, 3]), "face 0 is not a list"),
    "F huge index": (lambda V, F: (V, F.astype(np.int64) * 2**40), "references vertex"),
}


@pytest.mark.parametrize("case", sorted(BAD_ARRAYS))
def test_bad_arrays_raise_value_error(case, tmp_path):
    V, F = gproj.grid(nu=3, nv=3, noise=0.0)
    make, expected = BAD_ARRAYS[case]
    V, F = make(V, F)
    for call in (lambda: gproj.planarize(V, F), lambda: gproj.anet(V, F),
                 lambda: gproj.write_mesh(str(tmp_path / "m.obj"), V, F)):
        with pytest.raises(ValueError, match=expected.replace("(", r"\(").replace(")", r"\)")):
            call()


def test_bad_output_path_raises():
    V, F = gproj.grid(nu=3, nv=3)
    with pytest.raises(ValueError, match="extension"):
        gproj.write_mesh("/tmp/x.stl", V, F)
    with pytest.raises(ValueError):
        gproj.write_mesh("/nonexistent-dir/x.obj", V, F)
