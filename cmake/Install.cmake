# Install the libraries, headers and an exported package so find_package(stairplan) works.
include(CMakePackageConfigHelpers)
get_property(modules GLOBAL PROPERTY STAIRPLAN_MODULES)
get_property(STAIRPLAN_HAS_EGL GLOBAL PROPERTY STAIRPLAN_HAS_EGL)
install(TARGETS ${modules} EXPORT stairplanTargets
  ARCHIVE DESTINATION ${CMAKE_INSTALL_LIBDIR}
  LIBRARY DESTINATION ${CMAKE_INSTALL_LIBDIR}
  RUNTIME DESTINATION ${CMAKE_INSTALL_BINDIR})
install(TARGETS stairplan RUNTIME DESTINATION ${CMAKE_INSTALL_BINDIR})
# Headers the implementation shares between its files, which no public header includes (and some
# include urdfdom, a private dependency): not installed. scripts/check_install.sh checks that every
# installed header's includes of ours are installed too.
set(internal_headers body_nlp_internal.h difference_matrices.h urdf_parse.h urdf_pose.h lzf.h)
list(APPEND internal_headers executor_leg_state.h)
set(exclude_internal "")
foreach(header ${internal_headers})
  list(APPEND exclude_internal PATTERN ${header} EXCLUDE)
endforeach()
install(DIRECTORY stairplan/ DESTINATION ${CMAKE_INSTALL_INCLUDEDIR}/stairplan
  FILES_MATCHING PATTERN "*.h" PATTERN "node_modules" EXCLUDE ${exclude_internal})
install(FILES ${PROJECT_BINARY_DIR}/generated/stairplan/version.h DESTINATION ${CMAKE_INSTALL_INCLUDEDIR}/stairplan)
install(DIRECTORY data/ DESTINATION ${CMAKE_INSTALL_DATADIR}/stairplan)
install(EXPORT stairplanTargets NAMESPACE stairplan::
  DESTINATION ${CMAKE_INSTALL_LIBDIR}/cmake/stairplan)
configure_package_config_file(cmake/stairplanConfig.cmake.in
  ${PROJECT_BINARY_DIR}/stairplanConfig.cmake
  INSTALL_DESTINATION ${CMAKE_INSTALL_LIBDIR}/cmake/stairplan)
write_basic_package_version_file(${PROJECT_BINARY_DIR}/stairplanConfigVersion.cmake
  COMPATIBILITY SameMinorVersion)
install(FILES ${PROJECT_BINARY_DIR}/stairplanConfig.cmake ${PROJECT_BINARY_DIR}/stairplanConfigVersion.cmake
  DESTINATION ${CMAKE_INSTALL_LIBDIR}/cmake/stairplan)

# stairplan.pc for pkg-config: our archives, most dependent first, then the libraries of the
# dependencies that cannot be in its Requires: MuJoCo has no .pc file, and FCL's and Ipopt's add
# -std=c++11 to the cflags, which would override a consumer's -std=c++17. Those go in by path or
# with the flags pkg-config gives here.
set(STAIRPLAN_PC_LIBS "")
set(pc_modules ${modules})
list(REVERSE pc_modules)
foreach(module ${pc_modules})
  string(APPEND STAIRPLAN_PC_LIBS "-l${module} ")
endforeach()
pkg_check_modules(STAIRPLAN_PC_FCL QUIET fcl)
if(NOT STAIRPLAN_PC_FCL_FOUND)
  set(STAIRPLAN_PC_FCL_LDFLAGS "$<TARGET_LINKER_FILE:fcl>")
endif()
string(REPLACE ";" " " pc_dependency_libs "$<TARGET_LINKER_FILE:mujoco::mujoco>;${STAIRPLAN_PC_FCL_LDFLAGS};${IPOPT_LDFLAGS}")
string(APPEND STAIRPLAN_PC_LIBS "${pc_dependency_libs}")
# CLP and EGL are optional: required only when the solvers archive holds the CLP back-end or the
# simulation archive the offscreen renderer. In the separate objects of a normal build a consumer
# that never names ClpSolver or OffscreenRenderer left their objects out of its link and the
# missing entry went unseen; a unity build merges them with code every consumer needs.
set(STAIRPLAN_PC_OPTIONAL_REQUIRES "")
if(STAIRPLAN_HAS_CLP)
  string(APPEND STAIRPLAN_PC_OPTIONAL_REQUIRES " clp")
endif()
if(STAIRPLAN_HAS_EGL)
  string(APPEND STAIRPLAN_PC_OPTIONAL_REQUIRES " egl")
endif()
file(RELATIVE_PATH STAIRPLAN_PC_PREFIX_FROM_PCDIR /prefix/${CMAKE_INSTALL_LIBDIR}/pkgconfig /prefix)
string(REGEX REPLACE "/$" "" STAIRPLAN_PC_PREFIX_FROM_PCDIR "${STAIRPLAN_PC_PREFIX_FROM_PCDIR}")
configure_file(cmake/stairplan.pc.in ${PROJECT_BINARY_DIR}/stairplan.pc.in @ONLY)
file(GENERATE OUTPUT ${PROJECT_BINARY_DIR}/stairplan.pc INPUT ${PROJECT_BINARY_DIR}/stairplan.pc.in)
install(FILES ${PROJECT_BINARY_DIR}/stairplan.pc DESTINATION ${CMAKE_INSTALL_LIBDIR}/pkgconfig)
install(FILES LICENSE CHANGELOG.md DESTINATION ${CMAKE_INSTALL_DOCDIR})
