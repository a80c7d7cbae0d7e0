// The measures of docs/design.md §2.4, defined once and used by every verb and test.
// Signals are baseline-subtracted by the caller (e.g. sigma - sigma(t = 0)).
#pragma once
#include <cstddef>
#include <span>
#include <vector>

namespace granwave::analysis {

struct Peak {
  bool found = false;
  double time = 0.0;   // parabola-refined time of the maximum (s)
  double value = 0.0;  // parabola-refined maximum
  std::size_t index = 0;  // sample of the discrete maximum
};

struct Arrival {
  bool found = false;
  double time = 0.0;  // linearly interpolated crossing time (s)
};

// First peak: the first local maximum after the signal first exceeds `threshold_fraction`
// (30 %) of its maximum over the window, refined by a parabola through three samples.
Peak first_peak(std::span<const double> t, std::span<const double> y, double threshold_fraction = 0.3);

// First upward crossing of `level` at or after sample `start`, linearly interpolated.
Arrival first_crossing(std::span<const double> t, std::span<const double> y, double level, std::size_t start = 0);

// Half-peak arrival: first crossing of half the first peak.
Arrival half_peak_arrival(std::span<const double> t, std::span<const double> y, const Peak& peak);

// 1 % arrival: first crossing of 1 % of the first peak.
Arrival one_percent_arrival(std::span<const double> t, std::span<const double> y, const Peak& peak);

// Duration T of the first oscillation: from the 1 % arrival to the next (downward) crossing
// of the 1 % level; 0 when the signal never falls back within the window.
double first_oscillation_duration(std::span<const double> t, std::span<const double> y, const Peak& peak);

// Largest sample between the 1 % arrival and the end of the first oscillation (the leading
// pulse, which may have several humps), parabola-refined like first_peak.
Peak leading_pulse_max(std::span<const double> t, std::span<const double> y, const Peak& peak);

struct SignalMeasures {
  Peak first_peak;
  Arrival half_peak;
  Arrival one_percent;
  double duration = 0.0;
  Peak leading_pulse;
};
SignalMeasures measure_signal(std::span<const double> t, std::span<const double> y);

// Least-squares line y = intercept + slope x with standard errors (needs >= 3 points for errors).
struct LineFit {
  double slope = 0.0, intercept = 0.0;
  double slope_error = 0.0, intercept_error = 0.0;
  std::size_t n = 0;
};
LineFit fit_line(std::span<const double> x, std::span<const double> y);

// Front speed: fit of position against arrival time; slope = speed (position units per s).
LineFit front_speed(std::span<const double> arrival_times, std::span<const double> positions);

}  // namespace granwave::analysis
