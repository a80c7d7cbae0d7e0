// Energies of the coherent front and of the coda (analysis/coda.hpp).
#include "analysis/coda.hpp"

#include <algorithm>
#include <cmath>

namespace granwave::analysis {

FrontCoda front_and_coda(std::span<const double> t, std::span<const double> y, double t_arrival, double duration,
                         double t_stop) {
  FrontCoda r;
  const double nan = std::nan("");
  if (t.size() < 2 || !std::isfinite(t_arrival) || !std::isfinite(duration) || !(duration > 0.0)) {
    r.front = r.coda = r.coda_end = nan;
    return r;
  }
  const double dt = t[1] - t[0], front_end = t_arrival + duration;
  r.coda_end = std::min(std::isfinite(t_stop) ? t_stop : t.back(), t.back() + dt);
  for (std::size_t n = 0; n < t.size() && n < y.size(); ++n) {
    const double e = y[n] * y[n] * dt;
    if (t[n] >= t_arrival && t[n] < front_end) r.front += e;
    else if (t[n] >= front_end && t[n] < r.coda_end) r.coda += e;
  }
  return r;
}

}  // namespace granwave::analysis
