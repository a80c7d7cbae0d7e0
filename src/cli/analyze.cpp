// granwave analyze TRACES [--json] [--layers LO:HI] [--field F] [--pulse-field P] [--t-max T] [--period R]
// [--wavenumber-speed V]:
// the one ruler for
// the trace files of granwave, YADE and LIGGGHTS (src/analysis/trace_analysis.hpp).
#include <iostream>
#include <string>

#include "analysis/trace_analysis.hpp"
#include "analysis/pulse_fronts.hpp"
#include "analysis/trace_json.hpp"
#include "analysis/trace_text.hpp"
#include "cli/verbs.hpp"
#include "core/error.hpp"
#include "crystal/case_lattice.hpp"
#include "crystal/observables.hpp"
#include "impact/impact.hpp"

namespace granwave::cli {
namespace {

constexpr const char* kAnalyzeHelp = R"(usage: granwave analyze TRACES.h5 [--json] [--layers LO:HI] [--field F] [--pulse-field P] [--t-max T]
                        [--period oscillation|pulse] [--wavenumber-speed displacement_peak|first_peak]

Measures a trace file of any code (granwave, yade, liggghts; data/SCHEMA.md §3) with the one set
of measures of docs/design.md §2.4.

Crystal traces (seed 002):
  per layer (on sigma - sigma(t=0): sigma_zz for P, sigma_zx for S, sign-normalised so the pulse
  is positive): first peak (time, value), half-peak arrival, 1 % arrival, duration of the leading
  pulse (1 % arrival to the next 1 % crossing), period of the first oscillation (1 % arrival to the
  third 1 % crossing: the pulse and the trough after it), leading-pulse maximum, local speed,
  lambda = V T (T: --period), the first oscillation's length in the snapshot at the layer's first
  peak (the wavelength in space), k(z) = (2/l0) arccos(V_k/V(k->0)) (V_k: --wavenumber-speed);
  speeds: least-squares z against arrival time (first peak, half peak, 1 %) with standard errors
  over z/l0 = LO..HI (default 10 .. min(150, last free layer - 20); a packing's z-bins (l0 = the bin
  width h): its free bins by role, measured on the bins' mean velocity), shortened, with a note, where
  the first peak has not arrived before the end of the trace. A layer has arrived when its first
  peak lies before the last sample and it is on the front: from the first layer that arrived
  outwards, every nearer layer arrived, and its first peak is not earlier than the previous
  layer's 1 % arrival (beyond the front, noise or a precursor can show a local maximum); layers
  that have not arrived have no measures;
  local speed: slowness = (1,2,2,1)/6-weighted mean of the four first-peak delays over layers
  i-2..i+2 (= least squares with layer weights 1,2,3,2,1). It needs the refined peak time error
  well below a layer delay l0/V: `delay_samples` in the JSON is (l0/V)/dt. For a pulse of rms
  width sigma the sampling error is at most h^3 V/(4 sigma^2 l0) (tests/unit/analysis_synthetic.cpp);
  the parabola-refined peak makes the seed's 1 us output (6.5 samples per delay) enough: on the
  3200-particle P run, local speeds from 1 us and 0.2 us output agree to 0.03 % at z/l0 = 4..50
  (the seed, without refinement, needed a higher rate). The error quoted per layer is the scatter
  of the four delays, so near the source it includes the acceleration itself;
  dispersion: 2D FFT of the (t, z) field from the innermost driven layer (z = 0) to the last free
  layer, power-weighted omega_max(k) with phi = 4, sine fit omega_0 sin(k l0/2) over all k > 0,
  V(k->0) = omega_0 l0/2. Default field: the layer velocity (without one in the trace, the time
  derivative of the layer displacement). Not the stress: it weights the poorly excited short waves
  (6 % low on YADE traces of the seed's crystal). Not the raw displacement of a held step either:
  it stays at the step height to the end of the record, the window cuts it, and the resulting
  |F| ~ 1/omega dominates |F|^4 (omega_0 = 2.0e4 1/s instead of 3.09e5 on the 3200-particle run).
  The sine is the lattice's branch only for a wave that turns no particle (P along z, or S
  without tangential springs). The case's lattice is rebuilt from the trace's case text
  (case_toml; as `granwave theory`); when the wave's branch (u_z for P, u_x for S) is not the
  sine -- an S wave with tangential springs drives rotations -- the ridge of the spectrum is
  compared with that branch (as `figures crystal` does), the branch scaled to it,
  omega_ridge = s omega_branch(k), and V(k->0) = s V_branch (crystal_hm_s: 967.2 +- 0.8 m/s
  against the lattice's 967.6; the sine fit says 1081). The report says which model was fitted;
  a trace without its case, or of a polydisperse packing, gets the sine fit, labelled so.
Chain traces (seed 001): per contact the same measures on the contact force minus its t = 0 value,
  arrivals as for layers, front speed over contacts LO..HI (default 5 .. ncontacts - 7) in
  contacts/s and m/s (positions: x_j + a_j of /system, the far side of bead j).
`granwave run` prints the summary of this report (and, with --json, this JSON under "analysis")
for the trace it writes: the same code, the same numbers.

  --layers LO:HI   z/l0 range of the fits (crystal), contact range (chain); default crystal
                   10 .. min(150, last free - 20), a packing a few bins tall its free bins
                   (when the crystal's range would span fewer than 40 bins)
  --field F        dispersion field: velocity (default) | displacement | stress (raw fields)
  --pulse-field P  field of the per-layer measures and speeds: stress (default; sigma_zz for P,
                   sigma_zx for S) | velocity (u_z' for P, u_x' for S; the default for a trace
                   without the stress) -- two codes are compared on one field
  --t-max T        analyse t <= T only (s), e.g. to stop before a reflection returns
  --period R       T of lambda = V T (seed 002 sec. 3.4): oscillation (the full first oscillation;
                   default) or pulse (the leading pulse alone: 0.49 of a sine's period, 0.73-0.75
                   of the first oscillation on the seed's crystal). Without the flag,
                   the trace's case decides ([analysis] period, data/SCHEMA.md), else oscillation.
                   The full oscillation is the wavelength: V T equals the length of the first
                   oscillation in a snapshot of the crystal (docs/design.md §2.4) and reproduces the
                   seed's 8, 9, 10, 16, 19 l0 at z/l0 = 10, 15, 20, 80, 150
  --wavenumber-speed V
                   the local speed V_k of k = (2/l0) arccos(V_k/V(k->0)), seed 002 sec. 3.4's
                   second table lambda = 2 pi/k (the group speed of omega_0 sin(k l0/2) set equal
                   to the local speed): displacement_peak (default: the five-layer local speed of
                   the first peak of the layer displacement, u_z for P, u_x for S; on the seed's
                   crystal 8.2, 9.3, 10.1 l0 at z/l0 = 10, 15, 20 against its 8.3, 9.2, 10.1,
                   and 207.7 m/s at z/l0 = 20 against its 208) or
                   first_peak (that of the measured signal's first peak, the local speed of
                   lambda = V T: 10.7, 12.5, 13.9 l0 there). Without the flag, the trace's case
                   decides ([analysis] wavenumber_speed), else displacement_peak. A trace without
                   the displacement has no k in the default reading
  --json           one JSON object (schema "granwave-analyze/1") on one line: every number as
                   {"value", "error", "unit"} (error null where none applies), written as the
                   shortest decimal that reads back as the same double (NaN, inf: null; data/SCHEMA.md
                   "JSON outputs"). Top-level keys:
                   schema, file, code, code_version, case_name, time_convention, model,
                   crystal: mode, mode_source, measure_field, polarity, l0, output_interval,
                     wavenumber_speed_reading, wavenumber_speed_reading_source,
                     wavenumber_speed_field, last_free_layer_z_over_l0, fit_range {z_over_l0, requested, shortened, note},
                     v_first_peak, v_half_peak, v_one_percent (m/s, + z_over_l0 range, n),
                     omega_0 (1/s), v_k0 (m/s) (the sine fit, whatever the model),
                     small_k_slope {value, error, unit, label, k_max, n, resolution} (omega_max = V k
                     through the origin, k l0 <= 0.5), pulse_fronts {label, durations [{duration,
                     travel_layers, v_first_peak, v_half_peak}]} (the source history smoothed by a
                     Hann window of 4, 8, 16, 32 layer delays), front_and_coda {label, z_over_l0,
                     front_energy, coda_energy, coda_fraction, coda_window} (the leading pulse's
                     energy and the rest's until the front could return from the top; coda_window
                     the time summed, 0 where that return comes before the front has passed),
                     dispersion_model ("sine" | "lattice_branch"), long_wave {model, reason,
                     value, error, unit: V(k->0) of that model; with the case's lattice also
                     branch, v_lattice, sine_deviation; lattice_branch also ridge {scale,
                     columns, with_ridge, within_one_bin, median_offset_bins}}, dispersion {field, nt, nz, domega, dk, n_fit,
                     fit_rms, k, omega_max}, local_speed {method, delay_samples},
                     wavelength_at [{z_over_l0, local_speed, duration, period,
                     oscillation_length_over_l0, lambda_vt_over_l0, k_speed, lambda_k_over_l0}] at
                     z/l0 = 10, 15, 20, 80, 150,
                     layers {layer, z_over_l0, arrived, peak_time, peak_value, half_peak_time,
                     one_percent_time, duration, period, oscillation_length (no errors),
                     leading_max, local_speed, lambda_vt, displacement_peak_time, k_speed,
                     k_from_speed: each {unit, values,
                     errors}}
                   chain: fit_range {contacts, shortened, note}, v_first_peak, v_half_peak (m/s),
                     v_first_peak_contacts, v_half_peak_contacts (contacts/s),
                     contacts {contact, position, arrived, peak_time, peak_value, half_peak_time,
                     one_percent_time, duration, leading_max}
)";

// A trace that reads but cannot be measured (a file from elsewhere, perhaps damaged where no
// checksum guards it) is refused naming the file.
template <class Measure>
auto measured(const std::string& path, Measure&& measure) {
  try {
    return measure();
  } catch (const InputError& e) {
    throw InputError(path + ": " + e.what());
  }
}

}  // namespace

int cmd_analyze(const Args& args) { return cmd_analyze(args, std::cout); }

int cmd_analyze(const Args& args, std::ostream& out) {
  if (wants_help(args)) {
    out << kAnalyzeHelp;
    return 0;
  }
  const auto pos = positionals(args, {"--layers", "--field", "--pulse-field", "--t-max", "--period", "--wavenumber-speed"});
  if (pos.size() != 1) throw InputError("analyze: expected one trace file (granwave analyze --help)");
  const bool json = has_flag(args, "--json");
  int lo = -1, hi = -1;
  if (const auto s = option_value(args, "", "--layers"); !s.empty()) parse_layers(s, "integers", &lo, &hi);
  if (impact::is_impact_trace(pos[0])) {  // the rebound of an impact trace (data/SCHEMA.md §7.3)
    impact::print_analysis(impact::read_trace(pos[0]), json, out);
    return 0;
  }
  const auto file = analysis::read_trace(pos[0], crystal::observables());

  if (file.model == "chain") {
    if (!option_value(args, "", "--period").empty())
      throw InputError(pos[0] + ": --period is for crystal traces (the wavelength of seed 002 sec. 3.4)");
    if (!option_value(args, "", "--wavenumber-speed").empty())
      throw InputError(pos[0] + ": --wavenumber-speed is for crystal traces (the wavelength of seed 002 sec. 3.4)");
    if (!option_value(args, "", "--pulse-field").empty())
      throw InputError(pos[0] + ": --pulse-field is for crystal traces (a chain is measured on its contact forces)");
    const auto a = measured(pos[0], [&] { return analysis::analyze_chain(file.chain, {lo, hi}); });
    if (json) {
      out << json_text(analysis::to_json(file, a));
      return 0;
    }
    out << analysis::to_text(file, a);
    return 0;
  }

  analysis::CrystalAnalysisOptions opt;
  if (file.crystal.packing_bins)
    opt.no_lattice = crystal::kNoBranchesOfPacking;  // its case would import the packing file again
  else
    crystal::add_case_lattice(opt, file.case_toml, pos[0] + ":/case_toml");
  opt.lo = lo;
  opt.hi = hi;
  if (const auto f = option_value(args, "", "--field"); !f.empty()) opt.field = f;
  if (const auto f = option_value(args, "", "--pulse-field"); !f.empty()) opt.pulse_field = f;
  if (const auto t = option_value(args, "", "--t-max"); !t.empty()) {
    try {
      opt.t_max = std::stod(t);
    } catch (const std::exception&) {
      throw InputError("--t-max " + t + ": expected a time in seconds");
    }
  }
  if (const auto p = option_value(args, "", "--period"); !p.empty()) {
    opt.period = analysis::parse_period_reading(p);
    if (!opt.period) throw InputError("--period " + p + ": must be oscillation or pulse");
  }
  if (const auto v = option_value(args, "", "--wavenumber-speed"); !v.empty()) {
    opt.wavenumber_speed = analysis::parse_wavenumber_speed(v);
    if (!opt.wavenumber_speed) throw InputError("--wavenumber-speed " + v + ": must be displacement_peak or first_peak");
  }
  auto a = measured(pos[0], [&] { return analysis::analyze_crystal(file.crystal, opt); });
  analysis::add_pulse_fronts(file.crystal, opt, a);
  if (json) {
    out << json_text(analysis::to_json(file, a));
    return 0;
  }
  out << analysis::to_text(file, a);
  return 0;
}

}  // namespace granwave::cli
