"""stairplan: optimisation-centric stair planning for legged robots.

The C++ library's Python bindings (pybind11). Start with ``stairplan.plan()``; see
``help(stairplan.plan)``, ``stairplan.sweep``, ``stairplan.BodyPlanner`` and ``stairplan.optim``.
"""
import sys as _sys

from ._stairplan import (  # noqa: F401
    BodyPlanner, BodyPlannerOutput, BodyPlanStatus, BodyState, ConstrainedMap, FieldError, LegTarget,
    Perception, Plan, Robot, Stairs, __version__, design_gait, optim, perceive, plan, read_point_cloud,
    schema_version, simulate, stairs_from_footfalls, sweep, validate,
)

# `import stairplan.optim` works as well as `stairplan.optim`.
_sys.modules[__name__ + ".optim"] = optim

__all__ = [
    "BodyPlanner", "BodyPlannerOutput", "BodyPlanStatus", "BodyState", "ConstrainedMap", "FieldError",
    "LegTarget", "Perception", "Plan", "Robot", "Stairs", "design_gait", "optim", "perceive", "plan",
    "read_point_cloud", "schema_version", "simulate", "stairs_from_footfalls", "sweep", "validate",
]
