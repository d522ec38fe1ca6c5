#!/usr/bin/env bash
# The whole test suite: install, build, run every test with ctest, then the
# concurrency tests under ThreadSanitizer (scripts/tsan.sh).
set -euo pipefail
cd "$(dirname "$0")/.."
bash scripts/install-deps.sh
bash scripts/build.sh -DLCCP_BUILD_TESTS=ON -DLCCP_BUILD_PERF=OFF
ctest --test-dir build --output-on-failure -j"$(nproc)"
# The concurrency tests again, under ThreadSanitizer.
bash scripts/tsan.sh
