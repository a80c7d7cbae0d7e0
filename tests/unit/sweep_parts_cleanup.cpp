// A finished study removes its FILE.parts/ batches once FILE is complete (issue 12: `granwave
// figures crystal` left crystal_damping.h5.parts/ behind), and resuming still works: a study
// stopped part-way keeps its batches, and the rerun computes only the missing members, with the
// same datasets as an uninterrupted study; a rerun of a finished study reads its file back.
#include <catch2/catch.hpp>

#include <unistd.h>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <sstream>

#include "core/error.hpp"
#include "io/h5.hpp"
#include "sweep/crystal_study.hpp"
#include "sweep/spin_study.hpp"

using namespace granwave;
namespace fs = std::filesystem;

namespace {

fs::path fresh_dir(const std::string& name) {
  const fs::path d = fs::temp_directory_path() / ("granwave_" + name + "_" + std::to_string(::getpid()));
  fs::remove_all(d);
  fs::create_directories(d);
  return d;
}

std::size_t batches(const fs::path& parts) {
  std::size_t n = 0;
  if (fs::is_directory(parts))
    for (const auto& e : fs::directory_iterator(parts)) n += e.path().extension() == ".h5";
  return n;
}

// Three members of a 3 x 3 x 36 crystal for 0.12 ms (seconds each), one member per batch.
sweep::CrystalStudy tiny_crystal_study() {
  const std::string text = "[study]\nname = \"t\"\nkind = \"crystal\"\ncase = \"" + std::string(GRANWAVE_SOURCE_DIR) +
                           "/data/cases/crystal_p.toml\"\nvary = \"gamma_n\"\nvalues = [0.0, 0.1, 1.0]\npositions = [10, 12]\n";
  auto s = sweep::parse_crystal_study(text, "tiny.toml");
  s.base.crystal->cells = {3, 3, 36};
  s.t_end = 1.2e-4;
  s.batch = 1;
  return s;
}

bool same(const std::vector<double>& a, const std::vector<double>& b) {
  if (a.size() != b.size()) return false;
  for (std::size_t i = 0; i < a.size(); ++i)
    if (!(a[i] == b[i] || (std::isnan(a[i]) && std::isnan(b[i])))) return false;
  return true;
}

std::string smoke_text() {
  std::ifstream in(std::string(GRANWAVE_SOURCE_DIR) + "/data/studies/smoke.toml");
  std::stringstream ss;
  ss << in.rdbuf();
  return ss.str();
}

}  // namespace

TEST_CASE("crystal study: FILE.parts is gone once FILE is complete, and a stopped study resumes from it", "[sweep]") {
  const auto s = tiny_crystal_study();
  const fs::path dir = fresh_dir("parts_cleanup_crystal");
  std::ostringstream log;
  sweep::CrystalRunOptions opt;
  opt.quiet = true;
  opt.threads = 1;

  // Uninterrupted: the reference datasets, and no batches left.
  const std::string ref = (dir / "ref.h5").string();
  sweep::RunStats st0;
  sweep::run_crystal_study(s, ref, log, opt, &st0);
  REQUIRE(st0.computed == 3);
  CHECK(fs::exists(ref));
  CHECK_FALSE(fs::exists(ref + ".parts"));
  CHECK_FALSE(fs::exists(ref + ".tmp"));

  // Stopped after two members (as a kill between batches leaves it): batches kept, no study file.
  const std::string out = (dir / "study.h5").string();
  sweep::CrystalRunOptions stop = opt;
  stop.limit = 2;
  sweep::RunStats st1;
  sweep::run_crystal_study(s, out, log, stop, &st1);
  CHECK(st1.computed == 2);
  CHECK(batches(out + ".parts") == 2);
  CHECK_FALSE(fs::exists(out));

  // Resumed: only the missing member runs; then the batches go.
  sweep::RunStats st2;
  sweep::run_crystal_study(s, out, log, opt, &st2);
  CHECK(st2.resumed == 2);
  CHECK(st2.computed == 1);
  CHECK(fs::exists(out));
  CHECK_FALSE(fs::exists(out + ".parts"));
  {
    io::H5Reader a(ref), b(out);
    CHECK(same(a.read_double("/members/values"), b.read_double("/members/values")));
    CHECK(same(a.read_double("/members/profile"), b.read_double("/members/profile")));
  }

  // Run again: the finished file is read back (nothing computed, no batches made).
  sweep::RunStats st3;
  sweep::run_crystal_study(s, out, log, opt, &st3);
  CHECK(st3.computed == 0);
  CHECK(st3.resumed == 3);
  CHECK_FALSE(fs::exists(out + ".parts"));
  {
    io::H5Reader a(ref), b(out);
    CHECK(same(a.read_double("/members/values"), b.read_double("/members/values")));
  }
  fs::remove_all(dir);
}

TEST_CASE("spin study: FILE.parts is gone once FILE is complete, and a stopped study resumes from it", "[sweep]") {
  const auto s = sweep::parse_spin_study(smoke_text(), "smoke");
  const fs::path dir = fresh_dir("parts_cleanup_spin");
  sweep::SweepOptions o;
  o.progress = false;
  o.threads = 1;
  o.output = (dir / "smoke.h5").string();
  sweep::SweepOptions part = o;
  part.limit = 4;  // batch = 2: two batches, then stop
  const auto r1 = sweep::run_spin_study(s, part);
  CHECK(r1.stats.computed == 4);
  CHECK(batches(o.output + ".parts") == 2);
  CHECK_FALSE(fs::exists(o.output));
  const auto r2 = sweep::run_spin_study(s, o);
  CHECK(r2.stats.resumed == 4);
  CHECK(r2.stats.computed == r2.stats.total - 4);
  CHECK(fs::exists(o.output));
  CHECK_FALSE(fs::exists(o.output + ".parts"));
  fs::remove_all(dir);
}

TEST_CASE("commit_study renames first, then removes the batches, and a failed commit keeps them", "[sweep]") {
  const fs::path dir = fresh_dir("parts_cleanup_commit");
  const std::string parts = (dir / "s.h5.parts").string();
  fs::create_directories(parts);
  std::ofstream(parts + "/batch_00000000_1_0000.h5") << "x";
  {
    io::H5Writer w((dir / "s.h5").string());
    w.write("/x", std::vector<double>{1.0});
    sweep::commit_study(w, parts);
  }
  CHECK(fs::exists(dir / "s.h5"));
  CHECK_FALSE(fs::exists(parts));

  // The study file cannot be renamed into place (a directory holds its name): the batches stay.
  fs::create_directories(parts);
  std::ofstream(parts + "/batch_00000000_1_0000.h5") << "x";
  fs::create_directories(dir / "blocked.h5" / "inside");
  {
    io::H5Writer w((dir / "blocked.h5").string());
    w.write("/x", std::vector<double>{1.0});
    CHECK_THROWS(sweep::commit_study(w, parts));
  }
  CHECK(fs::exists(parts + "/batch_00000000_1_0000.h5"));
  fs::remove_all(dir);
}
