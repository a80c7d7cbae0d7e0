// The text report of `granwave analyze` (analysis/trace_text.hpp).
#include "analysis/trace_text.hpp"

#include <algorithm>
#include <cmath>

#include "core/format.hpp"

namespace granwave::analysis {
namespace {

std::string measured_line(const char* name, const Measured& m, const char* unit) {
  return fmt("%-16s %.6g +- %.2g %s\n", name, m.value, m.error, unit);
}

}  // namespace

std::string to_text(const TraceFile& f, const ChainAnalysis& a, bool table) {
  std::string o;
  o += fmt("%s: chain trace of %s (%s), %zu contacts, %zu samples\n", f.path.c_str(), f.code.c_str(), f.case_name.c_str(),
           f.chain.ncontacts, f.chain.nt);
  if (a.shortened) o += fmt("note: %s\n", a.note.c_str());
  o += fmt("front speed over contacts %d..%d:\n", a.lo, a.hi);
  o += measured_line("  first peak", a.v_first_peak_contacts, "contacts/s");
  o += measured_line("  half peak", a.v_half_peak_contacts, "contacts/s");
  o += measured_line("  first peak", a.v_first_peak, "m/s");
  o += measured_line("  half peak", a.v_half_peak, "m/s");
  if (!table) {  // a few rows of the table: the striker's contact and three along the chain
    const std::size_t nc = a.contacts.size();
    o += "first peak force:";
    std::vector<std::size_t> rows{0, nc / 4, nc / 2, (3 * nc) / 4};
    rows.erase(std::unique(rows.begin(), rows.end()), rows.end());
    for (std::size_t j : rows) {
      const auto& c = a.contacts[j];
      o += c.arrived ? fmt(" contact %zu %.6g N at %.6g s;", j, c.peak_value.value, c.peak_time.value)
                     : fmt(" contact %zu not arrived;", j);
    }
    o.back() = '\n';
    return o;
  }
  o += fmt("%8s %12s %12s %12s %12s %12s\n", "contact", "t_peak(s)", "F_peak(N)", "t_half(s)", "F_lead(N)", "T(s)");
  for (const auto& c : a.contacts)
    o += fmt("%8zu %12.6g %12.6g %12.6g %12.6g %12.6g\n", c.contact, c.peak_time.value, c.peak_value.value,
             c.half_peak_time.value, c.leading_max.value, c.duration.value);
  return o;
}

std::string to_text(const TraceFile& f, const CrystalAnalysis& a, bool table) {
  std::string o;
  o += fmt("%s: crystal trace of %s (%s), %c wave (%s), %zu layers, %zu samples, dt = %.4g s, l0 = %.6g m\n",
           f.path.c_str(), f.code.c_str(), f.case_name.c_str(), a.mode, a.mode_source.c_str(), f.crystal.nlayers,
           f.crystal.nt, a.dt, a.l0);
  o += fmt("measures on %s - its t=0 value (polarity %+g)\n", a.measure_field.c_str(), a.polarity);
  if (a.shortened) o += fmt("note: %s\n", a.note.c_str());
  o += fmt("speeds over z/l0 = %d..%d (n = %zu):\n", a.v_first_peak.lo, a.v_first_peak.hi, a.v_first_peak.n);
  o += measured_line("  first peak", a.v_first_peak.speed, "m/s");
  o += measured_line("  half peak", a.v_half_peak.speed, "m/s");
  o += measured_line("  1 % arrival", a.v_one_percent.speed, "m/s");
  const auto& d = a.dispersion;
  o += fmt("dispersion (%s, %zu x %zu, domega = %.4g 1/s, %zu k bins, rms %.4g 1/s):\n", a.dispersion_field.c_str(), d.nt,
           d.nz, d.domega, d.n_fit, d.fit_rms);
  const LongWaveFit& w = a.long_wave;
  const bool sine = w.model == "sine";
  o += measured_line(sine ? "  omega_0" : "  omega_0 (sine)", {d.omega0, d.omega0_error}, "1/s");
  o += measured_line(sine ? "  V(k->0)" : "  V(k->0) (sine)", {d.v_k0, d.v_k0_error}, "m/s");
  if (sine) {
    o += fmt("  model: sine fit omega_0 sin(k l0/2), V(k->0) = omega_0 l0/2 (%s)\n", w.reason.c_str());
  } else {
    o += fmt("  model: lattice branch (%s; the sine above does not describe it): ridge in %d of %d k columns, %d "
             "within one bin; omega_ridge = s omega_branch, s = %.5g +- %.2g\n",
             w.reason.c_str(), w.with_ridge, w.columns, w.within_one_bin, w.scale, w.scale_error);
    o += measured_line("  V(k->0)", {w.value, w.error}, "m/s");
    o += fmt("  (s V_branch, V_branch = %.6g m/s: the lattice's long-wave speed)\n", w.v_lattice);
  }
  o += measured_line("  small-k slope", {d.small_k_slope, d.small_k_slope_error}, "m/s");
  o += fmt("  (omega_max = V k through the origin over %zu bins, k l0 <= 0.5, no model of the branch; frequency\n"
           "  resolution bound +- %.3g m/s)\n", d.small_k_n, d.small_k_resolution);
  {
    std::string line;
    for (const auto& L : a.layers) {
      const long zq = std::lround(L.z_over_l0);
      if (!L.arrived || !std::isfinite(L.front_energy) || (zq != 10 && zq != 20 && zq != 40 && zq != 80 && zq != 150)) continue;
      line += fmt(" %ld: %.3f", zq, L.coda_energy / (L.front_energy + L.coda_energy));
    }
    if (!line.empty()) o += "coda share of the energy (coda / (front + coda)) at z/l0 =" + line + "\n";
  }
  if (!a.pulse_fronts.empty())
    o += "front speeds of longer pulses (the source history smoothed by a Hann window of duration T):\n";
  for (const auto& f : a.pulse_fronts) {
    if (!f.error.empty()) {
      o += fmt("  T = %.4g s (%g layers): %s\n", f.duration, f.travel_layers, f.error.c_str());
      continue;
    }
    o += fmt("  T = %.4g s (%g layers): first peak %.6g +- %.2g m/s, half peak %.6g +- %.2g m/s\n", f.duration,
             f.travel_layers, f.first_peak.speed.value, f.first_peak.speed.error, f.half_peak.speed.value,
             f.half_peak.speed.error);
  }
  o += fmt("local speeds need (l0/V)/dt = %.3g samples per layer delay here\n", a.delay_samples);
  o += fmt("wavelength V T: T = %s (period = \"%s\", %s)\n",
           a.period_reading == PeriodReading::pulse ? "the leading pulse, 1 % arrival to the next 1 % crossing"
                                                    : "the full first oscillation, 1 % arrival to the third 1 % crossing",
           to_string(a.period_reading), a.period_source == "case_toml" ? "from the case" : a.period_source.c_str());
  o += fmt("wavenumber k = (2/l0) arccos(V_k/V(k->0)): V_k = the local speed of the first peaks of %s "
           "(wavenumber_speed = \"%s\", %s)\n",
           a.wavenumber_speed_field.c_str(), to_string(a.wavenumber_speed),
           a.wavenumber_speed_source == "case_toml" ? "from the case" : a.wavenumber_speed_source.c_str());
  if (!table) return o;
  o += fmt("%6s %12s %12s %12s %12s %12s %10s %9s %9s %10s %9s\n", "z/l0", "t_peak(s)", "peak", "t_half(s)",
           "T_pulse(s)", "T_osc(s)", "V(m/s)", "VT/l0", "Losc/l0", "V_k(m/s)", "2pi/kl0");
  for (const auto& L : a.layers) {
    const double lk = std::isfinite(L.k_from_speed.value) ? 2 * M_PI / L.k_from_speed.value / a.l0 : NAN;
    o += fmt("%6.0f %12.6g %12.6g %12.6g %12.6g %12.6g %10.4g %9.3g %9.3g %10.4g %9.3g\n", L.z_over_l0,
             L.peak_time.value, L.peak_value.value, L.half_peak_time.value, L.duration.value, L.period.value,
             L.local_speed.value, L.lambda_vt.value / a.l0, L.oscillation_length.value / a.l0, L.k_speed.value, lk);
  }
  return o;
}

}  // namespace granwave::analysis
