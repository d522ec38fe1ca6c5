#!/usr/bin/env bash
# ThreadSanitizer over the concurrency tests that TSan can see through: the
# lock-free union-find hammered by std::threads and the pipeline's admission
# gate between the capture thread and the graph. Tests that run on TBB tasks
# are left out: Debian's libtbb is not built with TSan, so every task hand-off
# would be reported (measured: 80-95 false reports on a race-free toy; see
# perf/RESULTS.md). Any report fails the step.
set -euo pipefail
cd "$(dirname "$0")/.."
cmake -S . -B build-tsan -DCMAKE_BUILD_TYPE=RelWithDebInfo -DLCCP_SANITIZE_THREADS=ON \
  -DLCCP_BUILD_TESTS=ON -DLCCP_BUILD_PERF=OFF >/dev/null
cmake --build build-tsan -j"$(nproc)" --target lccp_concurrency_tests
TSAN_OPTIONS="halt_on_error=1 exitcode=66 second_deadlock_stack=1" \
  build-tsan/tests/lccp_concurrency_tests \
  --gtest_filter='FrameAdmission.*:UnionFind.*-UnionFind.ConcurrentUnionsWithTbbMatchBfs:UnionFind.ChainsUnitedFromBothEnds'
