#!/usr/bin/env python3
"""What calling BodyPlanner.update() from Python costs over the same C++ Update.

    PYTHONPATH=build/python nice -n 10 /usr/bin/python3 bench/python_update_overhead.py [--passes N]

Warm sequence against warm sequence: one traversal of the default stairs fills the planner's
caches, then each further traversal times every cycle from Python (perf_counter around the call)
and reads the C++ Update's own time of the same call (BodyPlannerOutput.total_us, measured inside
Update). The difference is the binding: argument conversion, dispatch and the returned reference.
"""
import argparse
import time

import numpy as np

import stairplan

PERIOD = 0.003


def main():
    parser = argparse.ArgumentParser()
    parser.add_argument("--passes", type=int, default=3)
    args = parser.parse_args()
    planner = stairplan.BodyPlanner(stairplan.plan())
    overhead, inner = [], []
    for p in range(args.passes + 1):
        planner.reset()
        state, now = planner.start_state(), 0.0
        while now <= planner.end_time:
            t0 = time.perf_counter()
            out = planner.update(state, now)
            seen = (time.perf_counter() - t0) * 1e6
            if p > 0 and out.solves == 1:  # the first pass and warm-up cycles fill caches
                overhead.append(seen - out.total_us)
                inner.append(out.total_us)
            state = planner.interpolate(now + PERIOD)
            now += PERIOD
    o = np.array(overhead)
    print(f"{len(o)} warm cycles; C++ Update p50 {np.median(inner):.1f} us")
    print(f"Python overhead per update() [us]: p50 {np.median(o):.2f}  p90 {np.percentile(o, 90):.2f}  "
          f"p99 {np.percentile(o, 99):.2f}  mean {o.mean():.2f}")


if __name__ == "__main__":
    main()
