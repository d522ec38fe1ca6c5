#!/usr/bin/env bash
# AddressSanitizer (with LeakSanitizer) + UndefinedBehaviorSanitizer over the whole
# test suite, built with clang into build-asan together with the libFuzzer targets
# (tests/fuzz; run by scripts/fuzz.sh), so CI compiles the project only once more.
# Any report fails: ASan and UBSan abort the process (tests that run the lccp binary
# see a signal), and the tests fail on it. Suppressions for third-party frames only:
# tests/sanitizers/. See https://clang.llvm.org/docs/AddressSanitizer.html and
# https://clang.llvm.org/docs/UndefinedBehaviorSanitizer.html.
set -euo pipefail
cd "$(dirname "$0")/.."
source tests/sanitizers/options.sh
jobs=$(( $(nproc) < 2 ? $(nproc) : 2 ))
# No Python module: an instrumented module cannot load into Debian's uninstrumented
# python3 (the sanitizer runtime must come first); its C++ code is the library's.
cmake -S . -B build-asan -DCMAKE_BUILD_TYPE=Release -DCMAKE_CXX_COMPILER=clang++-14 \
  -DLCCP_SANITIZE=address,undefined -DLCCP_BUILD_FUZZERS=ON -DLCCP_BUILD_PYTHON=OFF \
  -DLCCP_BUILD_TESTS=ON -DLCCP_BUILD_PERF=OFF -DLCCP_TEST_TIMEOUT=900 -DLCCP_PRECOMPILE_HEADERS=ON >/dev/null
# LCCP_ASAN_TARGET: build only that target (scripts/fuzz.sh); LCCP_ASAN_BUILD_ONLY=1: no tests.
cmake --build build-asan -j"$jobs" ${LCCP_ASAN_TARGET:+--target "$LCCP_ASAN_TARGET"}
[[ ${LCCP_ASAN_BUILD_ONLY:-0} == 1 ]] && exit 0
# The stress tests that run the lccp binary hundreds of times on mutated inputs or
# kill it at random moments are left to the release step (scripts/test.sh's ctest):
# under ASan each run is several times slower (they took 60-300 s each here), and
# the memory safety they probe is what the fuzz targets check in-process under the
# same sanitizers (scripts/fuzz.sh), .oni replay through OpenNI2 included. So is the
# 300-frame id-stability run of the synthetic scene (49 s in the release step on a
# loaded machine, over the 900 s limit under ASan there): its code runs under ASan in
# RobotScene.BundledRecordingIdsStayStable's 62 frames.
stress='Interrupt\.|OniMutationTest\.TwoHundred|IoFuzzRegression\.|RobotScene\.WholeScenePeriod'
# As many tests as cores: instrumented tests are CPU- and memory-bound; twice as many
# at once made them slower overall (a fresh clone's ASan tests: 534 s at -j2, 731 s at
# -j4, of which a few minutes shared the machine with another build).
ctest --test-dir build-asan --output-on-failure -j"$jobs" -E "$stress" ${LCCP_CTEST_ARGS:-}
