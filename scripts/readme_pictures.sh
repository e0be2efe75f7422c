#!/usr/bin/env bash
# Makes the README's two pictures: the viewer page of the default plan in headless Chromium at
# mid-climb (data/readme/viewer.png) and a MuJoCo frame of the same climb rendered offscreen
# (data/readme/mujoco_frame.png). Needs a build (scripts/build.sh) and scripts/setup.sh's chromium
# and ffmpeg.   bash scripts/readme_pictures.sh [BUILD_DIR]
set -euo pipefail
repo="$(cd "$(dirname "$0")/.." && pwd)"
bin="${1:-$repo/build}/bin/stairplan"
out="$repo/data/readme"
work="$(mktemp -d)"
trap 'rm -rf "$work"' EXIT
mkdir -p "$out"
"$bin" plan --out "$work" > /dev/null
"$bin" view "$work/plan.json" --html "$work/view.html"
mid="$(python3 -c "import json; print(round(json.load(open('$work/plan.json'))['duration_s'] / 2, 2))")"
chromium --headless --no-sandbox --disable-gpu --enable-unsafe-swiftshader --hide-scrollbars \
  --window-size=960,540 --user-data-dir="$work/chromium" --screenshot="$out/viewer.png" \
  "file://$work/view.html#t=$mid" 2> /dev/null
# One frame a second of the simulated climb; the README shows the one at mid-climb.
"$bin" simulate "$work/plan.json" --frames "$work/frames" --frame-ms 1000 > /dev/null
frames=("$work"/frames/frame_*.png)
cp "${frames[$(( ${#frames[@]} / 2 ))]}" "$out/mujoco_frame.png"
ls -l "$out"
