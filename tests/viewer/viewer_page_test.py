#!/usr/bin/env python3
"""`stairplan view` in a browser: the page for the default plan and for a plan with a foot moved off
its tread opens in headless Chromium without console messages; the robot (its blue) is drawn at
t = 0 and mid-plan, the two pictures differ, the valid plan shows no violation marker (magenta)
and the failing plan shows one.   viewer_page_test.py STAIRPLAN_BINARY WORK_DIR
Exit 77 (skipped) when chromium is absent or the binary has no three.js."""
import json
import os
import shutil
import subprocess
import sys

from png_pixels import read_png

SKIP = 77
WIDTH, HEIGHT = 600, 360
SIDE_PANEL, TOP_BAR = 240, 70  # the page's controls and legend (the legend has both colours)


def run(args, **kw):
    return subprocess.run(args, stdout=subprocess.PIPE, stderr=subprocess.PIPE, text=True, timeout=120, **kw)


def canvas_pixels(rows):
    return [p for row in rows[TOP_BAR:] for p in row[:len(row) - SIDE_PANEL]]


def is_robot(p):
    r, g, b = p
    return b > 120 and b > r + 60 and b > g + 40


def is_marker(p):
    r, g, b = p
    return r > 200 and g < 80 and b > 150


def screenshots(chromium, shots, work):
    """Takes the screenshots in parallel; returns the console lines Chromium logged for each."""
    procs = []
    for url, png in shots:
        args = [chromium, "--headless", "--no-sandbox", "--disable-gpu", "--enable-unsafe-swiftshader",
                "--hide-scrollbars", f"--window-size={WIDTH},{HEIGHT}", "--enable-logging=stderr", "--v=0",
                f"--user-data-dir={work}/chromium-{os.path.basename(png)}", f"--screenshot={png}", url]
        procs.append(subprocess.Popen(args, stdout=subprocess.PIPE, stderr=subprocess.PIPE, text=True))
    console = []
    for proc, (url, png) in zip(procs, shots):
        _, err = proc.communicate(timeout=120)
        assert os.path.exists(png), f"no screenshot of {url}:\n{err[-2000:]}"
        # Chromium's own note on the screenshot's read-back is not the page's.
        console += [line for line in err.splitlines() if ":CONSOLE" in line and "GPU stall due to ReadPixels" not in line]
    return console


def main():
    binary, work = sys.argv[1], sys.argv[2]
    chromium = shutil.which("chromium") or shutil.which("chromium-browser")
    if chromium is None:
        print("SKIP: chromium is not installed (scripts/setup.sh installs it)")
        return SKIP
    shutil.rmtree(work, ignore_errors=True)
    os.makedirs(work)
    plan_dir = os.path.join(work, "plan")
    r = run([binary, "plan", "--out", plan_dir])
    assert r.returncode == 0, r.stderr
    plan_path = os.path.join(plan_dir, "plan.json")
    ok_html = os.path.join(work, "ok.html")
    r = run([binary, "view", plan_path, "--html", ok_html])
    if r.returncode != 0 and "without three.js" in r.stderr:
        print("SKIP: " + r.stderr.strip())
        return SKIP
    assert r.returncode == 0, r.stderr

    # A foot moved 12 cm along its flight: off its tread; the validator says where and when.
    plan = json.load(open(plan_path))
    step = plan["footsteps"][len(plan["footsteps"]) // 4]
    step["x"] += 0.12
    bad_path = os.path.join(work, "bad.json")
    json.dump(plan, open(bad_path, "w"))
    report_path = os.path.join(work, "report.json")
    r = run([binary, "validate", bad_path, "--json"])
    assert r.returncode == 3, (r.returncode, r.stderr)
    open(report_path, "w").write(r.stdout)
    first = json.loads(r.stdout)["violations"][0]
    bad_html = os.path.join(work, "bad.html")
    r = run([binary, "view", bad_path, "--validation", report_path, "--html", bad_html])
    assert r.returncode == 0, r.stderr
    assert "INVALID" in open(bad_html).read(), "the failing plan's title does not say INVALID"

    mid = 0.5 * plan["body"][-1]["t"]
    shots = [(f"file://{ok_html}#t=0", os.path.join(work, "ok_0.png")),
             (f"file://{ok_html}#t={mid:.2f}", os.path.join(work, "ok_mid.png")),
             (f"file://{bad_html}#t={first['t']:.2f}", os.path.join(work, "bad.png"))]
    console = screenshots(chromium, shots, work)
    assert not console, "console messages:\n" + "\n".join(console)

    ok0, okmid, bad = (canvas_pixels(read_png(png)) for _, png in shots)
    robot0, robotmid = sum(map(is_robot, ok0)), sum(map(is_robot, okmid))
    changed = sum(a != b for a, b in zip(ok0, okmid))
    markers_ok, markers_bad = sum(map(is_marker, ok0)), sum(map(is_marker, bad))
    print(f"robot pixels t=0 {robot0}, mid {robotmid}; pixels changed {changed}; "
          f"marker pixels valid plan {markers_ok}, failing plan {markers_bad} ({first['kind']} at t={first['t']})")
    assert robot0 > 200 and robotmid > 200, "the robot is not drawn"
    assert changed > 500, "the picture at mid-plan equals the one at t = 0"
    assert markers_ok == 0, "the valid plan shows a violation marker"
    assert markers_bad > 30, "the failing plan shows no violation marker"
    return 0


if __name__ == "__main__":
    sys.exit(main())
