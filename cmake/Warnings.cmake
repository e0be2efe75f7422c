# One warning policy for every target of ours.
function(stairplan_set_warnings target)
  target_compile_options(${target} PRIVATE -Wall -Wextra -Wpedantic -Wshadow -Wnon-virtual-dtor)
  if(STAIRPLAN_WERROR)
    target_compile_options(${target} PRIVATE -Werror)
  endif()
endfunction()

# A module library: stairplan_<name>, exported as stairplan::<name>.
function(stairplan_add_module name)
  add_library(stairplan_${name} ${ARGN})
  add_library(stairplan::${name} ALIAS stairplan_${name})
  set_target_properties(stairplan_${name} PROPERTIES EXPORT_NAME ${name})
  target_include_directories(stairplan_${name} PUBLIC
    $<BUILD_INTERFACE:${PROJECT_SOURCE_DIR}>
    $<BUILD_INTERFACE:${PROJECT_BINARY_DIR}/generated>
    $<INSTALL_INTERFACE:${CMAKE_INSTALL_INCLUDEDIR}>)
  stairplan_set_warnings(stairplan_${name})
  stairplan_unity_sources(stairplan_${name})
  set_property(GLOBAL APPEND PROPERTY STAIRPLAN_MODULES stairplan_${name})
endfunction()

# A Catch2 test program registered with ctest, one test per TEST_CASE:
#   stairplan_add_test(name [END_TO_END] [COST n] sources...)
# COST (default 0) orders ctest's parallel run, highest first: a fresh clone has no timings of
# its own, and a minutes-long test started last leaves the other cores idle till it ends.
# END_TO_END: the program plans and replays whole flights through code the unit programs test
# (see stairplan_sanitized_test_env).
function(stairplan_add_test name)
  cmake_parse_arguments(PARSE_ARGV 1 arg "END_TO_END" "COST" "")
  if(NOT arg_COST)
    set(arg_COST 0)
  endif()
  add_executable(${name} ${arg_UNPARSED_ARGUMENTS})
  target_link_libraries(${name} PRIVATE stairplan_test_main)
  stairplan_set_warnings(${name})
  # A test program drives the optimised libraries and does little work of its own: -O1 compiles it
  # in about two thirds of -O3's time, and CI builds every test program from scratch twice.
  target_compile_options(${name} PRIVATE $<$<CONFIG:Release>:-O1>)
  target_compile_definitions(${name} PRIVATE
    STAIRPLAN_SHARED_DIR="${STAIRPLAN_SHARED_DIR}" STAIRPLAN_SOURCE_DIR="${STAIRPLAN_SOURCE_DIR}"
    STAIRPLAN_BIN_DIR="${PROJECT_BINARY_DIR}/bin")
  stairplan_quick_test_build(${name})
  stairplan_sanitized_test_env(env ${arg_END_TO_END})
  # --warn NoTests: a ctest entry whose name matches no TEST_CASE fails instead of passing empty
  # (catch_discover_tests splits a name at ';' into entries that match nothing).
  catch_discover_tests(${name} EXTRA_ARGS --warn NoTests PROPERTIES TIMEOUT 600 COST ${arg_COST} ${env})
endfunction()
