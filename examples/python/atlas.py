#!/usr/bin/env python3
"""A feasibility atlas: two robots swept over rise x run, one heatmap each, into a PNG.

    PYTHONPATH=build/python /usr/bin/python3 examples/python/atlas.py [--out atlas.png] [--size N] [--threads K]
        [--robot2 URDF]

Each cell is planned and validated as `stairplan sweep` does. The default grid is 3 x 3 per robot
so that it runs in well under a minute; --size 20 is the CLI's full sweep.
"""
import argparse
import os
import sys

import matplotlib

matplotlib.use("Agg")  # no display needed
import matplotlib.pyplot as plt  # noqa: E402
import numpy as np  # noqa: E402

import stairplan  # noqa: E402

STATUS_CODES = {"valid": 3, "invalid": 2, "infeasible": 1, "bad_stairs": 0}


def default_second_robot():
    here = os.path.dirname(os.path.abspath(__file__))
    path = os.path.join(here, "..", "..", "..", "shared", "data", "robots", "anymal_c.urdf")
    return path if os.path.exists(path) else None


def sweep(robot, size, threads):
    def progress(done, total):
        print(f"\r  {done}/{total}", end="" if done < total else "\n", file=sys.stderr, flush=True)
    rows = stairplan.sweep(robot=robot, rise=(0.12, 0.22, size), run=(0.22, 0.34, size), threads=threads,
                           progress=progress, as_array=True)
    grid = np.array([STATUS_CODES[s] for s in rows["status"]]).reshape(size, size)  # rise-major order
    return rows, grid


def main():
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--out", default="atlas.png")
    parser.add_argument("--size", type=int, default=3, help="points per axis (default 3)")
    parser.add_argument("--threads", type=int, default=os.cpu_count() or 1)
    parser.add_argument("--robot2", default=default_second_robot(), help="second robot's URDF (default ANYmal C)")
    args = parser.parse_args()
    robots = [("stairbot (built in)", None)]
    if args.robot2:
        robots.append((os.path.splitext(os.path.basename(args.robot2))[0], stairplan.Robot(args.robot2)))
    fig, axes = plt.subplots(1, len(robots), figsize=(5 * len(robots), 4.2), squeeze=False)
    cmap = matplotlib.colors.ListedColormap(["#999999", "#d62728", "#ff7f0e", "#2ca02c"])
    for ax, (name, robot) in zip(axes[0], robots):
        print(f"{name}: {args.size} x {args.size} stairs", file=sys.stderr)
        rows, grid = sweep(robot, args.size, args.threads)
        rises, runs = np.unique(rows["rise"]), np.unique(rows["run"])
        half_run = (runs[-1] - runs[0]) / max(args.size - 1, 1) / 2 or 0.005
        half_rise = (rises[-1] - rises[0]) / max(args.size - 1, 1) / 2 or 0.005
        ax.imshow(grid, origin="lower", cmap=cmap, vmin=-0.5, vmax=3.5, aspect="auto",
                  extent=(runs[0] - half_run, runs[-1] + half_run, rises[0] - half_rise, rises[-1] + half_rise))
        ax.set_title(f"{name}: {int((grid == 3).sum())}/{grid.size} valid")
        ax.set_xlabel("run [m]")
        ax.set_ylabel("rise [m]")
    handles = [matplotlib.patches.Patch(color=cmap(v), label=k) for k, v in STATUS_CODES.items()]
    fig.legend(handles=handles, loc="lower center", ncol=4)
    fig.tight_layout(rect=(0, 0.08, 1, 1))
    fig.savefig(args.out, dpi=100)
    print(f"wrote {args.out}")


if __name__ == "__main__":
    main()
