# The table of every input tried against the guards (tests/cli/guards_table.txt), one ctest per
# row: "cli: guards: NAME". Included by tests/cli.cmake.
set_property(DIRECTORY APPEND PROPERTY CMAKE_CONFIGURE_DEPENDS ${CMAKE_SOURCE_DIR}/tests/cli/guards_table.txt)
# Data rows only (a "[" in a comment would otherwise glue the rows of the CMake list together).
file(STRINGS ${CMAKE_SOURCE_DIR}/tests/cli/guards_table.txt guard_rows REGEX "^[A-Za-z0-9_.-]+ *[|]")
foreach(row IN LISTS guard_rows)
  if(row MATCHES "^#" OR row STREQUAL "")
    continue()
  endif()
  string(REPLACE "|" ";" cols "${row}")
  list(LENGTH cols ncols)
  if(NOT ncols EQUAL 6)
    message(FATAL_ERROR "tests/cli/guards_table.txt: a row needs 6 columns: ${row}")
  endif()
  set(fields name verb input args rc fragments)
  foreach(i RANGE 5)
    list(GET cols ${i} value)
    list(GET fields ${i} field)
    string(STRIP "${value}" ${field})
  endforeach()
  add_test(NAME "cli: guards: ${name}"
    COMMAND sh ${CMAKE_SOURCE_DIR}/tests/cli/expect.sh $<TARGET_FILE:granwave> ${CMAKE_SOURCE_DIR} ${CMAKE_BINARY_DIR}/cli-tests
            ${name} ${verb} ${input} "${args}" ${rc} "${fragments}")
  set_tests_properties("cli: guards: ${name}" PROPERTIES LABELS "cli;unit")
endforeach()
