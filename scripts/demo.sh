#!/usr/bin/env bash
# The main job: install, build, and segment the bundled real scene at P1.
# Outputs land in out/: a labelled PCD and a colour label image.
set -euo pipefail
cd "$(dirname "$0")/.."
bash scripts/install-deps.sh
bash scripts/build.sh -DLCCP_BUILD_TESTS=OFF -DLCCP_BUILD_PERF=OFF
mkdir -p out
./build/lccp segment tests/data/mosd_test34.pcd --config config/p1.yaml \
  -o out/mosd_test34_labels.pcd --png out/mosd_test34_labels.png
echo "demo: wrote out/mosd_test34_labels.pcd and out/mosd_test34_labels.png"
