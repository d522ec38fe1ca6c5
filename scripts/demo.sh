#!/usr/bin/env bash
# The main job: install, build, and replay the bundled real recording
# (recordings/mosd_scenes.oni, 62 Kinect frames) headless at P1.
# Outputs land in out/replay/: per frame a labelled PCD and a colour label
# image, and summary.json for the run.
#   scripts/demo.sh --view [[HOST:]PORT]   the same, watched in a browser: prints the
#   view's URL (default 127.0.0.1:8080), starts when a page opens it, and keeps
#   serving after the run until Ctrl-C.
set -euo pipefail
cd "$(dirname "$0")/.."
view=()
if [[ ${1:-} == --view ]]; then
  view=(--view "${2:-127.0.0.1:8080}" --view-hold)
elif (($#)); then
  echo "usage: scripts/demo.sh [--view [[HOST:]PORT]]" >&2
  exit 2
fi
bash scripts/install-deps.sh
bash scripts/build.sh -DLCCP_BUILD_TESTS=OFF -DLCCP_BUILD_PERF=OFF
./build/lccp replay recordings/mosd_scenes.oni --config config/p1.yaml -o out/replay --save pcd,png --quiet "${view[@]}"
echo "demo: wrote out/replay/frame_*.pcd (labelled clouds, binary_compressed), out/replay/frame_*.png (label images)"
echo "      and out/replay/summary.json; the program is ./build/lccp (see README: Use)"
