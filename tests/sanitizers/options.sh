# Sourced by scripts/asan.sh and scripts/fuzz.sh: the runtime options of
# AddressSanitizer, LeakSanitizer and UndefinedBehaviorSanitizer (the flags are
# documented in https://github.com/google/sanitizers/wiki/SanitizerCommonFlags and
# https://github.com/google/sanitizers/wiki/AddressSanitizerFlags).
# abort_on_error: a report kills the process with SIGABRT, which tests that run the
# lccp binary see as a signal (a plain exit code 1 would look like an lccp::Error).
sanitizers_dir="$(cd "$(dirname "${BASH_SOURCE[0]}")" && pwd)"
export ASAN_OPTIONS="abort_on_error=1:detect_leaks=1:strict_string_checks=1:detect_stack_use_after_return=1:check_initialization_order=1:strict_init_order=1${ASAN_OPTIONS:+:$ASAN_OPTIONS}"
export LSAN_OPTIONS="suppressions=$sanitizers_dir/lsan.supp:print_suppressions=0${LSAN_OPTIONS:+:$LSAN_OPTIONS}"
export UBSAN_OPTIONS="abort_on_error=1:halt_on_error=1:print_stacktrace=1:suppressions=$sanitizers_dir/ubsan.supp${UBSAN_OPTIONS:+:$UBSAN_OPTIONS}"
