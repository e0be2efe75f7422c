# Sourced by scripts/sanitize.sh and scripts/fuzz_long.sh: the sanitizer runtime options, unless the
# caller set its own. The end-to-end test programs append detect_stack_use_after_return=0
# (cmake/Sanitizers.cmake).
export ASAN_OPTIONS=${ASAN_OPTIONS:-detect_leaks=1:strict_string_checks=1:detect_stack_use_after_return=1:check_initialization_order=1}
export LSAN_OPTIONS=${LSAN_OPTIONS:-suppressions=$PWD/scripts/lsan.supp:print_suppressions=0}
export UBSAN_OPTIONS=${UBSAN_OPTIONS:-print_stacktrace=1:halt_on_error=1}
