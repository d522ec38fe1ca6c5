#!/usr/bin/env bash
# The whole test suite (CI: .ci/run). Installs what is missing, builds into build/ and
# runs every test with ctest; then the whole suite again under AddressSanitizer +
# UndefinedBehaviorSanitizer (clang, build-asan: scripts/asan.sh), the concurrency and
# pipeline tests under ThreadSanitizer against a TSan-built oneTBB (build-tsan:
# scripts/tsan.sh), and every libFuzzer target for LCCP_FUZZ_SECONDS (60) seconds
# (scripts/fuzz.sh). Prints the time each step took.
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
# One fuzz target at a time: two at once on this 2-vCPU machine ran each at half its
# rate (config 455k -> 231k inputs in 60 s), which would halve the fuzzing.
for source in tests/fuzz/fuzz_*.cpp; do
  target=$(basename "$source" .cpp)
  target=${target#fuzz_}
  step "fuzz $target" bash scripts/fuzz.sh "$target" "${LCCP_FUZZ_SECONDS:-60}"
done
