# Layout rules of README.md that the compiler cannot check.
add_test(NAME only_la_includes_petsc
  COMMAND ${CMAKE_COMMAND} -DSOURCE_DIR=${PROJECT_SOURCE_DIR} -P ${PROJECT_SOURCE_DIR}/cmake/check_petsc_includes.cmake)
