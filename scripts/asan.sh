#!/usr/bin/env bash
# AddressSanitizer (with LeakSanitizer) + UndefinedBehaviorSanitizer over the whole
# test suite, built with clang into build-asan together with the libFuzzer targets
# (tests/fuzz; run by scripts/fuzz.sh), so CI compiles the project only once more.
# Any report fails: ASan and UBSan abort the process (tests that run the lccp binary
# see a signal), and the tests fail on it. Suppressions for third-party frames only:
# tests/sanitizers/; UBSan checks the project's code, not the inline code of Debian's
# headers (tests/sanitizers/ubsan-ignore.txt), which ASan still instruments. See
# https://clang.llvm.org/docs/AddressSanitizer.html and
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
# The stress tests that run the lccp binary hundreds of times on mutated .oni files or
# kill it at fifty random moments are left to the release step (scripts/test.sh's
# ctest): under ASan they take 30-100 s each (2026-12-08), and the memory safety they
# probe is what the fuzz targets check in-process under the same sanitizers
# (scripts/fuzz.sh), .oni replay through OpenNI2 included. So is the 300-frame
# id-stability run of the synthetic scene (101 s under ASan): its code runs under ASan
# in RobotScene.BundledRecordingIdsStayStable's 62 frames. The shorter signal and
# mutation tests (Interrupt's single stops, IoFuzzRegression: 2-10 s each) run here.
stress='KilledAtFiftyRandomMoments|OniMutationTest\.TwoHundred|RobotScene\.WholeScenePeriod'
# As many tests as cores: instrumented tests are CPU- and memory-bound; twice as many
# at once made them slower overall (a fresh clone's ASan tests: 534 s at -j2, 731 s at
# -j4, of which a few minutes shared the machine with another build; with UBSan out of
# Debian's headers, 235 s at -j2 and 240 s at -j4, idle).
ctest --test-dir build-asan --output-on-failure -j"$jobs" -E "$stress" ${LCCP_CTEST_ARGS:-}
