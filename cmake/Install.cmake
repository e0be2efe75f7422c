# Install the libraries, headers and an exported package so find_package(stairplan) works.
include(CMakePackageConfigHelpers)
get_property(modules GLOBAL PROPERTY STAIRPLAN_MODULES)
install(TARGETS ${modules} EXPORT stairplanTargets
  ARCHIVE DESTINATION ${CMAKE_INSTALL_LIBDIR}
  LIBRARY DESTINATION ${CMAKE_INSTALL_LIBDIR}
  RUNTIME DESTINATION ${CMAKE_INSTALL_BINDIR})
install(TARGETS stairplan RUNTIME DESTINATION ${CMAKE_INSTALL_BINDIR})
foreach(dir geometry kinematics collision planning)
  install(DIRECTORY ${dir}/ DESTINATION ${CMAKE_INSTALL_INCLUDEDIR}/stairplan/${dir}
    FILES_MATCHING PATTERN "*.h" PATTERN "cli" EXCLUDE)
endforeach()
install(FILES ${PROJECT_BINARY_DIR}/generated/stairplan/version.h
  DESTINATION ${CMAKE_INSTALL_INCLUDEDIR}/stairplan/stairplan)
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
