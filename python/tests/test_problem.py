"""gproj.Problem: blocks, built-in terms, a term written in Python, both solvers."""
import numpy as np
import pytest

import gproj


def circle_problem():
    """examples/custom_constraint.cc in Python: five points pulled onto the unit circle."""
    p = gproj.Problem()
    points = p.add_block("points", 5, 2)
    start = np.array([[0.5 + 0.3 * i, 1.0 - 0.2 * i] for i in range(5)])
    p.set_values(points, start)

    def on_unit_circle(x, element):
        return [x @ x - 1.0], [2.0 * x]

    p.add_term("on_unit_circle", on_unit_circle, 1, p.items(points)[:, None])
    p.add_closeness(points, weight=0.01, name="stay_near")
    return p, points


def test_python_term_by_both_solvers():
    gp, points = circle_problem()
    # Fixed weights (Problem.solve fades them by default): the objective Ceres minimises.
    summary = gp.solve(residual_tolerance=0.0, soft_decay=1.0, soft_residual=0.0, epsilon_min=0.0)
    assert summary["solver"] == "gp" and summary["converged"]
    ceres, _ = circle_problem()
    ceres_summary = ceres.solve("ceres")
    assert ceres_summary["usable"]
    assert summary["objective"] == pytest.approx(ceres_summary["objective"], rel=1e-8)
    assert np.allclose(gp.values(points), ceres.values(points), atol=1e-6)
    radii = np.linalg.norm(gp.values(points), axis=1)
    assert np.all(np.abs(radii - 1.0) < 0.05)
    assert sorted(summary["iterations"][0]["families"]) == ["on_unit_circle", "stay_near"]


def test_python_term_matches_the_builtin_planarity():
    """The built-in quad planarity and the same rows written in Python reach the same result."""
    V, F = gproj.grid(nu=5, nv=5, noise=0.05)

    def build(python_planarity):
        p = gproj.Problem()
        vertices = p.add_block("vertices", len(V), 3)
        p.set_values(vertices, V)
        if python_planarity:
            normals = p.add_block("normals", len(F), 3)
            d1, d2 = V[F[:, 2]] - V[F[:, 0]], V[F[:, 3]] - V[F[:, 1]]
            n = np.cross(d1, d2)
            p.set_values(normals, n / np.linalg.norm(n, axis=1)[:, None])

            def planarity(x, element):
                n, v = x[:3], x[3:].reshape(4, 3)
                values, jac = np.zeros(5), np.zeros((5, 15))
                for j in range(4):
                    edge = v[(j + 1) % 4] - v[j]
                    values[j] = n @ edge
                    jac[j, :3] = edge
                    jac[j, 3 + 3 * ((j + 1) % 4):6 + 3 * ((j + 1) % 4)] += n
                    jac[j, 3 + 3 * j:6 + 3 * j] -= n
                values[4] = n @ n - 1.0
                jac[4, :3] = 2.0 * n
                return values, jac

            items = np.column_stack([p.items(normals), p.items(vertices)[F]])
            p.add_term("planarity", planarity, 5, items)
        else:
            p.add_planarity(vertices, F)
        p.add_closeness(vertices, weight=0.1)
        stencils = np.array([[i * 5 + j - 1, i * 5 + j, i * 5 + j + 1]
                             for i in range(5) for j in range(1, 4)])
        p.add_fairness(vertices, stencils, weight=1.0)
        return p, vertices

    results = []
    for python_planarity in (False, True):
        p, vertices = build(python_planarity)
        summary = p.solve(max_iterations=10, soft_decay=0.1)
        assert summary["iterations"][-1]["max_constraint"] < 1e-8
        results.append(p.values(vertices))
    assert np.allclose(results[0], results[1], atol=1e-8)


def test_generic_callback_stops():
    p, _ = circle_problem()
    summary = p.solve(callback=lambda record: record["iteration"] < 2, residual_tolerance=0.0)
    assert summary["termination"] == "USER_ABORT"
    assert len(summary["iterations"]) == 3


def test_python_term_exception_propagates():
    for solver in ("gp", "ceres"):
        p = gproj.Problem()
        b = p.add_block("a", 2, 1)

        def broken(x, element):
            raise ZeroDivisionError("broken term")

        p.add_term("broken", broken, 1, p.items(b)[:, None])
        with pytest.raises(ZeroDivisionError, match="broken term"):
            p.solve(solver)


def test_python_term_wrong_shapes_raise_value_error():
    p = gproj.Problem()
    b = p.add_block("a", 2, 3)
    p.add_term("bad", lambda x, e: (np.zeros(2), np.zeros((1, 3))), 1, p.items(b)[:, None])
    with pytest.raises(ValueError, match=r"term 'bad', element 0: values must have shape \(1,\), not \(2,\)"):
        p.solve()


def test_problem_input_errors():
    p = gproj.Problem()
    b = p.add_block("v", 4, 3)
    with pytest.raises(ValueError, match="already used"):
        p.add_block("v", 1, 1)
    with pytest.raises(ValueError, match="outside"):
        p.add_planarity(b, np.array([[0, 1, 2, 9]]))
    with pytest.raises(ValueError, match=r"values: shape \(3, 3\), expected \(4, 3\) for block 'v'"):
        p.set_values(b, np.zeros((3, 3)))
    with pytest.raises(ValueError, match="role"):
        p.add_closeness(b, role="hard")
    with pytest.raises(ValueError, match="no block"):
        p.values(3)
    p.add_closeness(b)
    with pytest.raises(ValueError, match="already used"):
        p.add_closeness(b)
    assert p.terms == ["closeness"]
    assert p.x.shape == (12,)


def test_items_outside_the_layout_and_duplicate_names_are_refused():
    p = gproj.Problem()
    points = p.add_block("points", 3, 2)
    p.set_values(points, np.zeros((3, 2)))

    def row(x, element):
        return [x[0]], [[1.0, 0.0]]

    with pytest.raises(ValueError, match=r"items: row 0 has index 5, outside \[0, 3\)"):
        p.add_term("row", row, 1, [[5]])
    p.add_term("row", row, 1, p.items(points)[:, None])
    with pytest.raises(ValueError, match="term name 'row' is empty or already used"):
        p.add_term("row", row, 1, p.items(points)[:, None])


def test_incompatible_constraints_are_not_converged_by_either_solver():
    """|x|^2 = 1 and |x|^2 = 4 on one point: both solvers end between them, and neither may call
    that converged while a constraint row is 1.5 away from zero."""
    for solver in ("gp", "ceres"):
        p = gproj.Problem()
        point = p.add_block("point", 1, 2)
        p.set_values(point, np.array([[0.7, 0.9]]))
        for name, r2 in (("unit", 1.0), ("double", 4.0)):
            p.add_term(name, lambda x, element, r2=r2: ([x @ x - r2], [2.0 * x]), 1,
                       p.items(point)[:, None])
        summary = p.solve(solver, residual_tolerance=1e-10)
        assert not summary["converged"], (solver, summary["termination"], summary["message"])
        assert summary["termination"] != "CONVERGENCE"
