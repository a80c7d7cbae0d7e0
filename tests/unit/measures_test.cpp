// The measures of docs/design.md §2.4 on signals whose answers are known in closed form.
#include <catch2/catch.hpp>

#include <cmath>
#include <string>
#include <vector>

#include "analysis/measures.hpp"

using namespace granwave::analysis;

namespace {
std::vector<double> linspace(double a, double b, int n) {
  std::vector<double> v(n);
  for (int i = 0; i < n; ++i) v[i] = a + (b - a) * i / (n - 1);
  return v;
}
}  // namespace

TEST_CASE("first peak of a parabola-shaped bump is exact", "[measures]") {
  // y = 1 - ((t - 0.3137)/0.1)^2 inside the bump: a parabola, so the 3-point refinement is exact.
  auto t = linspace(0.0, 1.0, 101);
  std::vector<double> y(t.size());
  for (std::size_t i = 0; i < t.size(); ++i) y[i] = std::max(0.0, 1.0 - std::pow((t[i] - 0.3137) / 0.1, 2));
  Peak p = first_peak(t, y);
  REQUIRE(p.found);
  CHECK(p.time == Approx(0.3137).epsilon(1e-12));
  CHECK(p.value == Approx(1.0).epsilon(1e-12));
}

TEST_CASE("first peak ignores precursors below 30 % and takes the first hump above", "[measures]") {
  auto t = linspace(0.0, 10.0, 1001);
  std::vector<double> y(t.size());
  auto bump = [](double t, double c, double a) { return a * std::exp(-std::pow((t - c) / 0.3, 2)); };
  for (std::size_t i = 0; i < t.size(); ++i) y[i] = bump(t[i], 2.0, 0.2) + bump(t[i], 5.0, 0.6) + bump(t[i], 8.0, 1.0);
  Peak p = first_peak(t, y);
  REQUIRE(p.found);
  CHECK(p.time == Approx(5.0).margin(2e-3));   // the 0.6 hump: first above 0.3 of the max
  CHECK(p.value == Approx(0.6).epsilon(1e-3));
  SignalMeasures m = measure_signal(t, y);
  // Half-peak crossing of a Gaussian: c - w sqrt(ln 2) (the 0.2 hump never reaches 0.3).
  CHECK(m.half_peak.time == Approx(5.0 - 0.3 * std::sqrt(std::log(2.0))).margin(1e-3));
}

TEST_CASE("arrivals and duration of a half-sine pulse", "[measures]") {
  // y = sin(pi (t - 1)/2) on [1, 3], 0 elsewhere: 1 % crossings at 1 + (2/pi) asin(0.01) and its mirror.
  auto t = linspace(0.0, 4.0, 40001);
  std::vector<double> y(t.size());
  for (std::size_t i = 0; i < t.size(); ++i) y[i] = (t[i] > 1 && t[i] < 3) ? std::sin(M_PI * (t[i] - 1) / 2) : 0.0;
  SignalMeasures m = measure_signal(t, y);
  const double a = 2.0 / M_PI * std::asin(0.01);
  CHECK(m.one_percent.time == Approx(1.0 + a).margin(1e-6));
  CHECK(m.half_peak.time == Approx(1.0 + 2.0 / M_PI * std::asin(0.5)).margin(1e-6));
  CHECK(m.duration == Approx(2.0 - 2 * a).margin(1e-6));
  CHECK(m.first_peak.time == Approx(2.0).margin(1e-6));
  CHECK(m.leading_pulse.value == Approx(1.0).margin(1e-6));
}

TEST_CASE("leading-pulse maximum finds the larger second hump of one pulse", "[measures]") {
  auto t = linspace(0.0, 10.0, 2001);
  std::vector<double> y(t.size());
  for (std::size_t i = 0; i < t.size(); ++i) {
    y[i] = 0.6 * std::exp(-std::pow((t[i] - 4.0) / 0.5, 2)) + 1.0 * std::exp(-std::pow((t[i] - 5.0) / 0.5, 2));
  }
  SignalMeasures m = measure_signal(t, y);
  CHECK(m.first_peak.time < 4.5);
  CHECK(m.leading_pulse.time > 4.8);
  CHECK(m.leading_pulse.value > m.first_peak.value);
}

TEST_CASE("line fit recovers slope and its standard error", "[measures]") {
  std::vector<double> x{0, 1, 2, 3, 4}, y{1, 3, 5, 7, 9};
  LineFit f = fit_line(x, y);
  CHECK(f.slope == Approx(2.0));
  CHECK(f.intercept == Approx(1.0));
  CHECK(f.slope_error == Approx(0.0).margin(1e-12));
  // Residuals +e, -e pattern: known closed-form standard error.
  std::vector<double> y2{1.1, 2.9, 5.1, 6.9, 9.1};
  LineFit g = fit_line(x, y2);
  // s2 = sum r^2/(n-2) with r from the fit; sxx = 10.
  double ss = 0;
  for (int i = 0; i < 5; ++i) ss += std::pow(y2[i] - g.intercept - g.slope * x[i], 2);
  CHECK(g.slope_error == Approx(std::sqrt(ss / 3.0 / 10.0)));
  CHECK(g.slope_error > 0.0);
}

TEST_CASE("a signal that never rises has no peak", "[measures]") {
  std::vector<double> t{0, 1, 2}, y{0, -1, -2};
  CHECK_FALSE(first_peak(t, y).found);
  CHECK_FALSE(measure_signal(t, y).half_peak.found);
}

TEST_CASE("period of the first oscillation of a sine is its period, the duration the leading half", "[measures]") {
  // y = sin(omega (t - t0)) for t > t0, a decaying tail after three cycles: the 1 % level is crossed
  // at t0 + asin(0.01)/omega (up), t0 + (pi - asin(0.01))/omega (down) and
  // t0 + (2 pi + asin(0.01))/omega (up again), so the period reading is 2 pi/omega exactly and the
  // duration (pi - 2 asin(0.01))/omega. lambda = V T with the period is the wavelength V 2 pi/omega.
  const double t0 = 1.0, omega = 3.7;
  auto t = linspace(0.0, 10.0, 100001);
  std::vector<double> y(t.size());
  for (std::size_t i = 0; i < t.size(); ++i) {
    const double s = t[i] - t0;
    y[i] = s <= 0 ? 0.0 : std::sin(omega * s) * (s < 6 * M_PI / omega ? 1.0 : std::exp(-(s - 6 * M_PI / omega)));
  }
  const SignalMeasures m = measure_signal(t, y);
  REQUIRE(m.first_peak.found);
  const double a = std::asin(0.01) / omega;
  CHECK(m.one_percent.time == Approx(t0 + a).margin(1e-7));
  CHECK(m.period == Approx(2 * M_PI / omega).margin(1e-7));
  CHECK(m.duration == Approx(M_PI / omega - 2 * a).margin(1e-7));
  CHECK(first_oscillation_period(t, y, m.first_peak) == m.period);
}

TEST_CASE("period is 0 when the signal does not come back up within the window, and the reading names", "[measures]") {
  // A half-sine pulse and silence: the leading pulse ends, no third crossing.
  auto t = linspace(0.0, 4.0, 4001);
  std::vector<double> y(t.size());
  for (std::size_t i = 0; i < t.size(); ++i) y[i] = (t[i] > 1 && t[i] < 3) ? std::sin(M_PI * (t[i] - 1) / 2) : 0.0;
  const SignalMeasures m = measure_signal(t, y);
  CHECK(m.duration > 0.0);
  CHECK(m.period == 0.0);
  CHECK(parse_period_reading("oscillation") == PeriodReading::oscillation);
  CHECK(parse_period_reading("pulse") == PeriodReading::pulse);
  CHECK_FALSE(parse_period_reading("Pulse"));
  CHECK(std::string(to_string(PeriodReading::pulse)) == "pulse");
  CHECK(std::string(to_string(PeriodReading::oscillation)) == "oscillation");
  CHECK(parse_wavenumber_speed("displacement_peak") == WavenumberSpeed::displacement_peak);
  CHECK(parse_wavenumber_speed("first_peak") == WavenumberSpeed::first_peak);
  CHECK_FALSE(parse_wavenumber_speed("half_peak"));
  CHECK(std::string(to_string(WavenumberSpeed::displacement_peak)) == "displacement_peak");
  CHECK(std::string(to_string(WavenumberSpeed::first_peak)) == "first_peak");
}

TEST_CASE("length of the first oscillation of a snapshot sin(kappa (z_f - z)) is its wavelength", "[measures]") {
  // A wave travelling to +z whose front is at z_f: y = sin(kappa (z_f - z)) behind it (three cycles,
  // then quiet towards the source), 0 ahead. Crossings of the 1 % level from the far end: the front
  // at z_f - asin(0.01)/kappa, then z_f - (pi - asin(0.01))/kappa, then z_f - (2 pi + asin(0.01))/kappa.
  const double zf = 7.3, kappa = 2.9;
  auto z = linspace(0.0, 10.0, 100001);
  std::vector<double> y(z.size());
  for (std::size_t i = 0; i < z.size(); ++i) {
    const double s = zf - z[i];
    y[i] = s <= 0 || s > 6 * M_PI / kappa ? 0.0 : std::sin(kappa * s);
  }
  CHECK(first_oscillation_length(z, y, 0.01) == Approx(2 * M_PI / kappa).margin(1e-7));
  // The leading pulse alone (no trough behind it): not three crossings.
  for (std::size_t i = 0; i < z.size(); ++i) y[i] = std::max(0.0, y[i]) * (zf - z[i] < M_PI / kappa ? 1.0 : 0.0);
  CHECK(first_oscillation_length(z, y, 0.01) == 0.0);
}
