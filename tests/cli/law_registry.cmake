# The contact-law registry (issue #26): no law comparison outside it; an enumerator without its
# description does not compile; the test-only third law runs through it. Included by tests/cli.cmake.
add_test(NAME "cli: law registry: no ContactLaw comparison outside the registry"
  COMMAND sh ${CMAKE_SOURCE_DIR}/tests/cli/law_registry_grep.sh ${CMAKE_SOURCE_DIR})
add_test(NAME "cli: law registry: an enumerator without its description does not compile"
  COMMAND ${CMAKE_COMMAND} -DCXX=${CMAKE_CXX_COMPILER} -DSRC=${CMAKE_SOURCE_DIR} -DOUT=${CMAKE_BINARY_DIR}/cli-tests/law_probe
          -P ${CMAKE_SOURCE_DIR}/tests/cli/law_enumerator_probe.cmake)
add_test(NAME "cli: law registry: the test law runs through check, run and theory"
  COMMAND /usr/bin/python3 ${CMAKE_SOURCE_DIR}/tests/cli/law_registry.py $<TARGET_FILE:granwave>
          $<TARGET_FILE:granwave_testlaw> ${CMAKE_SOURCE_DIR} ${CMAKE_BINARY_DIR}/cli-tests/test_law)
set_tests_properties("cli: law registry: no ContactLaw comparison outside the registry"
                     "cli: law registry: an enumerator without its description does not compile"
                     "cli: law registry: the test law runs through check, run and theory" PROPERTIES LABELS "cli;unit")
