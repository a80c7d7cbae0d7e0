// The measures of a trace (trace_file.hpp) of any code -- granwave, YADE, LIGGGHTS -- one ruler for
// all of them. Crystal traces (seed 002): per-layer measures of docs/design.md §2.4 on
// sigma - sigma(t = 0), speed fits with standard errors, local speeds, the 2D-FFT dispersion fit
// and the wavelength estimates of sec. 3.4. Chain traces (seed 001): per-contact measures and the
// front speed. Every measure comes from analysis/measures.hpp; nothing here knows which code
// wrote the trace.
//
// Local speed (seed 002 Fig. 4, "a centre-weighted average over five layers"): the local slowness
// at layer i is the (1, 2, 2, 1)/6-weighted mean of the four layer-to-layer delays of the first-peak
// time between layers i-2 .. i+2, i.e. ((t_{i+1} + t_{i+2}) - (t_{i-1} + t_{i-2})) / (6 l0);
// identical to the weighted least-squares slope of t against z with layer weights (1, 2, 3, 2, 1).
// V = 1/slowness. Its error is the scatter of the four delays times sqrt(sum w^2) = sqrt(10)/6.
// Delays are averaged, not speeds, because the peak times carry the noise.
//
// Wavenumber from the local speed (seed 002 sec. 3.4's second wavelength table): k = (2/l0)
// arccos(V/V(k->0)), V the five-layer local speed of the first peak of the layer displacement by
// default (measures.hpp WavenumberSpeed; `[analysis] wavenumber_speed`, `analyze --wavenumber-speed`).
#pragma once
#include <cstddef>
#include <optional>
#include <string>
#include <vector>

#include "analysis/dispersion.hpp"
#include "analysis/long_wave.hpp"
#include "analysis/measures.hpp"
#include "analysis/trace_file.hpp"

namespace granwave::analysis {

// A measured number with its standard error (NaN when not available).
struct Measured {
  double value = kNaN;
  double error = kNaN;
};

// ---- crystal ----
struct LayerMeasures {
  std::size_t layer = 0;     // index in the trace (0 = bottom, fixed layers included)
  double z = 0.0;            // m
  double z_over_l0 = 0.0;
  // First peak found strictly before the end of the trace, on the front: from the first layer
  // that arrived outwards, every layer before it arrived, and its first peak is not earlier than
  // the previous layer's 1 % arrival (trace_analysis.cpp, keep_causal_arrivals). Layers beyond
  // the front have no measures.
  bool arrived = false;
  Measured peak_time;        // s; error: |parabola - Gaussian| vertex of the same 3 samples
  Measured peak_value;       // Pa (signal units)
  Measured half_peak_time;   // s; error: h^2 |y''| / (8 |y'|), linear-interpolation bound
  Measured one_percent_time; // s; same
  Measured duration;         // s, the leading pulse: 1 % arrival to the next 1 % crossing
  Measured period;           // s, the full first oscillation: 1 % arrival to the third 1 % crossing
  Measured leading_max;      // largest value of the leading pulse
  Measured local_speed;      // m/s, five-layer centre-weighted (header)
  Measured lambda_vt;        // V T (m), T = period or duration by CrystalAnalysis::period_reading
  // m: the length of the first oscillation in the snapshot at the sample nearest this layer's first
  // peak (measures.hpp first_oscillation_length, level 1 % of this layer's first peak): the
  // wavelength read in space, against which lambda = V T is read in time.
  Measured oscillation_length;
  // s: first peak (measures.hpp) of the layer displacement minus its t = 0 value, sign-normalised
  // like the measured signal, on the front as `arrived` (its own causal filter).
  Measured displacement_peak_time;
  Measured k_speed;          // m/s, the local speed V put into k: by CrystalAnalysis::wavenumber_speed
  Measured k_from_speed;     // (2/l0) arccos(V/V(k->0)) (1/m), V = k_speed
  // sum y^2 dt of the measured signal over the coherent front and over the coda (analysis/coda.hpp)
  double front_energy = kNaN, coda_energy = kNaN;
  double coda_window = kNaN;  // s the coda is summed over (0: the front's return closed it before the front ended)
};

struct SpeedFit {
  std::string measure;       // "first_peak" | "half_peak" | "one_percent"
  Measured speed;            // m/s, slope of z against arrival time (front_speed)
  double intercept = kNaN;   // m
  int lo = 0, hi = 0;        // z/l0 range used (inclusive)
  std::size_t n = 0;
};

// The front of a longer pulse (analysis/pulse_fronts.hpp): the trace's source history smoothed by a
// Hann window of duration T, measured as the trace itself.
struct PulseFront {
  double duration = 0.0;         // T (s)
  double travel_layers = 0.0;    // T V / l0: the pulse's length in layers (bins), V the raw first-peak speed
  SpeedFit first_peak, half_peak;
  std::string error;             // the analysis' refusal for this T (then the fits are empty)
};

// A packing's default fit range is the crystal's, z/l0 = max(10, first free) .. min(150, last free - 20),
// when that spans at least this many bins; else its free bins (a packing a few bins tall).
inline constexpr int kTallPackingBins = 40;

struct CrystalAnalysisOptions {
  int lo = -1, hi = -1;       // z/l0 range of the fits (< 0: default 10 .. min(150, last - 20))
  // Dispersion field: "auto" (the layer velocity; without it the time derivative of the layer
  // displacement) | "velocity" | "displacement" | "stress" (raw). See analyze_crystal for why.
  std::string field = "auto";
  // Field of the per-layer measures: "auto" (the layer stress, sigma_zz for P and sigma_zx for S;
  // without it the layer velocity) | "stress" | "velocity". Two traces are compared on one field.
  std::string pulse_field = "auto";
  double t_max = -1.0;        // analyse t <= t_max only (< 0: the whole trace)
  // T of lambda = V T (measures.hpp); unset: the trace's case ([analysis] period), else oscillation.
  std::optional<PeriodReading> period;
  // V of k(V) (measures.hpp); unset: the trace's case ([analysis] wavenumber_speed), else displacement_peak.
  std::optional<WavenumberSpeed> wavenumber_speed;
  DispersionOptions dispersion;
  // The case's lattice branches (long_wave.hpp): V(k->0) from the branch when it is not a sine.
  // Unset: the sine fit, for the reason in `no_lattice`.
  std::optional<LatticeBranches> lattice;
  std::string no_lattice = "no lattice of the case given";
  // Only the per-layer measures and the three front speeds, not the coda, dispersion, wavelengths:
  // what pulse_fronts reads of each smoothed trace.
  bool fronts_only = false;
};

struct CrystalAnalysis {
  char mode = 'P';
  std::string mode_source, measure_field, dispersion_field;
  PeriodReading period_reading = PeriodReading::oscillation;
  std::string period_source = "default";  // "option" | "case_toml" | "default"
  WavenumberSpeed wavenumber_speed = WavenumberSpeed::displacement_peak;
  std::string wavenumber_speed_source = "default";  // "option" | "case_toml" | "default"
  // The signal whose first peaks give k_speed ("layer_displacement_z", ...); says so when the trace
  // lacks it (then k is NaN: no other signal stands in for it).
  std::string wavenumber_speed_field;
  double polarity = 1.0;     // the measured signal is polarity * (sigma - sigma(0))
  double l0 = 0.0, dt = 0.0; // output interval (s)
  std::vector<LayerMeasures> layers;  // every layer above the source (z > 0) up to the last free one
  int last_free = 0;                  // z/l0 of the last free layer
  int requested_lo = 0, requested_hi = 0;
  bool shortened = false;
  std::string note;                   // says why the range was shortened
  SpeedFit v_first_peak, v_half_peak, v_one_percent;
  // The output interval the local speeds need: the first-peak time error must stay well below
  // the layer delay l0/V; `delay_samples` = (l0/V_first_peak)/dt samples per layer delay.
  double delay_samples = kNaN;
  DispersionResult dispersion;
  LongWaveFit long_wave;  // V(k->0) and the model of the branch it comes from
  // Longer pulses' fronts: filled by add_pulse_fronts (analysis/pulse_fronts.hpp) where a report is
  // made (`analyze`, `run`), not by analyze_crystal itself
  std::vector<PulseFront> pulse_fronts;
};

CrystalAnalysis analyze_crystal(const CrystalTrace& trace, const CrystalAnalysisOptions& options = {});

// The series the per-layer measures are made on (options.pulse_field; "auto": the layer stress of the
// trace's mode, sigma_zz for P and sigma_zx for S, else, without it or on a packing's bins, the layer
// velocity) and its dataset name. Throws InputError for an unknown pulse_field or a stress asked for
// and absent; the member may name an empty series (analyze_crystal refuses that).
struct PulseSeries {
  std::vector<double> CrystalTrace::*member;
  std::string name;
};
PulseSeries pulse_series(const CrystalTrace& trace, const CrystalAnalysisOptions& options);

// The layer series a crystal analysis reads of a trace of mode 'P' or 'S' (pulse_series, the
// wavenumber speed's and the dispersion's fields choose among them): the stress, velocity and
// displacement along the mode's axis. The trace's other series cannot change a measure.
std::vector<std::string> measured_series(char mode);

// Five-layer local speed (header comment) from first-peak times t[i] at equal spacing dz;
// entries without a full window (or with a missing time, NaN) are NaN.
std::vector<Measured> local_speeds(const std::vector<double>& peak_times, double dz);

// ---- chain ----
struct ContactMeasures {
  std::size_t contact = 0;
  double position = kNaN;  // m
  bool arrived = false;    // as LayerMeasures::arrived
  Measured peak_time, peak_value, half_peak_time, one_percent_time, duration, leading_max;  // s, N
};
struct ChainAnalysis {
  std::vector<ContactMeasures> contacts;
  int lo = 0, hi = 0;               // contact range of the fits
  bool shortened = false;
  std::string note;
  Measured v_first_peak_contacts;   // contacts per second
  Measured v_half_peak_contacts;
  Measured v_first_peak, v_half_peak;  // m/s (when contact positions are known)
};
struct ChainAnalysisOptions {
  int lo = -1, hi = -1;  // contact range (< 0: default 5 .. ncontacts - 7)
};
ChainAnalysis analyze_chain(const ChainTrace& trace, const ChainAnalysisOptions& options = {});

}  // namespace granwave::analysis
