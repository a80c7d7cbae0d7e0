// libFuzzer target over the readers of files from elsewhere (issue #25): case and study TOML, and
// HDF5 trace, system and study files. The first byte picks the reader, the rest is the file. A
// reader may refuse its input (InputError: exit 2 in granwave) or fail a run (RunError); any other
// exception, a crash or a sanitizer report is a finding. Built by -DGRANWAVE_LIBFUZZER=ON with
// clang (scripts/test-all.sh: build-fuzz/); seeds in tests/fuzz/corpus.
#include <unistd.h>

#include <cstdint>
#include <cstdio>
#include <string>

#include "analysis/trace_analysis.hpp"
#include "chain/chain.hpp"
#include "config/case.hpp"
#include "core/error.hpp"
#include "crystal/packing.hpp"
#include "io/h5.hpp"
#include "sweep/crystal_study.hpp"
#include "sweep/spin_study.hpp"
#include "sweep/study.hpp"

using namespace granwave;

namespace {
std::string scratch_file() {
  static const std::string path = "/tmp/granwave_fuzz_" + std::to_string(getpid()) + ".h5";
  return path;
}
}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  if (size < 1) return 0;
  const int kind = data[0] % 7;
  const std::string text(reinterpret_cast<const char*>(data + 1), size - 1);
  try {
    switch (kind) {
      case 0: config::parse_case(text, "fuzz.toml"); break;
      case 1: sweep::parse_spin_study(text, "fuzz_study.toml"); break;
      case 2: sweep::parse_crystal_study(text, "fuzz_study.toml"); break;
      default: {
        const std::string path = scratch_file();
        std::FILE* f = std::fopen(path.c_str(), "wb");
        if (!f) return 0;
        std::fwrite(text.data(), 1, text.size(), f);
        std::fclose(f);
        if (kind == 3) {
          analysis::read_trace(path);
        } else if (kind == 4) {
          crystal::read_system(path);
        } else if (kind == 5) {
          io::H5Reader r(path);
          chain::read_system(r, "/");
        } else {
          io::H5Reader r(path);
          sweep::read_members(r, "/members");
        }
      }
    }
  } catch (const InputError&) {
  } catch (const RunError&) {
  }
  return 0;
}
