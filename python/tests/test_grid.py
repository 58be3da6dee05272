"""grid (the mesh problems' test grids) against the command line."""
import pytest

import gproj
from conftest import assert_close


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
