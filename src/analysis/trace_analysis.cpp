// The measures of any code's trace, one ruler (analysis/trace_analysis.hpp).
#include "analysis/trace_analysis.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <limits>

#include "analysis/coda.hpp"
#include "core/error.hpp"

namespace granwave::analysis {
namespace {

// ---------- per-signal errors ----------

// Bound on the error of a linearly interpolated crossing at time tc: h^2 |y''| / (8 |y'|).
double crossing_error(std::span<const double> t, std::span<const double> y, double tc) {
  const std::size_t n = t.size();
  if (n < 3 || !std::isfinite(tc)) return kNaN;
  std::size_t i = std::upper_bound(t.begin(), t.end(), tc) - t.begin();
  i = std::clamp<std::size_t>(i, 1, n - 1);
  const double h = t[i] - t[i - 1];
  const double slope = (y[i] - y[i - 1]) / h;
  const std::size_t c = std::clamp<std::size_t>(i, 1, n - 2);  // centre of a second difference
  const double curv = (y[c + 1] - 2 * y[c] + y[c - 1]) / (h * h);
  if (slope == 0.0) return 0.5 * h;
  return std::min(0.5 * h, h * h * std::abs(curv) / (8.0 * std::abs(slope)));
}

// Model error of the refined peak: the parabola (measures.hpp) and the Gaussian (log-parabola)
// through the same three samples are equally plausible; their difference is the uncertainty.
void peak_errors(std::span<const double> t, std::span<const double> y, const Peak& p, double* t_err, double* v_err) {
  const std::size_t i = p.index;
  *t_err = kNaN;
  *v_err = kNaN;
  if (!p.found || i == 0 || i + 1 >= y.size()) return;
  const double h = 0.5 * (t[i + 1] - t[i - 1]);
  if (!(y[i - 1] > 0.0 && y[i] > 0.0 && y[i + 1] > 0.0)) {
    *t_err = 0.5 * h;
    *v_err = std::abs(p.value - y[i]);
    return;
  }
  const double l0 = std::log(y[i - 1]), l1 = std::log(y[i]), l2 = std::log(y[i + 1]);
  const double den = l0 - 2 * l1 + l2;
  if (!(den < 0.0)) {
    *t_err = 0.5 * h;
    *v_err = std::abs(p.value - y[i]);
    return;
  }
  const double shift = 0.5 * h * (l0 - l2) / den;
  const double tg = t[i] + shift;
  const double vg = std::exp(l1 - 0.125 * (l0 - l2) * (l0 - l2) / den);
  *t_err = std::abs(tg - p.time);
  *v_err = std::abs(vg - p.value);
}

Measured measured(double v, double e) { return {v, e}; }

// All docs/design.md §2.4 measures of one baseline-subtracted signal, with their errors.
struct Signal {
  bool arrived = false;
  Measured peak_time, peak_value, half, one, duration, period, leading;
};
Signal measure_with_errors(std::span<const double> t, std::span<const double> y) {
  Signal s;
  const SignalMeasures m = measure_signal(t, y);
  const Peak& p = m.first_peak;
  // A first peak at the last sample is a signal still rising: not arrived.
  s.arrived = p.found && p.value > 0.0 && p.index + 1 < y.size();
  if (!s.arrived) return s;
  double te, ve;
  peak_errors(t, y, p, &te, &ve);
  s.peak_time = measured(p.time, te);
  s.peak_value = measured(p.value, ve);
  if (m.half_peak.found) s.half = measured(m.half_peak.time, crossing_error(t, y, m.half_peak.time));
  if (m.one_percent.found) s.one = measured(m.one_percent.time, crossing_error(t, y, m.one_percent.time));
  if (m.one_percent.found && m.duration > 0.0) {
    const double e1 = s.one.error, e2 = crossing_error(t, y, m.one_percent.time + m.duration);
    s.duration = measured(m.duration, std::hypot(e1, e2));
  }
  if (m.one_percent.found && m.period > 0.0)
    s.period = measured(m.period, std::hypot(s.one.error, crossing_error(t, y, m.one_percent.time + m.period)));
  if (m.leading_pulse.found) {
    peak_errors(t, y, m.leading_pulse, &te, &ve);
    s.leading = measured(m.leading_pulse.value, ve);
  }
  return s;
}

// A wave from the source reaches the layers (contacts) in order of distance: the front cannot skip
// one, and a farther one cannot peak before the pulse at the nearer one has begun. Beyond the
// front a signal can still show a local maximum, in noise or in a precursor: on the 160-layer P
// crystal cut at t = 0.78 ms (front at z/l0 = 117), layers 143..156 had "first peaks" of 1e-10 of
// the pulse at t = 16 us .. 0.71 ms; crystal_small (3 x 3 x 40, 0.1 ms) at z/l0 = 29..34 and
// crystal_poly2 at 191, 194..196. So, from the first signal that arrived (the one next to a held
// source, z/l0 = 1, may have none) outwards, a signal counts as an arrival only while every one
// before it arrived and its first peak is not earlier than the previous one's 1 % arrival; the
// rest are cleared (not arrived, no measures). Not "not earlier than the previous first peak":
// first peaks of neighbours need not be ordered (disordered chains, whose pulses have several
// humps: experiment68 contacts 40/41 peak at 0.810/0.796 ms; the wall contact of oriented20 before
// contact 39; layers near a fixed end, where the reflection makes the first peak). `s` is ordered
// from the source outwards.
void keep_causal_arrivals(std::vector<Signal>& s) {
  bool started = false, ended = false;
  double t_begun = -std::numeric_limits<double>::infinity();  // 1 % arrival of the previous arrival
  for (auto& x : s) {
    if (!ended && x.arrived && x.peak_time.value >= t_begun) {
      started = true;
      t_begun = std::isfinite(x.one.value) ? x.one.value : x.peak_time.value;
      continue;
    }
    if (started) ended = true;
    x = Signal{};
  }
}

// A reading of the seed (measures.hpp): the option's, else the case's, else the default already set.
template <class T>
void choose_reading(const std::optional<T>& option, const std::optional<T>& from_case, T* reading, std::string* source) {
  if (option) {
    *reading = *option;
    *source = "option";
  } else if (from_case) {
    *reading = *from_case;
    *source = "case_toml";
  }
}

SpeedFit fit_speed(const std::string& name, const std::vector<double>& times, const std::vector<double>& z,
                   const std::vector<int>& zl, int lo, int hi) {
  SpeedFit f;
  f.measure = name;
  f.lo = lo;
  f.hi = hi;
  std::vector<double> tt, zz;
  for (std::size_t i = 0; i < times.size(); ++i)
    if (zl[i] >= lo && zl[i] <= hi && std::isfinite(times[i])) tt.push_back(times[i]), zz.push_back(z[i]);
  f.n = tt.size();
  if (f.n < 3) return f;
  const LineFit lf = front_speed(tt, zz);
  f.speed = {lf.slope, lf.slope_error};
  f.intercept = lf.intercept;
  return f;
}

}  // namespace

// ---------- crystal ----------

std::vector<Measured> local_speeds(const std::vector<double>& t, double dz) {
  std::vector<Measured> v(t.size());
  static constexpr double w[4] = {1.0 / 6, 2.0 / 6, 2.0 / 6, 1.0 / 6};
  for (std::size_t i = 2; i + 2 < t.size(); ++i) {
    double d[4], s = 0.0;
    bool ok = true;
    for (int j = 0; j < 4; ++j) {
      d[j] = t[i - 2 + j + 1] - t[i - 2 + j];
      ok = ok && std::isfinite(d[j]);
      s += w[j] * d[j];
    }
    if (!ok || !(s > 0.0)) continue;
    double mean = 0.25 * (d[0] + d[1] + d[2] + d[3]), var = 0.0;
    for (double x : d) var += (x - mean) * (x - mean);
    var /= 3.0;
    const double s_err = std::sqrt(var) * std::sqrt(10.0) / 6.0;  // sqrt(sum w^2) = sqrt(10)/6
    v[i] = {dz / s, dz * s_err / (s * s)};
  }
  return v;
}

PulseSeries pulse_series(const CrystalTrace& tr, const CrystalAnalysisOptions& opt) {
  // Measures on sigma - sigma(0) (docs/design.md §2.4): sigma_zz for P, sigma_zx for S.
  const bool S = tr.mode == 'S';
  if (opt.pulse_field != "auto" && opt.pulse_field != "stress" && opt.pulse_field != "velocity")
    throw InputError("analyze: --pulse-field must be auto, stress or velocity (got '" + opt.pulse_field + "')");
  PulseSeries ps{S ? &CrystalTrace::stress_zx : &CrystalTrace::stress_zz, S ? "layer_stress_zx" : "layer_stress_zz"};
  const bool no_stress = (tr.*ps.member).empty();
  if (opt.pulse_field == "stress" && no_stress) throw InputError("analyze: --pulse-field stress: the trace has no " + ps.name);
  // a trace without stresses (auto), or on request: the layer velocity is the next best pulse. A
  // disordered packing smooths a step's stress front into a ramp without a first peak; the bins' mean
  // velocity keeps the pulse the step drives (auto takes it there).
  if (opt.pulse_field == "velocity" || no_stress || (opt.pulse_field == "auto" && tr.packing_bins))
    ps = {S ? &CrystalTrace::velocity_x : &CrystalTrace::velocity_z, S ? "layer_velocity_x" : "layer_velocity_z"};
  return ps;
}

std::vector<std::string> measured_series(char mode) {
  if (mode == 'S') return {"layer_stress_zx", "layer_velocity_x", "layer_displacement_x"};
  return {"layer_stress_zz", "layer_velocity_z", "layer_displacement_z"};
}

CrystalAnalysis analyze_crystal(const CrystalTrace& tr, const CrystalAnalysisOptions& opt) {
  CrystalAnalysis a;
  a.mode = tr.mode;
  a.mode_source = tr.mode_source;
  a.l0 = tr.l0;
  choose_reading(opt.period, tr.period, &a.period_reading, &a.period_source);
  choose_reading(opt.wavenumber_speed, tr.wavenumber_speed, &a.wavenumber_speed, &a.wavenumber_speed_source);
  const std::size_t nl = tr.nlayers;
  std::size_t nt = tr.nt;
  if (opt.t_max >= 0.0) nt = std::upper_bound(tr.time.begin(), tr.time.end(), opt.t_max) - tr.time.begin();
  if (nt < 8) throw InputError("analyze: fewer than 8 samples before t_max");
  const std::span<const double> t(tr.time.data(), nt);
  a.dt = (t[nt - 1] - t[0]) / (nt - 1);

  const bool S = tr.mode == 'S';
  const PulseSeries ps = pulse_series(tr, opt);
  const std::vector<double>* mf = &(tr.*ps.member);
  a.measure_field = ps.name;
  if (mf->empty()) throw InputError("analyze: the trace has no " + a.measure_field);

  const bool by_role = tr.packing_bins && tr.last_free_bin >= 0;
  const int last_index = by_role ? tr.last_free_bin : static_cast<int>(nl) - 1 - tr.fixed_layers;
  a.last_free = static_cast<int>(std::lround(tr.layer_z[last_index] / tr.l0));
  auto column = [&](const std::vector<double>& f, std::size_t p) {
    std::vector<double> y(nt);
    for (std::size_t i = 0; i < nt; ++i) y[i] = f[i * nl + p] - f[p];
    return y;
  };

  // Default fit range (sec. 3.3): z/l0 = 10 .. min(150, last - 20). A packing's few bins: its free bins, those
  // the crosscheck judges (a packing without roles: from the first bin above the source to two short of the last).
  // A tall packing (the crystal's range spans >= kTallPackingBins bins) takes the crystal's range: 20 bins
  // below the top wall leave the longest smoothed pulse (T = 32 layer delays) room before its reflection.
  const int first_free = by_role ? static_cast<int>(std::lround(tr.layer_z[tr.first_free_bin] / tr.l0)) : 1;
  const int tall_lo = std::max(10, first_free), tall_hi = std::min(150, a.last_free - 20);
  const bool few_bins = tr.packing_bins && tall_hi - tall_lo < kTallPackingBins;
  a.requested_lo = opt.lo >= 0 ? opt.lo : few_bins ? first_free : tall_lo;
  a.requested_hi = opt.hi >= 0 ? opt.hi
                   : few_bins ? (by_role ? a.last_free : std::max(2, a.last_free - 2))
                              : tall_hi;
  if (a.requested_hi - a.requested_lo < 2)
    throw InputError("analyze: the fit range z/l0 = " + std::to_string(a.requested_lo) + ".." +
                     std::to_string(a.requested_hi) + " has fewer than 3 layers (last free layer: " +
                     std::to_string(a.last_free) + ")");

  // Polarity: the sign of the largest excursion at the first layer of the range (S stresses may
  // be negative; the measures look for maxima).
  std::size_t ref = 0;
  for (std::size_t p = 0; p < nl; ++p)
    if (std::lround(tr.layer_z[p] / tr.l0) <= a.requested_lo) ref = p;
  {
    const auto y = column(*mf, ref);
    std::size_t im = 0;
    for (std::size_t i = 0; i < nt; ++i)
      if (std::abs(y[i]) > std::abs(y[im])) im = i;
    a.polarity = y[im] < 0.0 ? -1.0 : 1.0;
  }

  std::vector<int> above;  // the layers above the source (z > 0) up to the last free one
  for (int p = 0; p <= last_index; ++p)
    if (tr.layer_z[p] > 0.5 * tr.l0) above.push_back(p);
  std::vector<Signal> signals;
  for (int p : above) {
    auto y = column(*mf, p);
    for (auto& v : y) v *= a.polarity;
    signals.push_back(measure_with_errors(t, y));
  }
  keep_causal_arrivals(signals);
  std::vector<double> tp, th, t1, zz;
  std::vector<int> zl;
  for (std::size_t q = 0; q < above.size(); ++q) {
    const int p = above[q];
    const Signal& s = signals[q];
    LayerMeasures L;
    L.layer = p;
    L.z = tr.layer_z[p];
    L.z_over_l0 = L.z / tr.l0;
    L.arrived = s.arrived;
    L.peak_time = s.peak_time;
    L.peak_value = {s.peak_value.value * a.polarity, s.peak_value.error};
    L.half_peak_time = s.half;
    L.one_percent_time = s.one;
    L.duration = s.duration;
    L.period = s.period;
    L.leading_max = {s.leading.value * a.polarity, s.leading.error};
    a.layers.push_back(L);
    tp.push_back(s.peak_time.value);
    th.push_back(s.half.value);
    t1.push_back(s.one.value);
    zz.push_back(L.z);
    zl.push_back(static_cast<int>(std::lround(L.z_over_l0)));
  }

  // Shorten the range where the first peak has not arrived before the end of the trace.
  int hi = a.requested_lo - 1;
  for (std::size_t i = 0; i < a.layers.size(); ++i) {
    if (zl[i] < a.requested_lo || zl[i] > a.requested_hi) continue;
    if (!a.layers[i].arrived) break;
    hi = zl[i];
  }
  if (hi < a.requested_hi) {
    a.shortened = true;
    char buf[256];
    std::snprintf(buf, sizeof buf,
                  "the first peak has not arrived at z/l0 = %d before the end of the analysed trace (t = %.6g s): "
                  "fits use z/l0 = %d..%d instead of %d..%d",
                  hi + 1, t[nt - 1], a.requested_lo, hi, a.requested_lo, a.requested_hi);
    a.note = buf;
  }
  if (hi - a.requested_lo < 2) throw InputError("analyze: " + a.note + " (fewer than 3 layers)");
  a.v_first_peak = fit_speed("first_peak", tp, zz, zl, a.requested_lo, hi);
  a.v_half_peak = fit_speed("half_peak", th, zz, zl, a.requested_lo, hi);
  a.v_one_percent = fit_speed("one_percent", t1, zz, zl, a.requested_lo, hi);
  if (a.v_first_peak.speed.value > 0.0) a.delay_samples = tr.l0 / a.v_first_peak.speed.value / a.dt;
  if (opt.fronts_only) return a;

  // The coherent front and the coda (analysis/coda.hpp), up to the front's earliest return from the
  // top wall (the first fixed layer above the free ones), at the 1 % arrival speed.
  {
    const double v = std::max(a.v_one_percent.speed.value, a.v_first_peak.speed.value);
    const double z_wall = tr.layer_z[std::min<std::size_t>(last_index + 1, nl - 1)];
    for (std::size_t q = 0; q < above.size(); ++q) {
      LayerMeasures& L = a.layers[q];
      if (!L.arrived) continue;
      auto y = column(*mf, above[q]);
      for (auto& x : y) x *= a.polarity;
      const double t_back = v > 0.0 ? L.one_percent_time.value + 2.0 * (z_wall - L.z) / v : kNaN;
      const FrontCoda fc = front_and_coda(t, y, L.one_percent_time.value, L.duration.value, t_back);
      L.front_energy = fc.front, L.coda_energy = fc.coda;
      L.coda_window = std::max(0.0, fc.coda_end - (L.one_percent_time.value + L.duration.value));
    }
  }

  // Local speeds need consecutive layers: the layers vector holds every layer above the source.
  {
    std::vector<double> tpa(tp);
    for (std::size_t i = 0; i < a.layers.size(); ++i)
      if (!a.layers[i].arrived) tpa[i] = kNaN;
    const auto v = local_speeds(tpa, tr.l0);
    for (std::size_t i = 0; i < a.layers.size(); ++i) a.layers[i].local_speed = v[i];
  }

  // First peaks of the layer displacement, for k's local speed (measures.hpp WavenumberSpeed): the
  // same measures on u - u(0), made positive by the sign of its largest excursion at the reference
  // layer, with their own causal filter (they trail the stress peaks by half a pulse), and the same
  // five-layer local speed.
  std::vector<Measured> v_displacement(a.layers.size());
  {
    const std::vector<double>& uf = S ? tr.displacement_x : tr.displacement_z;
    if (!uf.empty()) {
      const auto y_ref = column(uf, ref);
      std::size_t im = 0;
      for (std::size_t i = 0; i < nt; ++i)
        if (std::abs(y_ref[i]) > std::abs(y_ref[im])) im = i;
      const double sign = y_ref[im] < 0.0 ? -1.0 : 1.0;
      std::vector<Signal> us;
      for (int p : above) {
        auto y = column(uf, p);
        for (auto& v : y) v *= sign;
        us.push_back(measure_with_errors(t, y));
      }
      keep_causal_arrivals(us);
      std::vector<double> tu(us.size(), kNaN);
      for (std::size_t q = 0; q < us.size(); ++q) {
        a.layers[q].displacement_peak_time = us[q].peak_time;
        if (us[q].arrived) tu[q] = us[q].peak_time.value;
      }
      v_displacement = local_speeds(tu, tr.l0);
    }
    if (a.wavenumber_speed == WavenumberSpeed::first_peak) a.wavenumber_speed_field = a.measure_field;
    else if (!uf.empty()) a.wavenumber_speed_field = S ? "layer_displacement_x" : "layer_displacement_z";
    else a.wavenumber_speed_field = std::string("none (the trace has no ") + (S ? "layer_displacement_x)" : "layer_displacement_z)");
  }

  // Dispersion (sec. 3.4) on the layer velocity by default, from the innermost driven layer
  // (z = 0) to the last free one. Not the stress (issue 5: it weights the poorly excited short
  // waves), and not the displacement of a held step: behind the front u stays at the step height
  // up to the end of the record, the window cuts it off, and that jump puts |F| ~ 1/omega at every
  // k, which dominates |F|^4 at the lowest frequencies (measured on the 3200-particle P run:
  // omega_0 = 2.0e4 1/s from u and from sigma, 308833 from v). The velocity is the time
  // derivative, a pulse that is back to ~0 at the end of the record.
  std::string fld = opt.field == "auto" ? "velocity" : opt.field;
  const std::vector<double>* df = nullptr;
  if (fld == "displacement") df = S ? &tr.displacement_x : &tr.displacement_z;
  else if (fld == "velocity") df = S ? &tr.velocity_x : &tr.velocity_z;
  else if (fld == "stress") df = S ? &tr.stress_zx : &tr.stress_zz;
  else throw InputError("analyze: --field must be displacement, velocity or stress (got '" + fld + "')");
  if (df->empty() && opt.field == "auto") {  // no velocity: differentiate the displacement in time
    fld = "displacement";
    df = S ? &tr.displacement_x : &tr.displacement_z;
  }
  if (df->empty() && opt.field == "auto") {
    // Speeds need only the stress; without any layer motion there is no dispersion to fit.
    a.dispersion_field = "none (the trace has no layer velocity or displacement)";
    a.dispersion.omega0 = a.dispersion.omega0_error = a.dispersion.v_k0 = a.dispersion.v_k0_error = kNaN;
  } else {
    if (df->empty()) throw InputError("analyze: the trace lacks the " + fld + " field for the dispersion");
    a.dispersion_field = std::string("layer_") + fld + (fld == "stress" ? (S ? "_zx" : "_zz") : (S ? "_x" : "_z"));
    const int first_index = tr.fixed_layers - 1;
    const std::size_t nz = static_cast<std::size_t>(last_index - first_index + 1);
    // "auto" without a velocity dataset: the forward difference of u, (u(t+dt) - u(t))/dt, i.e. the
    // velocity at mid-steps (one sample shorter).
    const bool differentiate = opt.field == "auto" && fld == "displacement";
    if (differentiate) a.dispersion_field += " (time derivative)";
    const std::size_t ntd = differentiate ? nt - 1 : nt;
    std::vector<double> field(ntd * nz);
    for (std::size_t i = 0; i < ntd; ++i)
      for (std::size_t q = 0; q < nz; ++q) {
        const std::size_t p = first_index + q;
        field[i * nz + q] = differentiate ? ((*df)[(i + 1) * nl + p] - (*df)[i * nl + p]) / a.dt
                                          : (*df)[i * nl + p] - (*df)[p];
      }
    DispersionOptions dopt = opt.dispersion;
    dopt.keep_spectrum = dopt.keep_spectrum || opt.lattice.has_value();  // the ridge against the branch
    a.dispersion = dispersion(field, ntd, nz, a.dt, tr.l0, dopt);
  }
  a.long_wave = fit_long_wave(a.dispersion, tr.mode, opt.lattice, opt.no_lattice);

  // The first oscillation in space: the snapshot when a layer's first peak passes, over every layer
  // above the source (z ascending), on the same signal (polarity, minus its t = 0 value).
  {
    std::vector<double> zs, prof(above.size());
    for (int p : above) zs.push_back(tr.layer_z[p]);
    for (auto& L : a.layers) {
      if (!L.arrived) continue;
      std::size_t n = std::lower_bound(t.begin(), t.end(), L.peak_time.value) - t.begin();  // the sample nearest the peak
      if (n >= nt) n = nt - 1;
      if (n > 0 && L.peak_time.value - t[n - 1] < t[n] - L.peak_time.value) --n;
      for (std::size_t q = 0; q < above.size(); ++q)
        prof[q] = a.polarity * ((*mf)[n * nl + above[q]] - (*mf)[above[q]]);
      const double level = 0.01 * std::abs(L.peak_value.value);
      const double len = first_oscillation_length(zs, prof, level);
      if (len > 0.0) L.oscillation_length = {len, kNaN};
    }
  }

  // Wavelength estimates (sec. 3.4): lambda = V T and k(z) = (2/l0) arccos(V_k(z)/V(k->0)).
  const double vk0 = a.dispersion.v_k0, vk0e = a.dispersion.v_k0_error;
  for (std::size_t i = 0; i < a.layers.size(); ++i) {
    auto& L = a.layers[i];
    const Measured& V = L.local_speed;
    const Measured& T = a.period_reading == PeriodReading::pulse ? L.duration : L.period;
    if (std::isfinite(V.value) && std::isfinite(T.value))
      L.lambda_vt = {V.value * T.value, std::hypot(V.error * T.value, V.value * T.error)};
    L.k_speed = a.wavenumber_speed == WavenumberSpeed::first_peak ? V : v_displacement[i];
    const Measured& Vk = L.k_speed;
    const double k = wavenumber_from_speed(Vk.value, vk0, tr.l0);
    if (std::isfinite(k)) {
      const double root = std::sqrt(vk0 * vk0 - Vk.value * Vk.value);
      const double dk_dv = (2.0 / tr.l0) / root, dk_dvk0 = (2.0 / tr.l0) * Vk.value / (vk0 * root);
      L.k_from_speed = {k, std::hypot(dk_dv * Vk.error, dk_dvk0 * vk0e)};
    }
  }
  return a;
}

// ---------- chain ----------

ChainAnalysis analyze_chain(const ChainTrace& tr, const ChainAnalysisOptions& opt) {
  ChainAnalysis a;
  const std::size_t nc = tr.ncontacts, nt = tr.nt;
  const std::span<const double> t(tr.time.data(), nt);
  std::vector<double> tp, th, idx, pos;
  std::vector<int> il;
  std::vector<Signal> signals;
  for (std::size_t j = 0; j < nc; ++j) {
    std::vector<double> y(nt);
    for (std::size_t i = 0; i < nt; ++i) y[i] = tr.contact_force[i * nc + j] - tr.contact_force[j];
    signals.push_back(measure_with_errors(t, y));
  }
  keep_causal_arrivals(signals);
  for (std::size_t j = 0; j < nc; ++j) {
    const Signal& s = signals[j];
    ContactMeasures c;
    c.contact = j;
    c.position = tr.contact_position[j];
    c.arrived = s.arrived;
    c.peak_time = s.peak_time;
    c.peak_value = s.peak_value;
    c.half_peak_time = s.half;
    c.one_percent_time = s.one;
    c.duration = s.duration;
    c.leading_max = s.leading;
    a.contacts.push_back(c);
    tp.push_back(s.peak_time.value);
    th.push_back(s.half.value);
    idx.push_back(static_cast<double>(j));
    pos.push_back(c.position);
    il.push_back(static_cast<int>(j));
  }
  // Default: contacts 5 .. nc - 7, away from the striker and the wall (the YADE/LIGGGHTS note
  // fits contacts 5-34 of 41).
  const int lo = opt.lo >= 0 ? opt.lo : 5;
  const int hi_req = opt.hi >= 0 ? opt.hi : static_cast<int>(nc) - 7;
  if (hi_req - lo < 2 || hi_req >= static_cast<int>(nc))
    throw InputError("analyze: the contact range " + std::to_string(lo) + ".." + std::to_string(hi_req) +
                     " is not inside 0.." + std::to_string(nc - 1) + " with at least 3 contacts");
  int hi = lo - 1;
  for (int j = lo; j <= hi_req; ++j) {
    if (!a.contacts[j].arrived) break;
    hi = j;
  }
  a.lo = lo;
  a.hi = hi;
  if (hi < hi_req) {
    a.shortened = true;
    a.note = "the first peak has not arrived at contact " + std::to_string(hi + 1) +
             " before the end of the trace: fits use contacts " + std::to_string(lo) + ".." + std::to_string(hi);
  }
  if (hi - lo < 2) throw InputError("analyze: " + a.note + " (fewer than 3 contacts)");
  a.v_first_peak_contacts = fit_speed("first_peak", tp, idx, il, lo, hi).speed;
  a.v_half_peak_contacts = fit_speed("half_peak", th, idx, il, lo, hi).speed;
  bool have_pos = true;
  for (int j = lo; j <= hi; ++j) have_pos = have_pos && std::isfinite(pos[j]);
  if (have_pos) {
    a.v_first_peak = fit_speed("first_peak", tp, pos, il, lo, hi).speed;
    a.v_half_peak = fit_speed("half_peak", th, pos, il, lo, hi).speed;
  }
  return a;
}

}  // namespace granwave::analysis
