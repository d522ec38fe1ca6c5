#!/usr/bin/env bash
# The whole test suite (CI: .ci/run). Installs what is missing, builds into build/ and
# runs every test with ctest; then the whole suite again under AddressSanitizer +
# UndefinedBehaviorSanitizer (clang, build-asan: scripts/asan.sh), the concurrency and
# pipeline tests under ThreadSanitizer against a TSan-built oneTBB (build-tsan:
# scripts/tsan.sh), and every libFuzzer target for LCCP_FUZZ_SECONDS (60) seconds
# (scripts/fuzz.sh), as many at once as there are cores (a fuzzer uses one), so each
# still gets a core for its whole time. Prints the time each step took.
set -euo pipefail
cd "$(dirname "$0")/.."
times=()
step() {
  local name=$1 start=$SECONDS
  shift
  echo "=== test.sh: $name"
  "$@"
  times+=("$(printf '%-12s %5d s' "$name" $((SECONDS - start)))")
  echo "=== test.sh: $name took $((SECONDS - start)) s"
}
summary() {
  echo "=== test.sh: step times"
  printf '  %s\n' "${times[@]}"
}
trap summary EXIT

step install bash scripts/install-deps.sh
step build bash scripts/build.sh -DLCCP_BUILD_TESTS=ON -DLCCP_BUILD_PERF=OFF
# Twice as many tests as cores: tests wait on sensors, timers and child processes for
# part of their time, which the other tests then use.
step ctest ctest --test-dir build --output-on-failure -j"$((2 * $(nproc)))"
step asan bash scripts/asan.sh
step tsan bash scripts/tsan.sh
# The fuzz targets, `nproc` at a time (each built by asan.sh above); any finding fails.
fuzz_together() {
  local pids=() target failed=0
  for target in "$@"; do
    LCCP_FUZZ_BUILT=1 bash scripts/fuzz.sh "$target" "${LCCP_FUZZ_SECONDS:-60}" &
    pids+=($!)
  done
  for pid in "${pids[@]}"; do wait "$pid" || failed=1; done
  return "$failed"
}
targets=($(ls tests/fuzz/fuzz_*.cpp | sed 's#.*/fuzz_##; s#\.cpp$##'))
for ((i = 0; i < ${#targets[@]}; i += $(nproc))); do
  group=("${targets[@]:i:$(nproc)}")
  step "fuzz ${group[*]}" fuzz_together "${group[@]}"
done
