"""The body planner's Update loop from Python: 1,000 cycles at 333 Hz over the shared plan."""
import math

import pytest

import stairplan


def test_update_loop_runs_1000_cycles(default_plan):
    planner = stairplan.BodyPlanner(default_plan)
    state = planner.start_state()
    period = 0.003
    failed = 0  # stale for a solve that failed; stale for the wall-clock budget depends on the machine
    for cycle in range(1000):
        now = cycle * period
        out = planner.update(state, now)
        assert out.status != stairplan.BodyPlanStatus.INFEASIBLE, cycle
        failed += out.status == stairplan.BodyPlanStatus.STALE and out.solve_status != "time_limit"
        ref = out.reference
        assert all(math.isfinite(v) for v in (ref.x, ref.z, ref.pitch, ref.com_shift))
        assert len(out.feet) == 4
        state = planner.interpolate(now + period)  # the robot tracks the plan
    assert failed < 50
    knots = out.knots
    assert knots.shape[1] == 8 and knots[0, 0] == pytest.approx(999 * period)
    assert planner.end_time > 3.0
