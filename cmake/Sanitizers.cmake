# Hardening builds (issue #9): AddressSanitizer + UndefinedBehaviorSanitizer for the whole project, and
# libFuzzer targets (tests/fuzz). Both need clang; scripts/sanitize.sh configures build-asan with both.
option(STAIRPLAN_SANITIZE "Build everything with -fsanitize=address,undefined (clang)" OFF)
option(STAIRPLAN_FUZZ "Build the libFuzzer targets in tests/fuzz (clang; implies coverage instrumentation)" OFF)
# The sanitized build is built from scratch in CI, so it trades incremental rebuilds for a shorter
# first build: each test program compiles as a few unity sources over one shared precompiled header.
option(STAIRPLAN_QUICK_TEST_BUILD "Unity sources and one precompiled header for the test programs" OFF)

if(STAIRPLAN_SANITIZE OR STAIRPLAN_FUZZ)
  if(NOT CMAKE_CXX_COMPILER_ID MATCHES "Clang")
    message(FATAL_ERROR "STAIRPLAN_SANITIZE/STAIRPLAN_FUZZ need clang (configure with -DCMAKE_CXX_COMPILER=clang++-14)")
  endif()
  # Every finding stops the program: a sanitizer report is a failure, never a warning in a log.
  add_compile_options(-fsanitize=address,undefined -fno-sanitize-recover=all -fno-omit-frame-pointer)
  add_link_options(-fsanitize=address,undefined -fno-sanitize-recover=all)
endif()

if(STAIRPLAN_SANITIZE)
  # Tests that take minutes under the sanitizers run fewer samples (tests/sanitized.h).
  add_compile_definitions(STAIRPLAN_SANITIZED)
endif()

# Called by a module's CMakeLists with the sources of its parsers, those a fuzz target reaches
# (tests/fuzz): with STAIRPLAN_FUZZ they, and only they, get libFuzzer's coverage instrumentation,
# compiled on their own (a unity source takes its target's flags). Instrumenting whole libraries
# ran the sanitized test suite, which shares them, 1.4-2x slower; the fuzzers need the feedback of
# the code they parse with, not of the planners. Relative paths are from the calling directory.
function(stairplan_fuzzed_sources module)
  if(NOT STAIRPLAN_FUZZ)
    return()
  endif()
  set(sources "")
  foreach(source IN LISTS ARGN)
    get_filename_component(path "${source}" ABSOLUTE BASE_DIR "${CMAKE_CURRENT_SOURCE_DIR}")
    list(APPEND sources "${path}")
  endforeach()
  set_source_files_properties(${sources} TARGET_DIRECTORY stairplan_${module} PROPERTIES
    COMPILE_OPTIONS -fsanitize=fuzzer-no-link SKIP_UNITY_BUILD_INCLUSION ON)
endfunction()

# Called by stairplan_add_module and for the CLI and the Python module: their sources compiled as a
# few unity sources, for a build from scratch (CI turns it on: scripts/test.sh and
# scripts/sanitize_configure.sh). File-local names must then be unique within each of them.
option(STAIRPLAN_UNITY_BUILD "Compile the module libraries, the CLI and the Python module as a few unity sources" OFF)
function(stairplan_unity_sources target)
  if(STAIRPLAN_UNITY_BUILD)
    set_target_properties(${target} PROPERTIES UNITY_BUILD ON UNITY_BUILD_BATCH_SIZE 16)
  endif()
endfunction()

# Called by stairplan_add_test: the test properties that set the sanitizers' run-time options.
# ASan's fake stacks (detect_stack_use_after_return, on in scripts/sanitize.sh) make the
# end-to-end programs a third slower (the validator's default-plan test 14.1 s instead of 10.4),
# minutes of CI; the functions they run are the unit programs' too, which keep the check. The
# programs a test starts (the CLI) run without them too (RunCommand, tests/test_paths.cc).
# Appended to ASAN_OPTIONS: of an option given twice ASan takes the last.
function(stairplan_sanitized_test_env out end_to_end)
  set(${out} "" PARENT_SCOPE)
  if(STAIRPLAN_SANITIZE AND end_to_end)
    set(${out} ENVIRONMENT_MODIFICATION "ASAN_OPTIONS=string_append::detect_stack_use_after_return=0" PARENT_SCOPE)
  endif()
endfunction()

# Called by stairplan_add_test. The first test program precompiles the headers nearly every test
# includes; the others reuse its precompiled header (their flags and definitions are the same).
function(stairplan_quick_test_build target)
  if(NOT STAIRPLAN_QUICK_TEST_BUILD)
    return()
  endif()
  set_target_properties(${target} PROPERTIES UNITY_BUILD ON UNITY_BUILD_BATCH_SIZE 16)
  get_property(pch_target GLOBAL PROPERTY STAIRPLAN_TEST_PCH_TARGET)
  if(pch_target)
    target_precompile_headers(${target} REUSE_FROM ${pch_target})
  else()
    target_precompile_headers(${target} PRIVATE
      <catch2/catch.hpp> <Eigen/Dense> <nlohmann/json.hpp> <random> <fstream> <sstream> <string> <vector>
      [["stairplan/kinematics/robot_kinematics.h"]] [["stairplan/collision/stair_collision_model.h"]] [["stairplan/planning/plan.h"]])
    set_property(GLOBAL PROPERTY STAIRPLAN_TEST_PCH_TARGET ${target})
  endif()
endfunction()
