// Helpers of the impact physics tests: a case of data/impact run at a chosen dt and measured.
#pragma once
#include <string>

#include "config/case.hpp"
#include "impact/impact.hpp"

namespace impact_test {

struct Outcome {
  granwave::impact::Setup setup;
  granwave::impact::Series series;
  granwave::impact::Rebound rebound;
};

inline granwave::impact::Setup setup_of(const std::string& file) {
  return granwave::impact::resolve(granwave::config::load_case(std::string(GRANWAVE_SOURCE_DIR) + "/data/impact/" + file));
}

// The resolved case run with dt = fraction * the closed-form contact time.
inline Outcome run_at(granwave::impact::Setup s, double fraction) {
  s.dt = fraction * s.contact_time;
  Outcome o;
  o.series = granwave::impact::simulate(s);
  o.rebound = granwave::impact::measure(granwave::impact::trace_of(s, o.series));
  o.setup = std::move(s);
  return o;
}

// max over the run of |kinetic + stored + dissipated - initial| / initial.
inline double energy_residual(const granwave::impact::Series& x) {
  double worst = 0.0;
  for (std::size_t i = 0; i < x.size(); ++i) {
    const double r = (x.kinetic[i] + x.stored[i] + x.dissipated[i] - x.kinetic[0]) / x.kinetic[0];
    worst = r > worst ? r : -r > worst ? -r : worst;
  }
  return worst;
}

}  // namespace impact_test
