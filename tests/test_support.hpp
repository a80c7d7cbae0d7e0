// Loud skips for the Catch2 v2 tests (v2 has no SKIP): skip() prints the marker that ctest's
// SKIP_REGULAR_EXPRESSION (CMakeLists.txt) reports as "Skipped", then exits with 77, so a run of
// the test binary outside ctest fails instead of passing. A test that cannot test never passes.
#pragma once
#include <cstdio>
#include <cstdlib>
#include <string>
#ifdef _OPENMP
#include <omp.h>
#endif

namespace test_support {

[[noreturn]] inline void skip(const std::string& why) {
  std::printf("GRANWAVE_SKIP: %s\n", why.c_str());
  std::fflush(stdout);
  std::fflush(stderr);
  std::_Exit(77);
}

// Threads that a parallel region asking for `wanted` really gets (1 without OpenMP).
inline int openmp_threads(int wanted) {
#ifdef _OPENMP
  int got = 0;
#pragma omp parallel num_threads(wanted)
  {
#pragma omp single
    got = omp_get_num_threads();
  }
  return got;
#else
  (void)wanted;
  return 1;
#endif
}

// Asks OpenMP for `wanted` threads in every later region (whatever OMP_NUM_THREADS says) and
// skips, loudly, when it cannot give them (no OpenMP, OMP_THREAD_LIMIT=1): never a vacuous pass.
// `untested` says what the test would have checked.
inline void require_openmp_threads(int wanted, const std::string& untested) {
#ifdef _OPENMP
  omp_set_num_threads(wanted);
#endif
  const int got = openmp_threads(wanted);
  if (got < wanted) skip("OpenMP gives " + std::to_string(got) + " thread(s): " + untested + " untested");
}

}  // namespace test_support
