// The measures of docs/design.md §2.4. Every verb, test and code comparison goes through these.
#include "analysis/measures.hpp"

#include <algorithm>
#include <cmath>
#include <stdexcept>

namespace granwave::analysis {
namespace {

void require_same_length(std::span<const double> t, std::span<const double> y) {
  if (t.size() != y.size()) throw std::invalid_argument("measures: time and signal lengths differ");
}

// Vertex of the parabola through (i-1, i, i+1); falls back to the sample at the edges or when
// the three points are collinear. Uniform sampling is not assumed.
Peak refine_parabola(std::span<const double> t, std::span<const double> y, std::size_t i) {
  Peak p{true, t[i], y[i], i};
  if (i == 0 || i + 1 >= y.size()) return p;
  const double t0 = t[i - 1], t1 = t[i], t2 = t[i + 1];
  const double y0 = y[i - 1], y1 = y[i], y2 = y[i + 1];
  // Lagrange form: y = a (t - t1)^2 + b (t - t1) + y1
  const double h0 = t0 - t1, h2 = t2 - t1;
  const double denom = h0 * h2 * (h0 - h2);
  if (denom == 0.0) return p;
  const double a = (h2 * (y0 - y1) - h0 * (y2 - y1)) / denom;
  const double b = (h0 * h0 * (y2 - y1) - h2 * h2 * (y0 - y1)) / denom;
  if (!(a < 0.0)) return p;  // not a maximum (flat or convex): keep the sample
  const double dt = -b / (2.0 * a);
  if (dt < h0 || dt > h2) return p;
  p.time = t1 + dt;
  p.value = y1 + b * dt / 2.0;  // y1 - b^2/(4a)
  return p;
}

// First local maximum at or after `start`: y[i] >= y[i-1] and y[i] > y[i+1] (a plateau
// counts once, at its first sample). The last sample counts only if the signal still rises.
std::size_t first_local_max(std::span<const double> y, std::size_t start) {
  for (std::size_t i = std::max<std::size_t>(start, 1); i + 1 < y.size(); ++i) {
    if (y[i] >= y[i - 1] && y[i] > y[i + 1]) {
      return i;
    }
  }
  return y.size() - 1;
}

}  // namespace

Peak first_peak(std::span<const double> t, std::span<const double> y, double threshold_fraction) {
  require_same_length(t, y);
  if (y.size() < 2) return {};
  const double window_max = *std::max_element(y.begin(), y.end());
  if (!(window_max > 0.0)) return {};
  const double threshold = threshold_fraction * window_max;
  std::size_t start = 0;
  while (start < y.size() && !(y[start] > threshold)) ++start;
  if (start == y.size()) return {};
  // The maximum may be exactly at `start` (a jump over the threshold): search from there.
  std::size_t i = start;
  if (i + 1 < y.size() && y[i] > y[i + 1]) return refine_parabola(t, y, i);
  i = first_local_max(y, start);
  return refine_parabola(t, y, i);
}

Arrival first_crossing(std::span<const double> t, std::span<const double> y, double level, std::size_t start) {
  require_same_length(t, y);
  if (y.empty() || start >= y.size()) return {};
  if (y[start] >= level) return {true, t[start]};
  for (std::size_t i = start + 1; i < y.size(); ++i) {
    if (y[i] >= level) {
      const double f = (level - y[i - 1]) / (y[i] - y[i - 1]);
      return {true, t[i - 1] + f * (t[i] - t[i - 1])};
    }
  }
  return {};
}

Arrival half_peak_arrival(std::span<const double> t, std::span<const double> y, const Peak& peak) {
  if (!peak.found) return {};
  return first_crossing(t, y, 0.5 * peak.value);
}

Arrival one_percent_arrival(std::span<const double> t, std::span<const double> y, const Peak& peak) {
  if (!peak.found) return {};
  return first_crossing(t, y, 0.01 * peak.value);
}

namespace {
// Index and interpolated time where the signal falls back below `level` after the peak sample.
bool end_of_first_oscillation(std::span<const double> t, std::span<const double> y, const Peak& peak,
                              std::size_t* index, double* time) {
  const double level = 0.01 * peak.value;
  for (std::size_t i = peak.index + 1; i < y.size(); ++i) {
    if (y[i] < level) {
      const double f = (y[i - 1] - level) / (y[i - 1] - y[i]);
      *index = i;
      *time = t[i - 1] + f * (t[i] - t[i - 1]);
      return true;
    }
  }
  return false;
}

// The 1 % arrival and the next 1 % crossing (the leading pulse's end); found = both exist.
struct LeadingPulse {
  bool found = false;
  double start = 0.0, end_time = 0.0;
  std::size_t end_index = 0;
};
LeadingPulse leading_pulse(std::span<const double> t, std::span<const double> y, const Peak& peak) {
  LeadingPulse p;
  const Arrival start = one_percent_arrival(t, y, peak);
  p.start = start.time;
  p.found = start.found && end_of_first_oscillation(t, y, peak, &p.end_index, &p.end_time);
  return p;
}
}  // namespace

double first_oscillation_duration(std::span<const double> t, std::span<const double> y, const Peak& peak) {
  const LeadingPulse p = leading_pulse(t, y, peak);
  return p.found ? p.end_time - p.start : 0.0;
}

double first_oscillation_period(std::span<const double> t, std::span<const double> y, const Peak& peak) {
  const LeadingPulse p = leading_pulse(t, y, peak);
  if (!p.found) return 0.0;
  // The third crossing: the first upward crossing of the 1 % level after the second one.
  const Arrival back = first_crossing(t, y, 0.01 * peak.value, p.end_index);
  if (!back.found) return 0.0;
  return back.time - p.start;
}

double first_oscillation_length(std::span<const double> z, std::span<const double> y, double level) {
  require_same_length(z, y);
  double cross[3];
  int found = 0;
  for (std::size_t i = y.size(); i-- > 1 && found < 3;) {
    // Between samples i (farther) and i - 1 (nearer the source): crossing number found + 1 is
    // upward towards the source for the 1st and 3rd, downward for the 2nd.
    const bool far_above = y[i] >= level, near_above = y[i - 1] >= level;
    if (far_above == near_above) continue;
    if ((found == 1) == near_above) continue;  // not the direction this crossing needs
    const double f = (level - y[i]) / (y[i - 1] - y[i]);
    cross[found++] = z[i] + f * (z[i - 1] - z[i]);
  }
  return found == 3 ? cross[0] - cross[2] : 0.0;
}

const char* to_string(PeriodReading r) { return r == PeriodReading::pulse ? "pulse" : "oscillation"; }

std::optional<PeriodReading> parse_period_reading(std::string_view s) {
  if (s == "oscillation") return PeriodReading::oscillation;
  if (s == "pulse") return PeriodReading::pulse;
  return std::nullopt;
}

const char* to_string(WavenumberSpeed r) {
  return r == WavenumberSpeed::first_peak ? "first_peak" : "displacement_peak";
}

std::optional<WavenumberSpeed> parse_wavenumber_speed(std::string_view s) {
  if (s == "displacement_peak") return WavenumberSpeed::displacement_peak;
  if (s == "first_peak") return WavenumberSpeed::first_peak;
  return std::nullopt;
}

Peak leading_pulse_max(std::span<const double> t, std::span<const double> y, const Peak& peak) {
  if (!peak.found) return {};
  std::size_t end_index = y.size();
  double end_time = 0.0;
  if (!end_of_first_oscillation(t, y, peak, &end_index, &end_time)) end_index = y.size();
  // From the first sample above 1 % up to the end of the leading pulse.
  std::size_t begin = 0;
  while (begin < y.size() && y[begin] < 0.01 * peak.value) ++begin;
  std::size_t best = peak.index;
  for (std::size_t i = begin; i < end_index; ++i) {
    if (y[i] > y[best]) best = i;
  }
  return refine_parabola(t, y, best);
}

SignalMeasures measure_signal(std::span<const double> t, std::span<const double> y) {
  SignalMeasures m;
  m.first_peak = first_peak(t, y);
  if (!m.first_peak.found) return m;
  m.half_peak = half_peak_arrival(t, y, m.first_peak);
  m.one_percent = one_percent_arrival(t, y, m.first_peak);
  m.duration = first_oscillation_duration(t, y, m.first_peak);
  m.period = first_oscillation_period(t, y, m.first_peak);
  m.leading_pulse = leading_pulse_max(t, y, m.first_peak);
  return m;
}

LineFit fit_line(std::span<const double> x, std::span<const double> y) {
  if (x.size() != y.size()) throw std::invalid_argument("fit_line: x and y lengths differ");
  LineFit f;
  f.n = x.size();
  if (f.n < 2) return f;
  const double n = static_cast<double>(f.n);
  double mx = 0, my = 0;
  for (std::size_t i = 0; i < f.n; ++i) {
    mx += x[i];
    my += y[i];
  }
  mx /= n;
  my /= n;
  double sxx = 0, sxy = 0;
  for (std::size_t i = 0; i < f.n; ++i) {
    sxx += (x[i] - mx) * (x[i] - mx);
    sxy += (x[i] - mx) * (y[i] - my);
  }
  if (sxx == 0.0) return f;
  f.slope = sxy / sxx;
  f.intercept = my - f.slope * mx;
  if (f.n > 2) {
    double ss = 0;
    for (std::size_t i = 0; i < f.n; ++i) {
      const double r = y[i] - f.intercept - f.slope * x[i];
      ss += r * r;
    }
    const double s2 = ss / (n - 2.0);  // residual variance
    f.slope_error = std::sqrt(s2 / sxx);
    f.intercept_error = std::sqrt(s2 * (1.0 / n + mx * mx / sxx));
  }
  return f;
}

LineFit front_speed(std::span<const double> arrival_times, std::span<const double> positions) {
  return fit_line(arrival_times, positions);
}

}  // namespace granwave::analysis
