#!/usr/bin/env bash
# Re-makes the bundled recordings with `lccp record` from the virtual sensor.
# Needs a build (scripts/build.sh) and, for the real frames, the mOSD test
# scenes in ../shared/data/mOSD/test (read-only data beside the checkout).
set -euo pipefail
cd "$(dirname "$0")/.."
lccp=build/lccp
mosd=${MOSD_DIR:-../shared/data/mOSD/test}

# Real frames: the 62 organized (640x480) mOSD test scenes, one per frame, in
# scene-number order (the virtual sensor reads a folder in file-name order).
scenes=$(mktemp -d)
trap 'rm -rf "$scenes"' EXIT
for cloud in "$mosd"/test*.pcd; do
  if head -c 400 "$cloud" | grep -aq '^HEIGHT 480'; then
    number=$(basename "$cloud" .pcd); number=${number#test}
    ln -s "$(realpath "$cloud")" "$scenes/$(printf 'test%02d.pcd' "$number")"
  fi
done
"$lccp" record --uri "virtual://clouds?path=$scenes" -o recordings/mosd_scenes.oni --frames 62

# The animated synthetic table-top scene (seed 1), its first 2 seconds.
"$lccp" record --uri "virtual://synthetic" -o recordings/synthetic_tabletop.oni --frames 60
