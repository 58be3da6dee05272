"""grid (the mesh problems' test grids) against the command line."""
import inspect

import pytest

import gproj
from conftest import assert_close


def test_grid_returns_the_mesh_alone_as_the_command_line_writes_it(cli):
    cli.run("grid", "-o", cli.path("g.obj"), "--nu", 5, "--nv", 7, "--surface", "enneper",
            "--noise", 0.02, "--seed", 9)
    mesh = gproj.grid(nu=5, nv=7, surface="enneper", noise=0.02, seed=9)
    assert isinstance(mesh, gproj.Mesh)
    V, F = mesh
    Vc, Fc = gproj.read_mesh(cli.path("g.obj"))
    assert V.shape == (35, 3) and F.shape == (24, 4)
    assert_close(V, Vc, tol=1e-9)  # the OBJ text rounds
    assert (F == Fc).all()
    parameters = list(inspect.signature(gproj.grid).parameters.values())
    assert [(p.name, p.default) for p in parameters[:3]] == [
        ("surface", "paraboloid"), ("nu", 21), ("nv", 21)]
    assert all(p.kind is inspect.Parameter.KEYWORD_ONLY for p in parameters)
    with pytest.raises(ValueError, match="^nu: 1 is not in \\[2, 100000\\]"):
        gproj.grid(nu=1)
    with pytest.raises(TypeError, match=r"^grid\(\) has no argument 'nosie'; did you mean 'noise'"):
        gproj.grid(nosie=0.1)
