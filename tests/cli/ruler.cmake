# One ruler (issue 12): `granwave run --json` prints under "analysis" exactly what `granwave
# analyze --json` prints for the trace it wrote (tests/cli/run_equals_analyze.py), for a chain, a
# crystal and two runs cut before the front crossed the fit range. Included by tests/cli.cmake.
find_program(GW_SYSTEM_PYTHON3 python3 PATHS /usr/bin NO_DEFAULT_PATH)
if(NOT GW_SYSTEM_PYTHON3)
  message(WARNING "no /usr/bin/python3: the cli ruler tests are not registered")
  return()
endif()
set(ruler_script ${CMAKE_SOURCE_DIR}/tests/cli/run_equals_analyze.py)
set(ruler_tmp ${CMAKE_BINARY_DIR}/cli-tests/ruler)
foreach(spec
    "chain oriented20|data/cases/oriented20.toml|"
    "crystal small|data/cases/crystal_small.toml|"
    "a packing from LAMMPS (its free bins by role)|data/cases/packing_lammps.toml|"
    "crystal cut at 160 layers and 0.9 ms (the issue's case)|tests/cli/cases/crystal_p_cut160.toml|--cut"
    "crystal cut at 160 layers and 0.6 ms, range shortened|tests/cli/cases/crystal_p_cut160_short.toml|--shortened")
  string(REPLACE "|" ";" parts "${spec}")
  list(GET parts 0 label)
  list(GET parts 1 case)
  list(GET parts 2 flag)
  add_test(NAME "cli: run and analyze print the same measures: ${label}"
    COMMAND ${GW_SYSTEM_PYTHON3} ${ruler_script} $<TARGET_FILE:granwave> ${CMAKE_SOURCE_DIR}/${case} ${ruler_tmp} ${flag})
  set_tests_properties("cli: run and analyze print the same measures: ${label}" PROPERTIES LABELS "cli")
endforeach()
# The readings of analyze (tests/cli/<script>.py GRANWAVE CASE CHAIN_CASE WORKDIR): the option, the
# case's [analysis] key read back from the trace, and their refusals.
function(gw_reading_test name script case)
  add_test(NAME "cli: ${name}"
    COMMAND ${GW_SYSTEM_PYTHON3} ${CMAKE_SOURCE_DIR}/tests/cli/${script}.py $<TARGET_FILE:granwave>
            ${CMAKE_SOURCE_DIR}/tests/cli/cases/${case}.toml ${CMAKE_SOURCE_DIR}/data/cases/oriented20.toml
            ${CMAKE_BINARY_DIR}/cli-tests/${script})
  set_tests_properties("cli: ${name}" PROPERTIES LABELS "cli")
endfunction()
# The wavelength's reading of T, and the run summary's lattice-dynamics S speed.
gw_reading_test("[analysis] period and analyze --period choose T of lambda = V T; run prints the lattice S speed"
                period_reading crystal_small_s_kt_pulse)
# k's local speed in seed 002 sec. 3.4.
gw_reading_test("[analysis] wavenumber_speed and analyze --wavenumber-speed choose V of k = (2/l0) arccos(V/V(k->0))"
                wavenumber_speed_reading crystal_small_k_first_peak)
