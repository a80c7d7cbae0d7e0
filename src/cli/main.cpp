// granwave: one verb per file in src/cli/. Exit codes (docs/design.md §2.3): 0 success,
// 2 bad input, 1 a failed run or check.
#include <malloc.h>
#include <sys/mman.h>
#include <unistd.h>

#include <cstdint>
#include <cstdlib>
#include <cstring>
#include <iostream>
#include <limits>
#include <map>
#include <string>

#include "cli/verbs.hpp"
#include "core/error.hpp"
#include "core/version.hpp"
#include "io/h5.hpp"
#include "sweep/distributed.hpp"

namespace {

constexpr const char* kUsage = R"(granwave — a reference solver for waves in granular media

usage: granwave VERB [ARGS] (granwave VERB --help for each verb)

  build CASE.toml -o system.h5          resolve spins, radii, relaxation; write the system file
  run CASE.toml [-o traces.h5] [--system system.h5] [--json] [--quiet] [--max-steps N] [--max-memory SIZE]
                                        simulate one case, write its trace file, print its measures
                                        (those of `analyze` on that trace)
  check CASE.toml [--max-steps N] [--max-memory SIZE]
                                        validate; print the resolved case, derived numbers, costs
  analyze traces.h5 [--json] [--layers LO:HI]
                                        wave speeds, arrivals, peaks, dispersion (any code's traces)
  theory CASE.toml [--json]             stiffness tensor, V_p, V_s, omega_0, t_c
  probe CASE.toml [--strain S] [--json] the static probe: strain, relax, stress change vs the relaxed tensor
  sweep STUDY.toml [-o study.h5] [--quiet]
                                        ensembles and parameter studies, resumable
  figures chain|crystal [--out DIR]     the seeds' figures as PNG, from fresh runs
  observables [--json]                  the crystal trace's observables: name, shape, unit, sampling
  packing CASE.toml [-o FILE.dump] [--min-contacts N] [--json]
                                        a periodic packing (prepared, gas or another code's) measured:
                                        Phi, z*, rattlers, pressure, residuals; written as a dump
  laws [--json]                         the contact laws: their [contact] keys, units, ranges, defaults
  version                               print the version

Exit codes: 0 success, 2 bad input, 1 a failed run.
)";

// Page faults are dear on a paravirtualised VM (about 10 us each): a run reuses large buffers that
// glibc would hand back to the kernel, and first-touches megabytes of arrays a 4 KiB page at a time.
// So the heap keeps what is freed and is grown once by 1 GiB of address space advised for 2 MiB
// pages, taken only as touched (what glibc's `glibc.malloc.hugetlb=1` does; measured in
// docs/benchmarks.md, sessions 36 and 37). A user's own malloc settings win: then nothing is done.
void prepare_heap() {
  if (std::getenv("GLIBC_TUNABLES") || std::getenv("MALLOC_TOP_PAD_") || std::getenv("MALLOC_MMAP_THRESHOLD_") ||
      std::getenv("MALLOC_TRIM_THRESHOLD_"))
    return;
  constexpr std::size_t kReserve = std::size_t{1} << 30, kHugePage = std::size_t{2} << 20;
  mallopt(M_MMAP_THRESHOLD, static_cast<int>(kReserve));  // blocks below 1 GiB come from the heap
  mallopt(M_TOP_PAD, 64 << 20);
  mallopt(M_TRIM_THRESHOLD, std::numeric_limits<int>::max());  // the reserve is never trimmed
  const std::size_t bytes = kReserve - 2 * kHugePage;
  void* block = std::malloc(bytes);
  if (!block) return;
  const auto start = reinterpret_cast<std::uintptr_t>(block);
  const auto brk = reinterpret_cast<std::uintptr_t>(sbrk(0));
  const auto lo = (start + kHugePage - 1) & ~(kHugePage - 1), hi = brk & ~(kHugePage - 1);
  // Only a block from the heap (glibc falls back to mmap where the break cannot grow).
  if (start + bytes <= brk && hi > lo) madvise(reinterpret_cast<void*>(lo), hi - lo, MADV_HUGEPAGE);
  std::free(block);
}

}  // namespace

int main(int argc, char** argv) {
  using namespace granwave;
  prepare_heap();
  const sweep::MpiSession mpi(&argc, &argv);  // MPI only when started by mpirun (sweep/distributed.hpp)
  if (argc < 2 || !std::strcmp(argv[1], "--help") || !std::strcmp(argv[1], "-h") || !std::strcmp(argv[1], "help")) {
    std::cout << kUsage;
    return argc < 2 ? 2 : 0;
  }
  const std::string verb = argv[1];
  cli::Args args(argv + 2, argv + argc);
  const std::map<std::string, int (*)(const cli::Args&)> verbs{
      {"build", cli::cmd_build},   {"run", cli::cmd_run},       {"check", cli::cmd_check},     {"analyze", cli::cmd_analyze},
      {"theory", cli::cmd_theory}, {"sweep", cli::cmd_sweep},   {"figures", cli::cmd_figures},
      {"observables", cli::cmd_observables},
      {"laws", cli::cmd_laws},     {"probe", cli::cmd_probe},
      {"packing", cli::cmd_packing},
  };
  if (verb == "version" || verb == "--version") {
    std::cout << "granwave " << version() << " (" << git_describe() << ")\n";
    return 0;
  }
  auto it = verbs.find(verb);
  if (it == verbs.end()) {
    std::cerr << "granwave: unknown verb '" << verb << "' (try granwave --help)\n";
    return 2;
  }
  // Under mpirun every rank's error reaches rank 0 (sweep/distributed.hpp): it alone prints.
  std::ostream quiet(nullptr);
  std::ostream& err = sweep::is_root() ? std::cerr : quiet;
  if (const std::string why = sweep::mpi_refusal(verb); !why.empty()) {
    err << "granwave " << verb << ": error: " << why << "\n";
    return 2;
  }
  try {
    return it->second(args);
  } catch (const InputError& e) {
    err << "granwave " << verb << ": error: " << e.what() << "\n";
    return 2;
  } catch (const RunError& e) {
    err << "granwave " << verb << ": run failed: " << e.what() << "\n";
    if (io::abandoned_files()) {  // a full disk: the HDF5 library's clean-up at exit would crash (io/h5.hpp)
      std::cout.flush();
      std::cerr.flush();
      std::_Exit(1);
    }
    return 1;
  } catch (const std::exception& e) {
    err << "granwave " << verb << ": internal error: " << e.what() << "\n";
    return 1;
  } catch (...) {
    // io/ turns the HDF5 library's failures into InputError or RunError; one that still escapes
    // comes from a file the library could not read: bad input, not a crash.
    if (const std::string why = io::hdf5_exception_message(); !why.empty()) {
      err << "granwave " << verb << ": error: HDF5: " << why << "\n";
      return 2;
    }
    err << "granwave " << verb << ": internal error: unknown exception\n";
    return 1;
  }
}
