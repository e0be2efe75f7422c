# Type stubs of stairplan.optim (hand-written).
from typing import Any, Callable, Optional, Sequence

import numpy as np
import numpy.typing as npt

Array = npt.NDArray[np.float64]

class VariableBlock:
    name: str
    start: int
    size: int

class ConstraintRows:
    name: str
    start: int
    size: int

class Program:
    def __init__(self) -> None: ...
    def add_variables(self, name: str, size: int) -> VariableBlock: ...
    def add_quadratic_cost(self, block: VariableBlock, Q: npt.ArrayLike, g: npt.ArrayLike) -> None: ...
    def add_cross_quadratic_cost(self, a: VariableBlock, b: VariableBlock, Q: npt.ArrayLike) -> None: ...
    def add_linear_cost(self, block: VariableBlock, g: npt.ArrayLike) -> None: ...
    def add_constant(self, c: float) -> None: ...
    def add_linear_constraint(self, terms: Sequence[tuple[VariableBlock, npt.ArrayLike]], lower: npt.ArrayLike,
                              upper: npt.ArrayLike, name: str = ...) -> ConstraintRows: ...
    def add_nonlinear_cost(self, blocks: Sequence[VariableBlock], value: Callable[[Array], float],
                           gradient: Callable[[Array, int], npt.ArrayLike], name: str = ...) -> None: ...
    def add_nonlinear_constraint(self, blocks: Sequence[VariableBlock], lower: npt.ArrayLike, upper: npt.ArrayLike,
                                 value: Callable[[Array], npt.ArrayLike],
                                 jacobian: Callable[[Array, int], npt.ArrayLike], name: str = ...) -> None: ...
    def set_variable_bounds(self, block: VariableBlock, lower: npt.ArrayLike, upper: npt.ArrayLike) -> None: ...
    def set_linear_cost(self, block: VariableBlock, g: npt.ArrayLike) -> None: ...
    def set_constraint_bounds(self, rows: ConstraintRows, lower: npt.ArrayLike, upper: npt.ArrayLike) -> None: ...
    def set_constraint_coefficients(self, rows: ConstraintRows, block: VariableBlock, A: npt.ArrayLike) -> None: ...
    def set_initial_guess(self, block: VariableBlock, x0: npt.ArrayLike) -> None: ...
    num_variables: int
    num_rows: int
    blocks: list[VariableBlock]
    is_quadratic: bool
    hessian: Array
    linear_cost: Array
    constant: float
    constraint_matrix: Array
    row_lower: Array
    row_upper: Array
    variable_lower: Array
    variable_upper: Array
    def objective(self, x: npt.ArrayLike) -> float: ...
    def max_violation(self, x: npt.ArrayLike) -> float: ...

def read_qps(path: Any) -> Program: ...

class SolveStatus:
    SOLVED: SolveStatus
    INFEASIBLE: SolveStatus
    UNBOUNDED: SolveStatus
    ITERATION_LIMIT: SolveStatus
    TIME_LIMIT: SolveStatus
    NUMERICAL_ERROR: SolveStatus
    INVALID_INPUT: SolveStatus

class SolveResult:
    status: SolveStatus
    solved: bool
    x: Array
    objective: float
    row_duals: Array
    bound_duals: Array
    nonlinear_duals: Array
    iterations: int
    solve_time_us: float
    primal_residual: float
    dual_residual: float

class Solver:
    name: str
    def solve(self, program: Program) -> SolveResult: ...

class ActiveSetQpSettings:
    max_iterations: int
    max_outer_iterations: int
    time_limit_s: float
    feasibility_tol: float
    refinement_steps: int
    warm_start: bool

class IpoptSettings:
    tolerance: float
    max_iterations: int
    time_limit_s: float
    string_options: dict[str, str]
    numeric_options: dict[str, float]
    integer_options: dict[str, int]

class NloptSettings:
    class Algorithm:
        SLSQP: NloptSettings.Algorithm
        COBYLA: NloptSettings.Algorithm
    algorithm: NloptSettings.Algorithm
    xtol_rel: float
    ftol_rel: float
    constraint_tol: float
    max_evaluations: int
    time_limit_s: float

class ActiveSetQpSolver(Solver):
    def __init__(self, settings: Optional[ActiveSetQpSettings] = ...) -> None: ...
    settings: ActiveSetQpSettings

class IpoptSolver(Solver):
    def __init__(self, settings: Optional[IpoptSettings] = ...) -> None: ...
    settings: IpoptSettings

class NloptSolver(Solver):
    def __init__(self, settings: Optional[NloptSettings] = ...) -> None: ...
    settings: NloptSettings
