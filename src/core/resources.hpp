// Guards at the edge (data/SCHEMA.md §1, "Limits and refusals"): `check`, `run` and `sweep`
// estimate what a run costs (steps, memory, output) from the case, before anything large is
// allocated, and refuse (exit code 2) a case over a limit, naming the keys that set the cost. The
// models add their own refusals for cases that cannot mean anything (an unstable dt, an overlap
// that reaches the radius, a derived number that is not finite) and warnings outside the model's
// validity: chain/guards.hpp, crystal/guards.hpp.
#pragma once
#include <string>
#include <vector>

namespace granwave {

// Steps of one run above which check and run refuse (--max-steps overrides): 1e9 steps is about
// 10 s per bead or particle at the measured 1e8 bead-steps/s of the chain.
inline constexpr double kDefaultMaxSteps = 1e9;
// The contact laws assume overlaps small against the radius (Hertz, seed 001 eq. 13; the linear
// spring, seed 002 eq. 1): warn above this fraction of the smaller radius, refuse at 1.
inline constexpr double kOverlapWarnFraction = 0.05;

struct ResourceLimits {
  double max_steps = kDefaultMaxSteps;  // --max-steps
  double max_memory = 0.0;              // bytes (--max-memory); 0: the machine's MemAvailable
  int parallel_runs = 1;                // runs in memory at once (a sweep's threads)
};

// MemAvailable of /proc/meminfo in bytes; 0 when it cannot be read.
double available_memory();
// The memory limit in bytes; `source` says where it comes from.
double memory_limit(const ResourceLimits& limits, std::string* source = nullptr);

// What one run costs, estimated from the case before it runs.
struct ResourceEstimate {
  double steps = 0.0;    // time steps
  double samples = 0.0;  // stored output samples
  double memory = 0.0;   // peak bytes of one run (an estimate from measured per-item costs, rounded up)
  double output = 0.0;   // bytes written (trace file, snapshots)
  std::string size;      // "41 beads", "3200 particles"
  std::string steps_keys, memory_keys;  // the case keys that set the steps and the memory
};

// The guards' verdict on a case: every refusal names its keys and numbers; warnings do not stop it.
struct Assessment {
  ResourceEstimate estimate;
  std::vector<std::string> refusals, warnings;
  // Refuses `name` = value unless it is finite (and > 0 when `positive`); `keys` set it.
  void require_finite(const std::string& name, double value, const std::string& keys, bool positive = true);
};

// Adds the refusals of steps and memory over `limits` to `a`.
void check_resources(Assessment& a, const ResourceLimits& limits);
// Adds a refusal when the output would not fit on the file system that holds `path`.
void check_output_space(Assessment& a, const std::string& path);
// Throws InputError("<origin>: refused: ...") with every refusal, one per line; no-op without any.
void enforce(const Assessment& a, const std::string& origin);
// "150000 steps (limit 1e+09, --max-steps), 6002 samples, memory ~ 4.2 MB of 20 GB (MemAvailable ...), output ~ 3.9 MB"
std::string describe(const ResourceEstimate& e, const ResourceLimits& limits);
std::string bytes_text(double bytes);

// Command-line values: a positive count ("1e9", "150000") and a size ("8G", "512M", "1e9").
// Throw InputError naming the option.
double parse_count(const std::string& option, const std::string& text);
// The number at the start of `text` (std::stod) and in *used the characters it took (0: none).
double leading_number(const std::string& text, std::size_t* used);
double parse_bytes(const std::string& option, const std::string& text);

}  // namespace granwave
