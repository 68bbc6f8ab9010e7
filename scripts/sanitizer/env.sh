# Sourced by scripts/test.sh --sanitize and scripts/fuzz.sh: how ASan, UBSan and LSan report.
# Every report from our code is fatal; lsan.supp ignores only leaks inside the OpenCL ICD loader
# and PoCL (and the LLVM it embeds), which the suite cannot fix. A variable already set wins.
sanitizer_dir="$(cd "$(dirname "${BASH_SOURCE[0]}")" && pwd)"
export ASAN_OPTIONS="${ASAN_OPTIONS:-abort_on_error=1:detect_leaks=1:strict_string_checks=1:detect_stack_use_after_return=1:check_initialization_order=1}"
export UBSAN_OPTIONS="${UBSAN_OPTIONS:-print_stacktrace=1:halt_on_error=1}"
export LSAN_OPTIONS="${LSAN_OPTIONS:-suppressions=$sanitizer_dir/lsan.supp:print_suppressions=0}"
# PoCL's default pthread device keeps worker threads that LSan's stop-the-world tracer sometimes
# crashes on at exit ("Tracer caught signal 11", about half the runs of an OpenCL test); its
# single-threaded basic device runs the same kernels and exits cleanly.
export POCL_DEVICES="${POCL_DEVICES:-basic}"
# Sanitized code runs 2-5x slower: the forked batches of the option tests and ctest allow more.
export TERRAWEAVE_FORK_BATCH_SECONDS="${TERRAWEAVE_FORK_BATCH_SECONDS:-300}"
