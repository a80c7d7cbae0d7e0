# MPI tests (label "mpi"; issue 16 items 1 and 4): `mpirun --oversubscribe -n R granwave sweep` writes the
# single-process study file for R = 1, 2, 3 and 1 or 2 threads per rank; a killed rank resumes;
# idle ranks; refusals. `mpirun -n R granwave run CRYSTAL` (slab decomposition) writes the serial
# trace file for R = 1, 2, 3 (tests/mpi/run_ranks.py). The driver (tests/mpi/sweep_ranks.py) exits 77 = SKIP, with the reason, in
# a build without MPI or without mpirun: never a silent pass. As root it sets Open MPI's
# OMPI_ALLOW_RUN_AS_ROOT{,_CONFIRM}.
set(MPI_DRIVER /usr/bin/python3 ${CMAKE_SOURCE_DIR}/tests/mpi/sweep_ranks.py)
set(MPI_TMP ${CMAKE_BINARY_DIR}/mpi-tests)
set(MPI_SMOKE ${CMAKE_SOURCE_DIR}/data/studies/smoke.toml)
if(GRANWAVE_MPI)
  set(MPI_BUILT ON)
else()
  set(MPI_BUILT OFF)
endif()

function(granwave_mpi_test name)
  add_test(NAME "mpi/sweep: ${name}" COMMAND ${MPI_DRIVER} ${ARGN})
  set_tests_properties("mpi/sweep: ${name}" PROPERTIES LABELS mpi SKIP_RETURN_CODE 77 TIMEOUT 300)
endfunction()

foreach(ranks 1 2 3)
  foreach(threads 1 2)
    granwave_mpi_test("mpirun -n ${ranks}, ${threads} threads: the single-process study file"
                      identity ${MPI_BUILT} $<TARGET_FILE:granwave> ${MPI_SMOKE} ${MPI_TMP}/identity_${ranks}_${threads} ${ranks} ${threads})
  endforeach()
endforeach()
granwave_mpi_test("crystal study on 3 ranks: the single-process study file"
                  identity ${MPI_BUILT} $<TARGET_FILE:granwave> ${CMAKE_SOURCE_DIR}/tests/data/mpi/crystal_tiny.toml ${MPI_TMP}/crystal 3 1)
granwave_mpi_test("rank 1, then rank 0 killed mid-sweep: a rerun resumes, same file"
                  resume ${MPI_BUILT} $<TARGET_FILE:granwave> ${CMAKE_SOURCE_DIR}/tests/data/mpi/resume.toml ${MPI_TMP}/resume)
granwave_mpi_test("more ranks than members: idle ranks, same file"
                  idle ${MPI_BUILT} $<TARGET_FILE:granwave> ${CMAKE_SOURCE_DIR}/tests/data/mpi/two_members.toml ${MPI_TMP}/idle)
granwave_mpi_test("build on 2 ranks is refused with exit 2 (only sweep and a crystal's run are distributed)"
                  refused ${MPI_BUILT} $<TARGET_FILE:granwave> ${CMAKE_SOURCE_DIR}/data/cases/crystal_small.toml ${MPI_TMP}/refused)
granwave_mpi_test("a build without MPI refuses to run as 2 ranks (exit 2)"
                  nompi ${MPI_BUILT} $<TARGET_FILE:granwave> ${MPI_SMOKE} ${MPI_TMP}/nompi)

# One crystal run split into slabs of layers (crystal/slab.hpp): the serial trace file, bit for bit.
set(MPI_RUN_DRIVER /usr/bin/python3 ${CMAKE_SOURCE_DIR}/tests/mpi/run_ranks.py)
function(granwave_mpi_run_test name)
  add_test(NAME "mpi/run: ${name}" COMMAND ${MPI_RUN_DRIVER} ${ARGN})
  set_tests_properties("mpi/run: ${name}" PROPERTIES LABELS mpi SKIP_RETURN_CODE 77 TIMEOUT 300)
endfunction()
set(MPI_SLAB ${CMAKE_SOURCE_DIR}/tests/data/mpi)
foreach(slab_case slab_p slab_s_friction slab_sliding slab_damped slab_poly slab_velocity slab_hertz slab_rolling)
  foreach(ranks 2 3)
    granwave_mpi_run_test("${slab_case} on ${ranks} ranks: the serial trace file"
                          identity ${MPI_BUILT} $<TARGET_FILE:granwave> ${MPI_SLAB}/${slab_case}.toml ${MPI_TMP}/run_${slab_case}_${ranks} ${ranks})
  endforeach()
endforeach()
granwave_mpi_run_test("slab_p on 1 rank (mpirun -n 1): the serial trace file"
                      identity ${MPI_BUILT} $<TARGET_FILE:granwave> ${MPI_SLAB}/slab_p.toml ${MPI_TMP}/run_slab_p_1 1)
foreach(ranks 2 3)
  granwave_mpi_run_test("slab_rebuild on ${ranks} ranks: rebuilds during the run, the serial trace file"
                        identity ${MPI_BUILT} $<TARGET_FILE:granwave> ${MPI_SLAB}/slab_rebuild.toml ${MPI_TMP}/run_slab_rebuild_${ranks} ${ranks} 3)
endforeach()
granwave_mpi_run_test("6 ranks for 5 layers: exit 2 naming crystal.cells[2], nothing written"
                      too_many ${MPI_BUILT} $<TARGET_FILE:granwave> ${MPI_SLAB}/slab_too_many.toml ${MPI_TMP}/run_too_many 6)
granwave_mpi_run_test("a chain run on 2 ranks: exit 2, nothing written"
                      chain ${MPI_BUILT} $<TARGET_FILE:granwave> ${CMAKE_SOURCE_DIR}/data/cases/oriented20.toml ${MPI_TMP}/run_chain)
