#!/usr/bin/env python3
"""A 333 Hz control loop in Python over the body planner (as examples/control_loop.cpp in C++).

    PYTHONPATH=build/python /usr/bin/python3 examples/python/control_loop.py [up|down]

Plans the default stairs once, then calls BodyPlanner.update() every 3 ms of plan time for the
whole flight, the robot tracking the plan perfectly, and prints the latency percentiles of the
call as seen from Python beside the C++ Update's own time.
"""
import sys
import time

import numpy as np

import stairplan

PERIOD = 0.003  # [s]


def traverse(planner):
    planner.reset()
    state = planner.start_state()
    seen, inner, stale = [], [], 0
    now = 0.0
    while now <= planner.end_time:
        t0 = time.perf_counter()
        out = planner.update(state, now)
        seen.append((time.perf_counter() - t0) * 1e6)
        inner.append(out.total_us)
        stale += out.status == stairplan.BodyPlanStatus.STALE
        if out.status == stairplan.BodyPlanStatus.INFEASIBLE:
            raise SystemExit(f"infeasible at t = {now:.3f} s")
        state = planner.interpolate(now + PERIOD)
        now += PERIOD
    return np.array(seen[1:]), np.array(inner[1:]), stale  # the first call is the warm-up


def main():
    direction = sys.argv[1] if len(sys.argv) > 1 else "up"
    plan = stairplan.plan(direction=direction)
    if plan.status != "ok":
        raise SystemExit(f"no plan: {plan.status_reason}")
    planner = stairplan.BodyPlanner(plan)
    traverse(planner)  # fills the planner's caches of bounds
    seen, inner, stale = traverse(planner)
    print(f"control loop: {len(seen) + 1} cycles at {1 / PERIOD:.0f} Hz over {planner.end_time:.2f} s, {stale} stale")
    for label, v in (("update() from Python", seen), ("C++ Update inside", inner)):
        p50, p90, p99 = np.percentile(v, [50, 90, 99])
        print(f"  {label:22s} [us]: p50 {p50:.1f}  p90 {p90:.1f}  p99 {p99:.1f}  max {v.max():.1f}")


if __name__ == "__main__":
    main()
