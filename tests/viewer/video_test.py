#!/usr/bin/env python3
"""`stairplan simulate --video`: MuJoCo's renderer offscreen (EGL) and ffmpeg make an mp4 of the
default climb that ffprobe reads, as long as the simulated time at the chosen speed (within 5 %),
and a frame of it is not blank.   video_test.py STAIRPLAN_BINARY WORK_DIR
Exit 77 (skipped) when ffmpeg is absent or the binary cannot render offscreen here."""
import json
import os
import shutil
import subprocess
import sys

from png_pixels import read_png

SKIP = 77
SPEED, FRAME_MS = 10.0, 1000  # a 40 s climb in 4 s of video: few frames to render and encode


def main():
    binary, work = sys.argv[1], sys.argv[2]
    if shutil.which("ffmpeg") is None or shutil.which("ffprobe") is None:
        print("SKIP: ffmpeg is not installed (scripts/setup.sh installs it)")
        return SKIP
    shutil.rmtree(work, ignore_errors=True)
    os.makedirs(work)
    r = subprocess.run([binary, "plan", "--out", work], capture_output=True, text=True, timeout=300)
    assert r.returncode == 0, r.stderr
    video = os.path.join(work, "climb.mp4")
    r = subprocess.run([binary, "simulate", os.path.join(work, "plan.json"), "--video", video, "--frame-ms", str(FRAME_MS),
                        "--video-speed", str(SPEED), "--json"], capture_output=True, text=True, timeout=600)
    if "offscreen rendering:" in r.stderr:
        print("SKIP: " + r.stderr.strip())
        return SKIP
    assert r.returncode == 0, r.stderr
    outcome = json.loads(r.stdout)
    simulated = outcome["sim_time_s"] / outcome["time_scale"]  # on the plan's clock, settling and holding included
    probe = subprocess.run(["ffprobe", "-v", "error", "-show_entries", "format=duration", "-of", "csv=p=0", video],
                           capture_output=True, text=True, timeout=60)
    duration = float(probe.stdout)
    expected = simulated / SPEED
    print(f"video {duration:.2f} s for {simulated:.2f} s simulated at speed {SPEED:g} ({expected:.2f} s expected), "
          f"{outcome['video']['frames']} frames")
    assert abs(duration - expected) <= 0.05 * expected, (duration, expected)

    frame = os.path.join(work, "middle.png")
    subprocess.run(["ffmpeg", "-v", "error", "-y", "-ss", f"{0.5 * duration:.2f}", "-i", video, "-frames:v", "1",
                    "-vf", "scale=320:-2", frame], check=True, timeout=60)
    pixels = [p for row in read_png(frame) for p in row]
    # Not blank: many colours, none covering most of the picture, and the robot's blue present.
    counts = {}
    for p in pixels:
        key = (p[0] // 16, p[1] // 16, p[2] // 16)
        counts[key] = counts.get(key, 0) + 1
    robot = sum(1 for r_, g, b in pixels if b > 120 and b > r_ + 60 and b > g + 30)
    print(f"middle frame: {len(counts)} colour bins, largest {max(counts.values()) / len(pixels):.0%}, {robot} robot pixels")
    assert len(counts) > 20 and max(counts.values()) < 0.8 * len(pixels), "the frame is blank"
    assert robot > 200, "the robot is not in the frame"
    return 0


if __name__ == "__main__":
    sys.exit(main())
