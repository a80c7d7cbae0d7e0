// libFuzzer target over the readers of files from elsewhere (issue #25): case TOML, trace files and
// the HDF5 reader under the system and study readers. The first byte picks the reader, the rest is the
// file. A reader may refuse its input (InputError: exit 2 in granwave) or fail (RunError); any other
// exception, a crash or a sanitizer report is a finding. Links granwave_base only (the crystal kernel
// does not compile with clang 14); the system and study readers' own checks are fuzzed through the
// binary by tests/files/fuzz_files.py. Built by -DGRANWAVE_LIBFUZZER=ON with clang
// (scripts/test-all.sh: build-fuzz/); seeds from tests/fuzz/seed_corpus.sh.
#include <unistd.h>

#include <cstdint>
#include <cstdio>
#include <string>
#include <vector>

#include "analysis/trace_analysis.hpp"
#include "config/case.hpp"
#include "core/error.hpp"
#include "io/h5.hpp"

using namespace granwave;

namespace {
std::string scratch_file() {
  static const std::string path = "/tmp/granwave_fuzz_" + std::to_string(getpid()) + ".h5";
  return path;
}

// What the system and study readers ask of io::H5Reader (data/SCHEMA.md §2, §5), each on its own.
void read_like_the_readers(const std::string& path) {
  io::H5Reader r(path);
  const std::vector<std::string> numeric = {"/mass", "/radius", "/position", "/hertz_constant", "/members/values",
                                            "/members/profile", "/system/mass", "/time"};
  const std::vector<std::string> integers = {"/layer", "/cell", "/material_index", "/members/index",
                                             "/members/profile_offset"};
  const std::vector<std::string> text = {"/material_names", "/members/label", "/members/value_names"};
  for (const auto& p : numeric) try { if (r.has(p)) r.read_double(p); } catch (const InputError&) {}
  for (const auto& p : integers) try { if (r.has(p)) r.read_int(p); } catch (const InputError&) {}
  for (const auto& p : text) try { if (r.has(p)) r.read_strings(p); } catch (const InputError&) {}
  for (const char* a : {"model", "case_name", "fingerprint", "wall"})
    try { if (r.has_attr("/", a)) r.attr_string("/", a); } catch (const InputError&) {}
  for (const char* a : {"l0", "fixed_layers", "layers", "magnetisation"})
    try { if (r.has_attr("/", a)) r.attr_double("/", a); } catch (const InputError&) {}
}
}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  if (size < 1) return 0;
  const int kind = data[0] % 3;
  const std::string text(reinterpret_cast<const char*>(data + 1), size - 1);
  try {
    if (kind == 0) {
      config::parse_case(text, "fuzz.toml");
    } else {
      const std::string path = scratch_file();
      std::FILE* f = std::fopen(path.c_str(), "wb");
      if (!f) return 0;
      std::fwrite(text.data(), 1, text.size(), f);
      std::fclose(f);
      if (kind == 1) analysis::read_trace(path, analysis::no_observables());
      else read_like_the_readers(path);
    }
  } catch (const InputError&) {
  } catch (const RunError&) {
  }
  return 0;
}
