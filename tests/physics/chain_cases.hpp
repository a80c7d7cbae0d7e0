// Inline chain cases for the chain tests (Table 1 materials of seed 001, the listing's brass wall).
#pragma once
#include <cstdio>
#include <string>

#include "config/case.hpp"

namespace chain_test {

inline std::string num(double x) {
  char b[64];
  std::snprintf(b, sizeof b, "%.17g", x);
  return b;
}

inline const char* kMaterials = R"(
[materials.large_steel]
mass = 3.63e-3
youngs_modulus = 193e9
poisson_ratio = 0.30
radius = 4.76e-3
[materials.small_steel]
mass = 0.45e-3
youngs_modulus = 193e9
poisson_ratio = 0.30
radius = 2.38e-3
[materials.aluminium]
mass = 1.26e-3
youngs_modulus = 72.4e9
poisson_ratio = 0.33
radius = 4.76e-3
[materials.brass]
youngs_modulus = 90.2e9
poisson_ratio = 0.34
)";

// A chain case from its [chain] ... tables; materials and the [case] header are added.
inline granwave::config::Case chain_case(const std::string& body) {
  return granwave::config::parse_case(
      "[case]\nname = \"test\"\nmodel = \"chain\"\n" + std::string(kMaterials) + body, "inline test case");
}

// A homogeneous large-steel chain: striker + `n_after` beads, wall "brass" or "free".
inline granwave::config::Case steel_chain(int n_after, double v0, const std::string& wall, double F0 = 0.0,
                                          double dt = 1e-8, double t_end = 1e-3) {
  return chain_case("[chain]\nstriker = { material = \"large_steel\", velocity = " + num(v0) +
                    " }\nwall = \"" + wall + "\"\nprecompression = " + num(F0) +
                    "\n[[chain.segment]]\nbeads = [\"large_steel\"]\nrepeat = " + std::to_string(n_after) +
                    "\n[integrator]\ndt = " + num(dt) + "\nt_end = " + num(t_end) + "\n");
}

}  // namespace chain_test
