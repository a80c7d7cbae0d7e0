# The crystal's one table of observables (issue #37): `granwave observables`, data/SCHEMA.md §3's rows,
# and the test-only observable down to the trace file and its reader. Included by tests/cli.cmake.
add_test(NAME "cli: observables: one table; SCHEMA.md lists it; the test observable reaches the trace and its reader"
  COMMAND /usr/bin/python3 ${CMAKE_SOURCE_DIR}/tests/cli/observables.py $<TARGET_FILE:granwave>
          $<TARGET_FILE:granwave_testobservable> ${CMAKE_SOURCE_DIR} ${CMAKE_BINARY_DIR}/cli-tests/observables)
set_tests_properties("cli: observables: one table; SCHEMA.md lists it; the test observable reaches the trace and its reader"
                     PROPERTIES LABELS "cli")
