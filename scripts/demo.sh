#!/usr/bin/env bash
# The main job: install, build, and replay the bundled real recording
# (recordings/mosd_scenes.oni, 62 Kinect frames) headless at P1.
# Outputs land in out/replay/: per frame a labelled PCD and a colour label
# image, and summary.json for the run.
set -euo pipefail
cd "$(dirname "$0")/.."
bash scripts/install-deps.sh
bash scripts/build.sh -DLCCP_BUILD_TESTS=OFF -DLCCP_BUILD_PERF=OFF
./build/lccp replay recordings/mosd_scenes.oni --config config/p1.yaml -o out/replay --save pcd,png --quiet
echo "demo: wrote out/replay/frame_*.pcd (labelled clouds, binary_compressed), out/replay/frame_*.png (label images)"
echo "      and out/replay/summary.json; the program is ./build/lccp (see README: Use)"
