// The guards' estimates of a run's cost against the machine's limits (core/resources.hpp).
#include "core/resources.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <sstream>

#include "core/error.hpp"
#include "core/format.hpp"

namespace granwave {
double available_memory() {
  std::ifstream in("/proc/meminfo");
  std::string key, unit;
  double kib = 0.0;
  while (in >> key >> kib) {
    std::getline(in, unit);
    if (key == "MemAvailable:") return kib * 1024.0;
  }
  return 0.0;
}

double memory_limit(const ResourceLimits& l, std::string* source) {
  if (l.max_memory > 0.0) {
    if (source) *source = "--max-memory";
    return l.max_memory;
  }
  const double m = available_memory();
  if (source) *source = m > 0.0 ? "MemAvailable of /proc/meminfo" : "unknown: /proc/meminfo unreadable, not checked";
  return m;
}

std::string bytes_text(double b) {
  if (!std::isfinite(b)) return "an infinite amount";
  const char* unit[] = {"B", "kB", "MB", "GB", "TB", "PB", "EB"};
  int u = 0;
  while (b >= 1000.0 && u < 6) b /= 1000.0, ++u;
  return fmt(b < 10 ? "%.2g" : b < 1000 ? "%.0f" : "%.3g", b) + " " + unit[u];
}

void Assessment::require_finite(const std::string& name, double value, const std::string& keys, bool positive) {
  if (std::isfinite(value) && (!positive || value > 0.0)) return;
  refusals.push_back(name + " = " + fmt("%.6g", value) + " is not " + (positive ? "a finite positive number" : "finite") +
                     "; change " + keys);
}

void check_resources(Assessment& a, const ResourceLimits& l) {
  const ResourceEstimate& e = a.estimate;
  if (!(e.steps <= l.max_steps))
    a.refusals.push_back(fmt("%.6g", e.steps) + " time steps (" + e.size + ") exceed the limit of " + fmt("%.6g", l.max_steps) +
                         " steps; change " + e.steps_keys + ", or raise the limit with --max-steps N");
  std::string source;
  const double limit = memory_limit(l, &source);
  const double need = e.memory * std::max(1, l.parallel_runs);
  if (limit > 0.0 && !(need <= limit))
    a.refusals.push_back("the run (" + e.size + (e.samples > 0 ? ", " + fmt("%.6g", e.samples) + " samples" : std::string()) +
                         ") needs about " + bytes_text(need) +
                         (l.parallel_runs > 1 ? " (" + std::to_string(l.parallel_runs) + " runs at once)" : std::string()) +
                         " of memory, more than the " + bytes_text(limit) + " available (" + source + "); change " +
                         e.memory_keys + (l.parallel_runs > 1 ? ", use fewer --threads" : "") +
                         ", or set the limit with --max-memory SIZE");
}

void check_output_space(Assessment& a, const std::string& path) {
  namespace fs = std::filesystem;
  std::error_code ec;
  fs::path dir = fs::absolute(fs::path(path), ec).parent_path();
  while (!dir.empty() && !fs::exists(dir, ec) && dir != dir.parent_path()) dir = dir.parent_path();
  const auto sp = fs::space(dir, ec);
  if (ec) return;  // unknown: not checked
  const double avail = static_cast<double>(sp.available);
  if (!(a.estimate.output <= avail))
    a.refusals.push_back("the output needs about " + bytes_text(a.estimate.output) + ", more than the " + bytes_text(avail) +
                         " free in " + dir.string() + "; change " + a.estimate.memory_keys + " or write elsewhere (-o)");
}

void enforce(const Assessment& a, const std::string& origin) {
  if (a.refusals.empty()) return;
  std::string msg = origin + ": refused:";
  for (const auto& r : a.refusals) msg += "\n  " + r;
  throw InputError(msg);
}

std::string describe(const ResourceEstimate& e, const ResourceLimits& l) {
  std::string source;
  const double limit = memory_limit(l, &source);
  std::ostringstream s;
  s << fmt("%.6g", e.steps) << " steps of " << e.size << " (limit " << fmt("%.4g", l.max_steps) << ", --max-steps), "
    << fmt("%.6g", e.samples) << " samples; memory ~ " << bytes_text(e.memory) << " of "
    << (limit > 0.0 ? bytes_text(limit) : std::string("?")) << " (" << source << "); output ~ " << bytes_text(e.output);
  return s.str();
}

double leading_number(const std::string& text, std::size_t* used) {
  *used = 0;
  try {
    return std::stod(text, used);
  } catch (const std::exception&) {
    *used = 0;
    return 0.0;
  }
}

double parse_count(const std::string& option, const std::string& text) {
  std::size_t used = 0;
  const double v = leading_number(text, &used);
  if (used != text.size() || !std::isfinite(v) || !(v >= 1.0))
    throw InputError(option + " must be a number >= 1 (got '" + text + "')");
  return std::floor(v);
}

double parse_bytes(const std::string& option, const std::string& text) {
  std::size_t used = 0;
  const double v = leading_number(text, &used);
  double scale = 1.0;
  if (used > 0 && used + 1 == text.size()) {
    switch (text.back()) {
      case 'k': case 'K': scale = 1e3; break;
      case 'M': scale = 1e6; break;
      case 'G': scale = 1e9; break;
      case 'T': scale = 1e12; break;
      default: used = 0;
    }
    if (used) ++used;
  }
  if (used == 0 || used != text.size() || !std::isfinite(v) || !(v > 0.0))
    throw InputError(option + " must be a size in bytes > 0, optionally with k, M, G or T (got '" + text + "')");
  return v * scale;
}

}  // namespace granwave
