// The measures of docs/design.md §2.4, defined once and used by every verb and test.
// Signals are baseline-subtracted by the caller (e.g. sigma - sigma(t = 0)).
#pragma once
#include <cstddef>
#include <optional>
#include <span>
#include <string_view>
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

// Period T of the first oscillation: from the 1 % arrival to the third crossing of the 1 % level
// (up at the arrival, down after the leading pulse, up again after the trough that follows it),
// the end interpolated; 0 when the signal does not come back up within the window. For
// y = sin(omega (t - t0)), t > t0, it is 2 pi/omega exactly, where the duration above is
// (pi - 2 asin 0.01)/omega: a full cycle against the leading half.
double first_oscillation_period(std::span<const double> t, std::span<const double> y, const Peak& peak);

// Length of the first oscillation in a snapshot y(z) of a wave travelling towards +z (z ascending):
// from the front (the last upward crossing of `level`, searching from the far end towards the
// source) back to the third crossing of `level` (down behind the leading pulse, up again behind the
// trough), both interpolated; 0 when the profile does not cross three times. The spatial twin of
// first_oscillation_period: for y = sin(kappa (z_f - z)), z < z_f, it is 2 pi/kappa.
double first_oscillation_length(std::span<const double> z, std::span<const double> y, double level);

// Which T makes the wavelength lambda = V T of seed 002 sec. 3.4 ("the duration T of the first
// oscillation of a signal (based on first-arrival time, one per cent peak level)"):
//   oscillation: first_oscillation_period, the full first oscillation (the default: a wavelength is
//                a full cycle; it reproduces the seed's table, docs/design.md §2.4);
//   pulse:       first_oscillation_duration, the leading pulse alone (granwave's reading before).
enum class PeriodReading { oscillation, pulse };
const char* to_string(PeriodReading r);
std::optional<PeriodReading> parse_period_reading(std::string_view s);  // nullopt if neither name

// Which local speed V(z) seed 002 sec. 3.4 puts into its second wavelength table, lambda = 2 pi/k with
// k = (2/l0) arccos(V/V(k->0)) (the group speed of omega_0 sin(k l0/2) set equal to V):
//   displacement_peak: the five-layer local speed of the first peak of the layer displacement (u_z
//                      for P, u_x for S), i.e. of the instant the particle velocity's first pulse
//                      ends (the default: 8.21, 9.27, 10.10 l0 at z/l0 = 10, 15, 20 against the
//                      seed's 8.3, 9.2, 10.1, and 207.7 m/s at z/l0 = 20 against its 208,
//                      docs/design.md §2.4);
//   first_peak:        that of the measured signal's first peak (the stress; the local speed of
//                      lambda = V T and of Fig. 4; granwave's reading before).
// Both apply first_peak above and the same local-speed formula; only the signal differs.
enum class WavenumberSpeed { displacement_peak, first_peak };
const char* to_string(WavenumberSpeed r);
std::optional<WavenumberSpeed> parse_wavenumber_speed(std::string_view s);  // nullopt if neither name

// Largest sample between the 1 % arrival and the end of the first oscillation (the leading
// pulse, which may have several humps), parabola-refined like first_peak.
Peak leading_pulse_max(std::span<const double> t, std::span<const double> y, const Peak& peak);

struct SignalMeasures {
  Peak first_peak;
  Arrival half_peak;
  Arrival one_percent;
  double duration = 0.0;  // first_oscillation_duration
  double period = 0.0;    // first_oscillation_period
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
