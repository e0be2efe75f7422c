# Type stubs of the stairplan package (hand-written; tests/python/test_stubs.py checks that every
# public name of the module is declared here).
import os
from typing import Any, Callable, Iterable, Optional, Sequence, Union

import numpy as np
import numpy.typing as npt

from . import optim as optim

__version__: str
schema_version: int

PathLike = Union[str, os.PathLike[str]]
Axis = Union[float, tuple[float, float, int], str]

class FieldError(ValueError):
    field: str

class Stairs:
    def __init__(self, spec: Union[None, dict[str, Any], PathLike, Stairs] = ..., **fields: Any) -> None: ...
    steps: int
    rise: float
    run: float
    nosing: float
    width: float
    direction: str
    total_rise: float
    rises: list[float]
    def height_at(self, x: float, y: float) -> float: ...
    def to_dict(self) -> dict[str, Any]: ...

class Robot:
    def __init__(self, urdf: Optional[PathLike] = ...) -> None: ...
    @staticmethod
    def from_urdf_string(xml: str, source: str = ...) -> Robot: ...
    name: str
    source: str
    base_link: str
    total_mass: float
    hip_length: float
    hip_width: float
    legs: list[dict[str, Any]]

class ConstrainedMap:
    regions: list[dict[str, Any]]

class Perception:
    found: bool
    reason: str
    stairs: Optional[Stairs]
    map: Optional[ConstrainedMap]
    fit: dict[str, Any]

class Plan:
    status: str
    status_reason: str
    validated: bool
    valid: bool
    ok: bool
    gait: str
    cadence_s: float
    duration: float
    legs: list[str]
    footsteps: np.ndarray
    body: np.ndarray
    validation: Optional[dict[str, Any]]
    timing_us: dict[str, float]
    robot: Robot
    stairs: Stairs
    map: ConstrainedMap
    def to_dict(self) -> dict[str, Any]: ...
    def to_json(self) -> str: ...
    def to_svg(self) -> str: ...

class BodyState:
    def __init__(self, t: float = ..., x: float = ..., y: float = ..., z: float = ..., pitch: float = ...,
                 yaw: float = ..., com_shift: float = ..., com_shift_y: float = ...) -> None: ...
    t: float
    x: float
    y: float
    z: float
    pitch: float
    yaw: float
    com_shift: float
    com_shift_y: float

class BodyPlanStatus:
    OK: BodyPlanStatus
    STALE: BodyPlanStatus
    INFEASIBLE: BodyPlanStatus

class LegTarget:
    stance: bool
    foot_W: npt.NDArray[np.float64]
    target_W: npt.NDArray[np.float64]
    t_liftoff: float
    t_touchdown: float

class BodyPlannerOutput:
    status: BodyPlanStatus
    solve_status: str
    knots: npt.NDArray[np.float64]
    reference: BodyState
    feet: list[LegTarget]
    conflicts: int
    next_violation: float
    iterations: int
    solves: int
    total_us: float

class BodyPlanner:
    def __init__(self, plan: Plan, horizon: int = ...) -> None: ...
    def update(self, state: BodyState, now: float, height_offset: float = ..., pitch_offset: float = ...) -> BodyPlannerOutput: ...
    def start_state(self) -> BodyState: ...
    def interpolate(self, t: float) -> BodyState: ...
    def reset(self) -> None: ...
    end_time: float
    desired_hip_height: float

def plan(robot: Union[None, Robot, PathLike] = ..., stairs: Union[None, Stairs, dict[str, Any], PathLike, Perception] = ...,
         **options: Any) -> Plan: ...
def validate(plan: Union[Plan, PathLike], robot: Union[None, Robot, PathLike] = ...) -> dict[str, Any]: ...
def simulate(plan: Plan, settings: Optional[dict[str, float]] = ..., **kwargs: float) -> dict[str, Any]: ...
def sweep(robot: Union[None, Robot, PathLike] = ..., rise: Axis = ..., run: Axis = ..., nosing: Axis = ...,
          steps: Axis = ..., directions: Union[str, Sequence[str]] = ..., threads: int = ...,
          progress: Optional[Callable[[int, int], None]] = ..., as_array: bool = ...,
          **options: Any) -> Union[list[dict[str, Any]], np.ndarray]: ...
def design_gait(rise: float = ..., run: float = ..., max_leg_length: float = ..., body_length: float = ...,
                body_width: float = ..., buffer: float = ..., hip_clearance: Optional[float] = ...) -> dict[str, Any]: ...
def read_point_cloud(path: PathLike) -> npt.NDArray[np.float64]: ...
def perceive(cloud: Union[PathLike, npt.ArrayLike], direction: str = ..., facing: str = ...) -> Perception: ...
def stairs_from_footfalls(footfalls: Union[PathLike, Iterable[Sequence[Any]]]) -> list[dict[str, Any]]: ...
