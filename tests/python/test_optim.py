"""The optimisation core from numpy: a Maros-Meszaros QP against its published optimum."""
import csv
import os

import numpy as np
import pytest

from conftest import shared_path
from stairplan import optim


def reference_objective(name):
    with open(shared_path("data/qp/maros_meszaros/INDEX.tsv")) as f:
        for row in csv.DictReader(f, delimiter="\t"):
            if row["name"] == name:
                return float(row["opt_published"])
    raise KeyError(name)


def numpy_program(name):
    """The QPS file's data as numpy matrices, rebuilt into a fresh Program through the numpy API."""
    read = optim.read_qps(shared_path(os.path.join("data/qp/maros_meszaros", name + ".SIF")))
    H, g, A = read.hessian, read.linear_cost, read.constraint_matrix
    assert isinstance(H, np.ndarray) and H.shape == (read.num_variables, read.num_variables)
    prog = optim.Program()
    x = prog.add_variables("x", read.num_variables)
    prog.add_quadratic_cost(x, H, g)
    prog.add_constant(read.constant)
    prog.add_linear_constraint([(x, A)], read.row_lower, read.row_upper)
    prog.set_variable_bounds(x, read.variable_lower, read.variable_upper)
    return prog, x


@pytest.mark.parametrize("name", ["HS35", "HS21", "HS118"])
def test_maros_meszaros_qp_from_numpy_matches_the_published_optimum(name):
    prog, _ = numpy_program(name)
    expected = reference_objective(name)
    for solver in (optim.ActiveSetQpSolver(), optim.IpoptSolver()):
        result = solver.solve(prog)
        assert result.status == optim.SolveStatus.SOLVED, solver.name
        assert result.objective == pytest.approx(expected, rel=1e-6, abs=1e-8), solver.name
        assert prog.max_violation(result.x) < 1e-5  # Ipopt stops an interior point 1e-6 inside


def test_nonlinear_callbacks_from_python_reach_the_qp_optimum():
    # HS35's objective as a Python callable: NLopt's SLSQP and Ipopt find the QP's optimum.
    prog, x = numpy_program("HS35")
    H, g, c = prog.hessian, prog.linear_cost, prog.constant
    nl = optim.Program()
    y = nl.add_variables("y", 3)
    nl.add_nonlinear_cost([y], lambda v: 0.5 * v @ H @ v + g @ v + c, lambda v, k: H @ v + g)
    nl.add_linear_constraint([(y, prog.constraint_matrix)], prog.row_lower, prog.row_upper)
    nl.set_variable_bounds(y, prog.variable_lower, prog.variable_upper)
    for solver in (optim.NloptSolver(), optim.IpoptSolver()):
        result = solver.solve(nl)
        assert result.solved, solver.name
        assert result.objective == pytest.approx(reference_objective("HS35"), rel=1e-6)


def test_warm_resolve_after_an_in_place_update():
    prog = optim.Program()
    z = prog.add_variables("z", 2)
    prog.add_quadratic_cost(z, np.eye(2), np.zeros(2))
    solver = optim.ActiveSetQpSolver()
    prog.set_variable_bounds(z, np.array([1.0, -1.0]), np.array([2.0, 1.0]))
    assert solver.solve(prog).x == pytest.approx([1.0, 0.0])
    prog.set_linear_cost(z, np.array([0.0, -0.5]))
    assert solver.solve(prog).x == pytest.approx([1.0, 0.5])
