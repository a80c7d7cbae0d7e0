// Resumption after `kill -9`, through the real binary: the killed sweep leaves committed batches
// and no study file; the restart computes only what is missing and ends with the datasets of an
// uninterrupted run (provenance attributes aside).
#include <signal.h>
#include <sys/wait.h>
#include <unistd.h>

#include <catch2/catch.hpp>
#include <chrono>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <regex>
#include <sstream>
#include <thread>

#include "../test_support.hpp"
#include "io/h5.hpp"

namespace fs = std::filesystem;

namespace {
std::string read(const fs::path& p) {
  std::ifstream in(p);
  std::stringstream ss;
  ss << in.rdbuf();
  return ss.str();
}
std::size_t batches(const fs::path& dir) {
  std::size_t n = 0;
  if (!fs::is_directory(dir)) return 0;
  for (const auto& e : fs::directory_iterator(dir))
    if (e.path().extension() == ".h5") ++n;
  return n;
}
bool same_bits(const std::vector<double>& a, const std::vector<double>& b) {
  return a.size() == b.size() && std::memcmp(a.data(), b.data(), a.size() * sizeof(double)) == 0;
}
}  // namespace

TEST_CASE("kill -9 mid-sweep, restart: only the missing runs, same datasets") {
  const std::string bin = GRANWAVE_BINARY;
  // Without the binary nothing is tested: a ctest skip (a failure outside ctest), never a pass.
  if (!fs::exists(bin)) test_support::skip("no granwave binary at " + bin + " (build the granwave target first)");
  const fs::path dir = fs::temp_directory_path() / ("granwave_kill_test_" + std::to_string(getpid()));
  fs::remove_all(dir);
  fs::create_directories(dir);
  std::string text = read(fs::path(GRANWAVE_SOURCE_DIR) / "data/studies/smoke.toml");
  auto sub = [&](const std::string& a, const std::string& b) {
    const auto p = text.find(a);
    REQUIRE(p != std::string::npos);
    text.replace(p, a.size(), b);
  };
  sub("n_total = [8]", "n_total = [24]");
  sub("configurations = 3", "configurations = 12");
  sub("batch = 2", "batch = 3");
  const fs::path study = dir / "kill.toml", out = dir / "kill.h5", parts = dir / "kill.h5.parts";
  std::ofstream(study) << text;

  const pid_t pid = fork();
  REQUIRE(pid >= 0);
  if (pid == 0) {
    freopen("/dev/null", "w", stdout);
    execl(bin.c_str(), bin.c_str(), "sweep", study.c_str(), "-o", out.c_str(), "--quiet", "--threads", "1", nullptr);
    _exit(127);
  }
  const auto t0 = std::chrono::steady_clock::now();
  while (batches(parts) < 2 && std::chrono::steady_clock::now() - t0 < std::chrono::seconds(120))
    std::this_thread::sleep_for(std::chrono::milliseconds(1));
  kill(pid, SIGKILL);
  int status = 0;
  waitpid(pid, &status, 0);
  REQUIRE(WIFSIGNALED(status));  // killed mid-way, not finished
  REQUIRE(!fs::exists(out));
  const std::size_t committed = batches(parts);
  REQUIRE(committed >= 2);

  const std::string log = (dir / "resume.log").string();
  REQUIRE(std::system((bin + " sweep " + study.string() + " -o " + out.string() + " --quiet > " + log).c_str()) == 0);
  std::smatch m;
  const std::string summary = read(log);
  REQUIRE(std::regex_search(summary, m, std::regex(R"(runs: (\d+) \((\d+) computed, (\d+) resumed\))")));
  const long total = std::stol(m[1]), computed = std::stol(m[2]), resumed = std::stol(m[3]);
  INFO(summary.substr(summary.find("runs:")));
  REQUIRE(total == 12 * 12 + 1);
  REQUIRE(resumed >= static_cast<long>(3 * committed));
  REQUIRE(computed == total - resumed);
  REQUIRE(!fs::exists(parts));

  const fs::path ref = dir / "ref.h5";
  REQUIRE(std::system((bin + " sweep " + study.string() + " -o " + ref.string() + " --quiet > /dev/null").c_str()) == 0);
  granwave::io::H5Reader a(out.string()), b(ref.string());
  for (const char* d : {"/members/values", "/members/profile", "/members/measure_norm", "/members/decay_rate",
                        "/members/work", "/groups/N24/M", "/groups/N24/mean", "/groups/N24/median", "/groups/N24/q25"})
    REQUIRE(same_bits(a.read_double(d), b.read_double(d)));
  REQUIRE(a.read_int("/members/index") == b.read_int("/members/index"));
  REQUIRE(a.read_strings("/members/label") == b.read_strings("/members/label"));
  for (const char* k : {"mc", "mc_lo", "mc_hi", "reference_measure"})
    REQUIRE(a.attr_double("/groups/N24", k) == b.attr_double("/groups/N24", k));
  fs::remove_all(dir);
}
