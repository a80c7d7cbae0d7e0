// The crystal benchmarks' cases and timing (bench/bench_crystal.cpp, bench/bench_frame.cpp): seed 002's
// crystal with and without friction, a crystal excited by a step of its source layers, and the fastest of
// single calls.
#pragma once
#include <algorithm>
#include <chrono>
#include <cstdlib>
#include <string>
#include <vector>

#include "config/case.hpp"
#include "crystal/derive.hpp"
#include "crystal/dynamics.hpp"
#include "crystal/packing.hpp"

namespace granwave::bench {

// data/cases/crystal_p.toml (seed 002's P wave) with `layers` cells in z, k_t and the lever arm.
inline config::Case seed_case(int layers, double kt, config::LeverArm arm = config::LeverArm::radius) {
  config::Case c = config::load_case(std::string(GRANWAVE_SOURCE_DIR) + "/data/cases/crystal_p.toml");
  c.crystal->cells[2] = layers;
  c.contact.set_number("kt", kt);
  c.contact.friction().lever_arm = arm;
  return c;
}

// Case c's crystal with its source layers displaced by 1e-4 d in z, so that the forces are not trivial.
inline crystal::Dynamics excited(const config::Case& c) {
  const crystal::Packing p = crystal::make_packing(c);
  crystal::Dynamics dyn(p, crystal::case_model(c.contact, c.crystal->density), crystal::derive(c).dt);
  std::vector<std::size_t> source;
  for (std::size_t q = 0; q < p.size(); ++q)
    if (p.layer[q] < p.fixed_layers) source.push_back(q);
  dyn.displace(source, 0.0, 0.0, 1e-4 * p.d);
  return dyn;
}

// argv[k] as a whole number >= 1, or `fallback` where there is none; anything else calls usage() (which exits 2).
inline long whole_argument(int argc, char** argv, int k, long fallback, void (*usage)()) {
  if (argc <= k) return fallback;
  char* end = nullptr;
  const long v = std::strtol(argv[k], &end, 10);
  if (end == argv[k] || *end != '\0' || v < 1) usage();
  return v;
}

// Fastest of `calls` single calls of f, in seconds.
template <class F>
double fastest(int calls, F&& f) {
  double best = 1e300;
  for (int k = 0; k < calls; ++k) {
    const auto t0 = std::chrono::steady_clock::now();
    f();
    best = std::min(best, std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count());
  }
  return best;
}

}  // namespace granwave::bench
