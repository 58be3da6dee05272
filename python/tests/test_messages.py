"""Library messages name options as Python keywords: `name` reads name here, --name on the
command line (docs/architecture.md, "Adding a problem")."""
import pathlib

import numpy as np
import pytest

import gproj

DATA = pathlib.Path(__file__).resolve().parents[2] / "examples" / "data"
P2, P3 = [-0.6840402866513374, 1.8793852415718169, 0], [1, 1.7320508075688772, 0]


def message_of(call, *args, **kwargs):
    """The ValueError message `call` raises; it speaks Python: no flags, no backquotes."""
    with pytest.raises(ValueError) as error:
        call(*args, **kwargs)
    message = str(error.value)
    assert "--" not in message and "`" not in message, message
    return message


def holed_grid():
    """A 5 x 5 quad grid on a hyperbolic paraboloid without its middle face: an annulus."""
    V, F = gproj.grid(nu=6, nv=6, surface="hypar")
    F = np.asarray(F)
    centres = np.asarray(V)[F].mean(axis=1)
    middle = np.argmin(np.linalg.norm(centres - np.asarray(V).mean(axis=0), axis=1))
    return V, np.delete(F, middle, axis=0)


def test_remesh_names_edge_length_when_the_quads_are_too_small():
    V, F = gproj.read_mesh(str(DATA / "monkey_saddle_tri.obj"))
    message = message_of(gproj.remesh, V, F, edge_length=1e-4)
    assert "(edge_length) 0.0001 is" in message and "mean triangle edges" in message


def test_mrevolution_names_up_when_it_lies_in_the_drawing_plane():
    curve = np.loadtxt(DATA / "m_revolution_curve.txt")  # in the plane z = 0
    message = message_of(gproj.mrevolution, curve, p2=P2, p3=P3, up=[1, 0, 0])
    assert message.startswith("up lies in the drawing plane"), message


def test_mrevolution_names_p2_and_p3_when_they_are_off_the_circle():
    curve = np.loadtxt(DATA / "m_revolution_curve.txt")
    message = message_of(gproj.mrevolution, curve, p2=P2, p3=[1, 1.5, 0])
    assert ": p3 is " in message and "(p2: " in message, message


def test_hnet_names_allow_not_simply_connected_on_a_mesh_with_a_hole():
    V, F = holed_grid()
    message = message_of(gproj.hnet, V, F)
    assert "not simply connected" in message
    assert "pass allow_not_simply_connected to optimise anyway" in message


def test_cyclidic_names_closure_tolerance_and_planarize_circular():
    V, F = gproj.read_mesh(str(DATA / "noisy_grid_21x21.obj"))
    message = message_of(gproj.cyclidic, V, F)
    assert "not circular" in message and "(closure_tolerance " in message, message
    assert "planarize with circular" in message, message


def test_the_command_line_spells_the_same_message_with_flags(cli):
    source = cli.write_mesh("holed.obj", *holed_grid())
    run = cli.run("hnet", source, "-o", cli.path("h.json"), check=False)
    assert run.returncode == 1, run.stderr
    assert "pass --allow-not-simply-connected to optimise anyway" in run.stderr, run.stderr
    assert "`" not in run.stderr, run.stderr


def test_options_that_would_have_no_effect_are_refused():
    """An option whose condition is missing changed nothing before, silently; now the run says
    what it needs."""
    curve = np.loadtxt(DATA / "canal_curve.txt")
    message = message_of(gproj.canal, curve, first_point=[-0.5, 0.5, 2], length=2,
                         fixed_lengths=True)
    assert message.startswith("fixed_lengths needs smooth"), message
    gproj.canal(curve, first_point=[-0.5, 0.5, 2], length=2, fixed_lengths=True, smooth=True)

    V, F = gproj.grid(nu=5, nv=5, noise=0.05)
    message = message_of(gproj.planarize, V, F, ceres_soft_scale=0.01)
    assert message == "ceres_soft_scale applies to solver ceres only", message
    gproj.planarize(V, F, ceres_soft_scale=0.01, solver="ceres", max_iterations=3)
    gproj.planarize(V, F, options=gproj.PlanarizeOptions())  # the default is no misuse

    surface = DATA / "freeform_10x10.json"
    message = message_of(gproj.weingarten, surface, relation_on="auxiliaries", max_iterations=1)
    assert message.startswith("relation_on places a fixed relation (linear"), message
    gproj.weingarten(surface, relation_on="auxiliaries", linear=[0, 1, 0], max_iterations=1)
