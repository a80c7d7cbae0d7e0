# Files from elsewhere never crash granwave (issue #25): hostile data in valid traces, a full disk,
# and a seeded mutation fuzzer over trace, system, study and TOML files. Python (h5py) drives them.
set(FILES_PY /usr/bin/python3)
set(FILES_TMP ${CMAKE_BINARY_DIR}/files-tests)

add_test(NAME "files: hostile data inside valid traces exits 2 naming the dataset"
  COMMAND ${FILES_PY} ${CMAKE_SOURCE_DIR}/tests/files/hostile_traces.py ${GW} ${FILES_TMP}/hostile)
set_tests_properties("files: hostile data inside valid traces exits 2 naming the dataset" PROPERTIES LABELS "cli;unit")

add_test(NAME "files: run, build and sweep on a full disk exit 1 and lose nothing"
  COMMAND ${FILES_PY} ${CMAKE_SOURCE_DIR}/tests/files/full_disk.py ${GW} ${FILES_TMP}/full_disk)
set_tests_properties("files: run, build and sweep on a full disk exit 1 and lose nothing" PROPERTIES LABELS "cli;unit")

add_test(NAME "files: a trace whose object header continues at an impossible length or address exits 2 naming the file"
  COMMAND ${FILES_PY} ${CMAKE_SOURCE_DIR}/tests/files/damaged_addresses.py ${GW} ${FILES_TMP}/damaged_addresses)
# HDF5 leaks a block on this error path (tests/files/lsan_hdf5.supp); granwave exits 2 right after.
set_tests_properties("files: a trace whose object header continues at an impossible length or address exits 2 naming the file"
  PROPERTIES LABELS "cli;unit"
  ENVIRONMENT "LSAN_OPTIONS=suppressions=${CMAKE_SOURCE_DIR}/tests/files/lsan_hdf5.supp:print_suppressions=0")

# The fuzzer: 3000 inputs on the Release build (27 s on 2 idle cores); under the sanitizers 400 inputs (21 s)
# with a longer bound (each run is ~5x slower). The regression inputs below are kept from it.
if(GRANWAVE_SANITIZE)
  set(FUZZ_ARGS --inputs 400 --timeout 60)
else()
  set(FUZZ_ARGS --inputs 3000 --timeout 10)
endif()
add_test(NAME "files: seeded mutation fuzzer over traces, systems, studies and TOML"
  COMMAND ${FILES_PY} ${CMAKE_SOURCE_DIR}/tests/files/fuzz_files.py ${GW} ${FILES_TMP}/fuzz ${FUZZ_ARGS})
set_tests_properties("files: seeded mutation fuzzer over traces, systems, studies and TOML" PROPERTIES
  LABELS "cli;unit;fuzz" TIMEOUT 600
  ENVIRONMENT "LSAN_OPTIONS=suppressions=${CMAKE_SOURCE_DIR}/tests/files/lsan_hdf5.supp:print_suppressions=0")

# libFuzzer (clang): -DGRANWAVE_LIBFUZZER=ON builds readers_fuzzer; scripts/test-all.sh runs it for 60 s.
if(GRANWAVE_LIBFUZZER)
  add_executable(readers_fuzzer ${CMAKE_SOURCE_DIR}/tests/fuzz/readers_fuzzer.cpp)
  target_compile_options(readers_fuzzer PRIVATE -fsanitize=fuzzer)
  target_link_options(readers_fuzzer PRIVATE -fsanitize=fuzzer)
  # granwave_base only: clang 14 cannot compile the crystal's kernel (lambdas that capture structured
  # bindings, C++20), so the fuzzer reads traces without the table of observables (their datasets' shape
  # checks are fuzzed by tests/files/fuzz_files.py through the program).
  target_link_libraries(readers_fuzzer PRIVATE granwave_base)
  # theory/ is linked (the trace analysis reaches the lattice dynamics) but is no reader: at -O0 (each file
  # then out of the unity batches), clang compiles it in a fraction of the -O1 batch's 3.5 min, the
  # stage's longest job, while the readers keep -O1.
  file(GLOB theory_sources ${CMAKE_SOURCE_DIR}/src/theory/*.cpp)
  set_property(SOURCE ${theory_sources} APPEND PROPERTY COMPILE_OPTIONS -O0)
endif()

# Regression inputs (the first two from the issue's experiment (1000 mutated crystal40 traces, seed 20261126, in the
# format before #25: no checksums, variable-length strings), their untouched datasets zeroed so that
# they gzip to 5 kB: one claimed a dataset extent of 3e18 values (std::vector max_size: exit 1), one
# crashed the HDF5 library in its global heap (SIGSEGV under H5Aread of a root attribute)).
function(granwave_damaged_trace name words)
  add_test(NAME "files: analyze of damaged trace ${name} exits 2 naming the file"
    COMMAND sh -c "gzip -dc ${CMAKE_SOURCE_DIR}/tests/data/damaged/${name}.h5.gz > ${CLI_TMP}/${name}.h5 && \
${GW} analyze ${CLI_TMP}/${name}.h5 --json > /dev/null 2> ${CLI_TMP}/${name}.err; rc=$?; \
test $rc -eq 2 || { cat ${CLI_TMP}/${name}.err; echo \"exit code $rc, expected 2\"; exit 1; }; \
grep -Eq -- '${name}.h5.*${words}' ${CLI_TMP}/${name}.err || { cat ${CLI_TMP}/${name}.err; exit 1; }")
  set_tests_properties("files: analyze of damaged trace ${name} exits 2 naming the file" PROPERTIES LABELS "cli;unit")
endfunction()
granwave_damaged_trace(trace_huge_extent "claims .* values")
granwave_damaged_trace(trace_vlen_heap_crash "(damaged|checksum mismatch)")
# From the 10 000 traces of the issue's "done when" (fuzz_files.py --seed 1, an h5py-format trace):
# a damaged version-1 object header on which H5Aexists_by_name crashed (SIGSEGV in a memcpy). Such a
# header has no checksum: whether the library crashes on it (the crash guard's message) or decodes
# garbage (then refused by the measures, naming the file) depends on the heap's layout, which changes
# with the binary and even the path's length; either way exit 2 naming the file.
granwave_damaged_trace(trace_attr_header_crash "(damaged file: the HDF5 library crashed reading ./system/@|: analyze: the fit range)")
