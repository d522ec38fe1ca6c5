#!/usr/bin/env bash
# ThreadSanitizer over the concurrency tests (the lock-free union-find, the
# pipeline's admission gate, the background stream and push source), the
# pipeline tests (the oneTBB flow graph) and
# every stage's parallel loops on 2 and 4 threads, both supervoxel growths, on
# the small synthetic scene (the mOSD frames reach them through the pipeline).
# TSan only sees the synchronization of code built with -fsanitize=thread, so
# oneTBB itself is built from third_party/oneTBB-2021.8.0 with oneTBB's own
# TBB_SANITIZE=thread option (once, into build-tsan/onetbb; reused after) and
# the tests are built against it instead of Debian's libtbb. Any report fails
# the step. See https://clang.llvm.org/docs/ThreadSanitizer.html and
# third_party/README.md.
set -euo pipefail
cd "$(dirname "$0")/.."
jobs=$(( $(nproc) < 2 ? $(nproc) : 2 ))
onetbb_src=third_party/oneTBB-2021.8.0
onetbb=build-tsan/onetbb

# 1. oneTBB with TSan (about a minute on 2 cores), installed into build-tsan/onetbb.
if [[ ! -f $onetbb/lib/cmake/TBB/TBBConfig.cmake ]]; then
  echo "tsan: building oneTBB 2021.8.0 with -fsanitize=thread into $onetbb"
  cmake -S "$onetbb_src" -B build-tsan/onetbb-build -DCMAKE_BUILD_TYPE=RelWithDebInfo \
    -DTBB_TEST=OFF -DTBB_EXAMPLES=OFF -DTBB_STRICT=OFF -DTBB_SANITIZE=thread -DTBBMALLOC_BUILD=OFF \
    -DTBB_DISABLE_HWLOC_AUTOMATIC_SEARCH=ON -DCMAKE_INSTALL_PREFIX="$PWD/$onetbb" \
    -DCMAKE_CXX_FLAGS_RELWITHDEBINFO="-O2 -g1 -DNDEBUG" \
    -DCMAKE_INSTALL_LIBDIR=lib >/dev/null
  cmake --build build-tsan/onetbb-build -j"$jobs"
  cmake --install build-tsan/onetbb-build >/dev/null
fi

# 2. The tests, built with TSan against that oneTBB (TBB_DIR wins over the system's).
cmake -S . -B build-tsan -DCMAKE_BUILD_TYPE=RelWithDebInfo -DLCCP_SANITIZE_THREADS=ON \
  -DTBB_DIR="$PWD/$onetbb/lib/cmake/TBB" -DCMAKE_PREFIX_PATH="$PWD/$onetbb" \
  -DLCCP_BUILD_TESTS=ON -DLCCP_BUILD_PERF=OFF -DLCCP_BUILD_PYTHON=OFF >/dev/null
cmake --build build-tsan -j"$jobs" --target lccp_concurrency_tests

# 3. Run them. The test binary must load the TSan oneTBB, not Debian's; both
# paths are resolved, as the checkout may be reached through a symlink.
tests=build-tsan/tests/lccp_concurrency_tests
loaded=$(ldd "$tests" | awk '$1 ~ /^libtbb\.so/ { print $3 }')
if [[ -z $loaded || $(readlink -f "$loaded") != $(readlink -f "$onetbb/lib/$(basename "$loaded")") ]]; then
  echo "tsan: $tests is not linked against $onetbb" >&2
  ldd "$tests" | grep -i tbb >&2
  exit 1
fi
# In two halves at once (gtest's sharding: every test runs in exactly one), each
# half's log printed after it: 72 s against 92 s in one process on this 2-core machine.
export TSAN_OPTIONS="halt_on_error=1 exitcode=66 second_deadlock_stack=1 ${TSAN_OPTIONS:-}"
filter='FrameAdmission.*:UnionFind.*:Pipeline*:BackgroundStream.*:PushSource.*:Threads/Determinism.*/box_on_table_*-*_1threads'
logs=$(mktemp -d "${TMPDIR:-/tmp}/lccp_tsan.XXXXXX")
trap 'rm -rf "$logs"' EXIT
for shard in 0 1; do
  GTEST_TOTAL_SHARDS=2 GTEST_SHARD_INDEX=$shard "$tests" --gtest_filter="$filter" >"$logs/$shard.log" 2>&1 &
done
failed=0
for shard in 0 1; do
  wait -n || failed=1
done
cat "$logs/0.log" "$logs/1.log"
exit "$failed"
