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
    $<INSTALL_INTERFACE:${CMAKE_INSTALL_INCLUDEDIR}/stairplan>)
  stairplan_set_warnings(stairplan_${name})
  set_property(GLOBAL APPEND PROPERTY STAIRPLAN_MODULES stairplan_${name})
endfunction()

# A Catch2 test program registered with ctest, one test per TEST_CASE.
function(stairplan_add_test name)
  add_executable(${name} ${ARGN})
  target_link_libraries(${name} PRIVATE stairplan_test_main)
  stairplan_set_warnings(${name})
  target_compile_definitions(${name} PRIVATE
    STAIRPLAN_SHARED_DIR="${STAIRPLAN_SHARED_DIR}" STAIRPLAN_SOURCE_DIR="${STAIRPLAN_SOURCE_DIR}"
    STAIRPLAN_BIN_DIR="${PROJECT_BINARY_DIR}/bin")
  stairplan_quick_test_build(${name})
  catch_discover_tests(${name} PROPERTIES TIMEOUT 600)
endfunction()
