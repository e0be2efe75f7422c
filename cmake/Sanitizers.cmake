# Hardening builds (issue #9): AddressSanitizer + UndefinedBehaviorSanitizer for the whole project, and
# libFuzzer targets (tests/fuzz). Both need clang; scripts/sanitize.sh configures build-asan with both.
option(STAIRPLAN_SANITIZE "Build everything with -fsanitize=address,undefined (clang)" OFF)
option(STAIRPLAN_FUZZ "Build the libFuzzer targets in tests/fuzz (clang; implies coverage instrumentation)" OFF)

if(STAIRPLAN_SANITIZE OR STAIRPLAN_FUZZ)
  if(NOT CMAKE_CXX_COMPILER_ID MATCHES "Clang")
    message(FATAL_ERROR "STAIRPLAN_SANITIZE/STAIRPLAN_FUZZ need clang (configure with -DCMAKE_CXX_COMPILER=clang++-14)")
  endif()
  # Every finding stops the program: a sanitizer report is a failure, never a warning in a log.
  add_compile_options(-fsanitize=address,undefined -fno-sanitize-recover=all -fno-omit-frame-pointer)
  add_link_options(-fsanitize=address,undefined -fno-sanitize-recover=all)
endif()

if(STAIRPLAN_FUZZ)
  # Coverage feedback for libFuzzer in every library; only the fuzz targets link libFuzzer's main.
  add_compile_options(-fsanitize=fuzzer-no-link)
endif()
