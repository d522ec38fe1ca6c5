#!/usr/bin/env bash
# Runs one libFuzzer target for a while:  scripts/fuzz.sh TARGET SECONDS
# TARGET is one of tests/fuzz/fuzz_<TARGET>.cpp (pcd, ply, config, uri, oni, view). The
# target is built in build-asan (clang, ASan + UBSan; scripts/asan.sh) if needed and
# started on a temporary copy of its seed corpus tests/fuzz/corpus/TARGET, so the
# repository is not modified. A crash, a sanitizer report, an exception other than
# lccp::Error, a leak, a timeout or running out of memory is a finding: the script
# exits non-zero and prints where the input that caused it was saved.
# libFuzzer's options: https://llvm.org/docs/LibFuzzer.html#options
set -euo pipefail
cd "$(dirname "$0")/.."
usage="usage: scripts/fuzz.sh TARGET SECONDS (TARGET: $(ls tests/fuzz/fuzz_*.cpp | sed 's#.*/fuzz_##; s#\.cpp##' | tr '\n' ' '))"
target=${1:?$usage}
seconds=${2:?$usage}
[[ -f tests/fuzz/fuzz_$target.cpp ]] || { echo "$usage" >&2; exit 2; }

LCCP_ASAN_BUILD_ONLY=1 LCCP_ASAN_TARGET="fuzz_$target" bash scripts/asan.sh
source tests/sanitizers/options.sh
binary=$PWD/build-asan/tests/fuzz/fuzz_$target
findings=$PWD/build-asan/fuzz-findings/$target
mkdir -p "$findings"
work=$(mktemp -d "${TMPDIR:-/tmp}/lccp_fuzz_$target.XXXXXX")
trap 'rm -rf "$work"' EXIT
mkdir "$work/corpus"
cp -r "tests/fuzz/corpus/$target/." "$work/corpus/"

log=$findings/last-run.log
start=$(date +%s)
set +e
# -timeout: one input running this long is a hang; generous for a loaded machine.
(cd "$work" && "$binary" -max_total_time="$seconds" -timeout=30 -rss_limit_mb=4096 -print_final_stats=1 \
   -artifact_prefix="$findings/" "$work/corpus") >"$log" 2>&1
status=$?
set -e
runs=$(grep -o 'stat::number_of_executed_units: *[0-9]*' "$log" | grep -o '[0-9]*$' || echo 0)
elapsed=$(( $(date +%s) - start ))
echo "fuzz $target: ${runs:-0} inputs in ${elapsed} s ($(( ${runs:-0} / (elapsed > 0 ? elapsed : 1) ))/s), corpus $(ls "$work/corpus" | wc -l) files; log $log"
if (( status != 0 )); then
  input=$(grep -o "Test unit written to [^ ]*" "$log" | tail -1 | sed 's/Test unit written to //')
  echo "fuzz $target: FINDING (exit $status). The input: ${input:-see $log}" >&2
  echo "  reproduce: $binary ${input:-<input>}" >&2
  grep -m1 -E "ERROR: |runtime error:|terminate called|==ERROR" "$log" >&2 || tail -20 "$log" >&2
  exit 1
fi
