# MPI tests (label "mpi"; issue 16 item 1): `mpirun --oversubscribe -n R granwave sweep` writes the
# single-process study file for R = 1, 2, 3 and 1 or 2 threads per rank; a killed rank resumes;
# idle ranks; refusals. The driver (tests/mpi/sweep_ranks.py) exits 77 = SKIP, with the reason, in
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
granwave_mpi_test("run on 2 ranks is refused with exit 2 (only sweep is distributed)"
                  refused ${MPI_BUILT} $<TARGET_FILE:granwave> ${CMAKE_SOURCE_DIR}/data/cases/crystal_small.toml ${MPI_TMP}/refused)
granwave_mpi_test("a build without MPI refuses to run as 2 ranks (exit 2)"
                  nompi ${MPI_BUILT} $<TARGET_FILE:granwave> ${MPI_SMOKE} ${MPI_TMP}/nompi)
