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

# The fuzzer: 3000 inputs on the Release build (~40 s on 2 cores); under the sanitizers 600 inputs
# with a longer bound (each run is ~5x slower). The regression inputs below are kept from it.
if(GRANWAVE_SANITIZE)
  set(FUZZ_ARGS --inputs 600 --timeout 60)
else()
  set(FUZZ_ARGS --inputs 3000 --timeout 10)
endif()
add_test(NAME "files: seeded mutation fuzzer over traces, systems, studies and TOML"
  COMMAND ${FILES_PY} ${CMAKE_SOURCE_DIR}/tests/files/fuzz_files.py ${GW} ${FILES_TMP}/fuzz ${FUZZ_ARGS})
set_tests_properties("files: seeded mutation fuzzer over traces, systems, studies and TOML" PROPERTIES
  LABELS "cli;unit;fuzz" TIMEOUT 600)

# libFuzzer (clang): -DGRANWAVE_LIBFUZZER=ON builds readers_fuzzer; scripts/test-all.sh runs it for 60 s.
if(GRANWAVE_LIBFUZZER)
  add_executable(readers_fuzzer ${CMAKE_SOURCE_DIR}/tests/fuzz/readers_fuzzer.cpp)
  target_compile_options(readers_fuzzer PRIVATE -fsanitize=fuzzer)
  target_link_options(readers_fuzzer PRIVATE -fsanitize=fuzzer)
  target_link_libraries(readers_fuzzer PRIVATE granwave_sweep granwave_chain granwave_crystal granwave_base)
endif()
