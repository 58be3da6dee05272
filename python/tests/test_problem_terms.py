"""gproj.Problem beyond terms with hand derivatives: complex-step Jacobians with the sparsity
probed once, given Jacobians checked, inequalities written in Python, held items, closeness on
chosen items, the solver's schedule, and the docstring's own example."""
import math
import re
import textwrap

import numpy as np
import pytest

import gproj


def sphere_points(n=12, seed=3):
    """Points near the unit sphere, some below z = 0.3."""
    rng = np.random.default_rng(seed)
    P = rng.normal(size=(n, 3))
    P /= np.linalg.norm(P, axis=1)[:, None]
    return P * (1.0 + 0.1 * rng.uniform(-1, 1, size=(n, 1)))


def on_sphere_given(x, element):
    return np.array([x @ x - 1.0]), 2.0 * x[None, :]


def on_sphere_cs(x, element):
    return np.array([x @ x - 1.0])


def sphere_problem(function, **kwargs):
    p = gproj.Problem()
    V = p.add_block("points", 12, 3)
    p.set_values(V, sphere_points())
    p.add_term("on_sphere", function, 1, p.items(V)[:, None], **kwargs)
    p.add_closeness(V, weight=0.1)
    return p, V


@pytest.mark.parametrize("jac", ["auto", "cs"])
def test_complex_step_derivatives_match_given_ones(jac):
    given, V = sphere_problem(on_sphere_given, jac="given")
    computed, _ = sphere_problem(on_sphere_cs, jac=jac)
    a, b = given.solve(), computed.solve()
    assert a["converged"] and b["converged"], (a["message"], b["message"])
    assert a["iterations"][-1]["max_constraint"] <= 1e-10
    # Exact to rounding: the same iterates.
    assert len(a["iterations"]) == len(b["iterations"])
    assert np.allclose(given.values(V), computed.values(V), rtol=0, atol=1e-11)
    assert np.allclose(np.linalg.norm(computed.values(V), axis=1), 1.0, atol=1e-10)


def test_complex_step_on_a_term_of_several_items_and_rows():
    """Edge lengths of a closed polygon held at 1 by rows over pairs of points: the term uses
    np.linalg.norm-free, complex-safe code and two items per element."""
    n = 8
    angles = np.linspace(0, 2 * np.pi, n, endpoint=False)
    start = np.column_stack([np.cos(angles), np.sin(angles), 0.1 * np.sin(3 * angles)])
    p = gproj.Problem()
    V = p.add_block("points", n, 3)
    p.set_values(V, start)

    def length_and_height(x, element):
        a, b = x[:3], x[3:]
        d = b - a
        return np.array([d @ d - 0.5, a[2] + b[2]])

    items = p.items(V)[np.column_stack([np.arange(n), (np.arange(n) + 1) % n])]
    p.add_term("edges", length_and_height, 2, items, jac="cs")
    p.add_closeness(V, weight=0.01)
    summary = p.solve(max_iterations=50)
    assert summary["converged"], summary["message"]
    X = p.values(V)
    d = X[(np.arange(n) + 1) % n] - X
    assert np.allclose((d * d).sum(axis=1), 0.5, atol=1e-9)
    assert np.allclose(X[:, 2] + X[(np.arange(n) + 1) % n, 2], 0.0, atol=1e-9)


def test_the_probed_sparsity_keeps_untouched_scalars_out_of_the_pattern():
    """A row that reads only x and y of its point: z stays out of the Jacobian's pattern, and
    after the probe the complex step never steps z again."""
    stepped = np.zeros(3, int)

    def circle(x, element):
        if np.iscomplexobj(x):
            stepped[np.flatnonzero(x.imag)] += 1
        return np.array([x[0] * x[0] + x[1] * x[1] - 1.0])

    def build(function, **kwargs):
        p = gproj.Problem()
        V = p.add_block("points", 6, 3)
        p.set_values(V, sphere_points(6))
        p.add_term("circle", function, 1, p.items(V)[:, None], **kwargs)
        return p

    sparse = build(circle, jac="cs").solve(max_iterations=1, residual_tolerance=0.0)
    after_one = stepped.copy()
    stepped[:] = 0
    build(circle, jac="cs").solve(max_iterations=6, residual_tolerance=0.0)
    assert after_one[2] == stepped[2] == 2 * 6  # the probe: at the start and a perturbed point
    assert stepped[0] > after_one[0] > 2 * 6
    assert sparse["jacobian_nonzeros"] == 6 * 2
    full = build(lambda x, e: (np.array([x[0] ** 2 + x[1] ** 2 - 1.0]),
                               np.array([[2 * x[0], 2 * x[1], 1.0]])), check_jac=False).solve(
        max_iterations=1, residual_tolerance=0.0)
    assert full["jacobian_nonzeros"] == 6 * 3


def test_a_wrong_given_jacobian_is_refused_naming_the_entry():
    def wrong(x, element):
        return np.array([x @ x - 1.0]), np.array([[2 * x[0], 2 * x[1], x[2]]])  # 2 z, not z

    p, _ = sphere_problem(wrong)
    with pytest.raises(ValueError, match=re.escape("term 'on_sphere', element 0: the given "
                                                   "jacobian's entry (0, 2) is")):
        p.solve()
    q, _ = sphere_problem(wrong, check_jac=False)
    q.solve()  # unchecked: the user's responsibility


def test_a_given_jacobian_of_a_function_that_refuses_complex_input_is_checked_by_differences():
    def real_only(x, element):
        r = math.sqrt(float(x @ x))
        return np.array([r - 1.0]), (x / r)[None, :] * 1.5  # wrong by 1.5

    p, _ = sphere_problem(real_only)
    with pytest.raises(ValueError, match="the central-difference derivative is"):
        p.solve()


def test_a_function_that_drops_imaginary_parts_is_refused():
    def dropping(x, element):
        out = np.zeros(1)  # float64: assigning a complex value keeps its real part only
        out[0] = x @ x - 1.0
        return out

    p, _ = sphere_problem(dropping, jac="cs")
    with pytest.raises(ValueError, match="drops imaginary parts"):
        p.solve()


def test_a_function_that_fails_on_complex_input_says_why():
    def angle(x, element):  # np.arctan2 refuses complex input
        return np.array([np.arctan2(x[1], x[0]) - 0.5])

    p, _ = sphere_problem(angle, jac="cs")
    with pytest.raises(TypeError, match="fails on a complex x"):
        p.solve()
    # math.sqrt on a complex128 keeps its real part (with a ComplexWarning): found by the probe.
    q, _ = sphere_problem(lambda x, e: np.array([math.sqrt(x @ x) - 1.0]), jac="cs")
    with pytest.warns(np.ComplexWarning), pytest.raises(ValueError, match="drops imaginary parts"):
        q.solve()


def test_a_tuple_of_values_in_auto_mode_gets_a_hint():
    p = gproj.Problem()
    V = p.add_block("v", 2, 2)
    p.add_term("pair", lambda x, e: (x[0] - 1.0, x[1] - 2.0), 2, p.items(V)[:, None])
    with pytest.raises(ValueError, match="return the values as one array, or pass jac='cs'"):
        p.solve()
    with pytest.raises(ValueError, match="jac must be 'auto', 'given'"):
        p.add_term("other", lambda x, e: x, 1, p.items(V)[:, None], jac="numeric")


@pytest.mark.parametrize("jac", ["cs", "given"])
@pytest.mark.parametrize("solver", ["gp", "ceres"])
def test_inequalities_hold_and_pull_only_where_violated(jac, solver):
    """Points pulled onto the unit sphere with z >= 0.3: those below end on the circle z = 0.3,
    those above stay where the sphere constraint alone puts them."""
    P = sphere_points(16, seed=5)
    p = gproj.Problem()
    V = p.add_block("points", len(P), 3)
    p.set_values(V, P)
    p.add_term("on_sphere", on_sphere_given, 1, p.items(V)[:, None])
    if jac == "cs":
        slack = p.add_inequality("above", lambda x, e: x[2:] - 0.3, 1, p.items(V)[:, None],
                                 jac="cs")
    else:
        slack = p.add_inequality("above", lambda x, e: (x[2:] - 0.3, np.array([[0.0, 0.0, 1.0]])),
                                 1, p.items(V)[:, None])
    p.add_closeness(V, weight=0.1)
    # Ceres keeps fixed weights: closeness scaled down so that the rows decide.
    summary = p.solve(solver, max_iterations=200, soft_scale=1e-8)
    X = p.values(V)
    assert np.all(X[:, 2] >= 0.3 - 1e-6), X[:, 2]
    assert np.allclose(np.linalg.norm(X, axis=1), 1.0, atol=1e-6)
    below = P[:, 2] < 0.25
    assert below.sum() >= 3  # the bound is active for these
    assert np.allclose(X[below, 2], 0.3, atol=1e-5)
    assert p.values(slack).shape == (len(P), 1)
    if solver == "gp":
        assert summary["converged"], summary["message"]
        # A satisfied bound's slack is sqrt(g): the slack block holds the distances' roots.
        above = X[:, 2] > 0.31
        assert np.allclose(p.values(slack)[above, 0] ** 2, X[above, 2] - 0.3, atol=1e-9)


def test_held_items_do_not_move_in_either_solver():
    for solver in ("gp", "ceres"):
        p, V = sphere_problem(on_sphere_given)
        mask = np.zeros(12, bool)
        mask[[1, 4, 7]] = True
        start = p.values(V)
        start[mask] /= np.linalg.norm(start[mask], axis=1)[:, None]  # their rows can hold
        p.set_values(V, start)
        p.hold(V, mask)
        p.hold(V, [9])
        assert p.held(V).tolist() == [i in (1, 4, 7, 9) for i in range(12)]
        p.hold(V, [9], held=False)
        summary = p.solve(solver, soft_scale=1e-2)
        X = p.values(V)
        assert np.array_equal(X[mask], start[mask])  # bit for bit
        assert not np.allclose(X[9], start[9])
        radii = np.linalg.norm(X[~mask], axis=1)
        if solver == "gp":
            assert summary["converged"], summary["message"]
            assert np.allclose(radii, 1.0, atol=1e-9)
        else:  # fixed weights: a balance with closeness
            assert np.allclose(radii, 1.0, atol=1e-3)


def test_holding_refuses_bad_items_and_eliminable_blocks():
    p = gproj.Problem()
    V = p.add_block("v", 4, 3)
    N = p.add_block("n", 2, 3, eliminable=True)
    with pytest.raises(ValueError, match="eliminable"):
        p.hold(N)
    with pytest.raises(ValueError, match=r"index 4 \(position 1\) is outside block 'v' of 4"):
        p.hold(V, [0, 4])
    with pytest.raises(ValueError, match=r"boolean mask of shape \(3,\), expected \(4,\)"):
        p.hold(V, np.ones(3, bool))
    with pytest.raises(TypeError, match="a boolean mask of shape"):
        p.hold(V, np.zeros((2, 2), int))


def test_closeness_on_chosen_items_pulls_only_those():
    p = gproj.Problem()
    V = p.add_block("v", 5, 2)
    p.set_values(V, np.zeros((5, 2)))
    targets = np.array([[1.0, 2.0], [3.0, 4.0]])
    p.add_closeness(V, items=[1, 3], targets=targets, role="constraint", name="pins")
    p.add_closeness(V, weight=1e-3, name="rest")
    p.solve(residual_tolerance=1e-12)
    X = p.values(V)
    assert np.allclose(X[[1, 3]], targets, atol=1e-9)
    assert np.allclose(X[[0, 2, 4]], 0.0)
    with pytest.raises(ValueError, match=r"targets: shape \(5, 2\), expected \(2, 2\) for the "
                                         r"chosen items of block 'v'"):
        p.add_closeness(V, items=[1, 3], targets=np.zeros((5, 2)), name="bad")
    with pytest.raises(ValueError, match=r"targets: shape \(2, 2\), expected \(3, 2\)"):
        p.add_closeness(V, items=np.array([True, False, True, True, False]),
                        targets=np.zeros((2, 2)), name="bad2")


def test_numerical_failure_is_not_usable():
    """A term that turns NaN away from its start: the solve fails and says the result is not
    usable."""
    p = gproj.Problem()
    V = p.add_block("v", 1, 1)
    p.set_values(V, np.array([[0.0]]))
    p.add_term("wall", lambda x, e: (np.array([x[0] - 2.0 if x[0] < 1e-9 else np.nan]),
                                     np.array([[1.0]])), 1, p.items(V)[:, None], check_jac=False)
    summary = p.solve()
    assert summary["termination"] == "FAILURE", summary["message"]
    assert summary["usable"] is False and summary["converged"] is False


def test_the_docstring_example_converges_with_its_defaults():
    """The Problem docstring's example, run as written on a PQ mesh of the sphere with noise."""
    doc = gproj.Problem.__doc__
    code = textwrap.dedent("\n".join(line for line in doc.splitlines()
                                     if line.startswith("    ")))
    # A latitude-longitude grid of the unit sphere above z = 0 (planar quads), disturbed.
    nu, nv = 7, 9
    lat = np.linspace(0.2, 1.2, nu)
    lon = np.linspace(0.0, 1.6, nv)
    grid = np.array([[np.cos(a) * np.cos(b), np.cos(a) * np.sin(b), np.sin(a)]
                     for a in lat for b in lon])
    rng = np.random.default_rng(1)
    vertices = grid + 0.02 * rng.normal(size=grid.shape)
    corners = [0, nv - 1, (nu - 1) * nv, nu * nv - 1]
    vertices[corners] = grid[corners]
    quads = np.array([[i * nv + j, i * nv + j + 1, (i + 1) * nv + j + 1, (i + 1) * nv + j]
                      for i in range(nu - 1) for j in range(nv - 1)])
    scope = {"gproj": gproj, "np": np, "n": len(vertices), "vertices": vertices,
             "quads": quads, "corners": corners}
    exec(code, scope)
    summary = scope["summary"]
    assert summary["converged"], summary["message"]
    X = scope["p"].values(scope["V"])
    assert np.allclose(np.linalg.norm(X, axis=1), 1.0, atol=1e-9)
    assert np.all(X[:, 2] >= 0.1 - 1e-9)
    assert np.array_equal(X[corners], vertices[corners])
    # Planar quads: the distance between the diagonals relative to the edge length.
    for q in quads:
        a, b, c, d = X[q]
        n = np.cross(c - a, d - b)
        assert abs(n @ (b - a)) / np.linalg.norm(n) < 1e-8 * np.linalg.norm(b - a) + 1e-10
    # Not far from the start: closeness guided the solve.
    assert np.abs(X - vertices).max() < 0.1
