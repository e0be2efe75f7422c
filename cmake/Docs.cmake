# API documentation with Doxygen (FindDoxygen; Debian's doxygen): `cmake --build build --target docs`
# writes build/docs/html/index.html from the /// comments of the installed headers. The target is
# not part of the default build; tests/docs runs the same configuration and fails on any warning.
# Included after cmake/Install.cmake, whose install rules it mirrors: the include root stairplan/
# without node_modules and the internal headers listed there, plus the generated version.h.
if(NOT internal_headers)
  message(FATAL_ERROR "cmake/Docs.cmake needs the internal_headers of cmake/Install.cmake: include it after")
endif()
set(STAIRPLAN_DOCS_DIR ${PROJECT_BINARY_DIR}/docs)
set(STAIRPLAN_DOCS_INPUT "")
set(STAIRPLAN_DOCS_INPUT "${PROJECT_SOURCE_DIR}/stairplan ${PROJECT_BINARY_DIR}/generated/stairplan/version.h")
set(STAIRPLAN_DOCS_EXCLUDE "*/node_modules/*")
foreach(header ${internal_headers})
  string(APPEND STAIRPLAN_DOCS_EXCLUDE " */${header}")
endforeach()
configure_file(cmake/Doxyfile.in ${PROJECT_BINARY_DIR}/Doxyfile @ONLY)

find_package(Doxygen QUIET)
if(DOXYGEN_FOUND)
  add_custom_target(docs COMMAND ${DOXYGEN_EXECUTABLE} ${PROJECT_BINARY_DIR}/Doxyfile
    WORKING_DIRECTORY ${PROJECT_BINARY_DIR}
    COMMENT "API documentation in ${STAIRPLAN_DOCS_DIR}/html" VERBATIM)
endif()
