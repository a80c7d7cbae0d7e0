// The JSON report of `granwave analyze --json` (analysis/trace_json.hpp).
#include "analysis/trace_json.hpp"

#include <cmath>
#include <string>
#include <vector>

namespace granwave::analysis {
namespace {

Json qty(const Measured& m, const char* unit) { return {{"value", m.value}, {"error", m.error}, {"unit", unit}}; }
Json qty(double v, const char* unit) { return {{"value", v}, {"unit", unit}}; }

// One number of each layer (contact).
template <class T, class F>
Json list(const std::vector<T>& rows, F get) {
  Json a = Json::array();
  for (const auto& r : rows) a.push_back(get(r));
  return a;
}

// One measure over the layers (contacts): {"unit", "values", ["errors"]}.
template <class T>
Json column(const std::vector<T>& rows, Measured T::*m, const char* unit, bool with_error = true) {
  Json values = Json::array(), errors = Json::array();
  for (const auto& r : rows) {
    values.push_back((r.*m).value);
    errors.push_back((r.*m).error);
  }
  Json o = {{"unit", unit}, {"values", values}};
  if (with_error) o["errors"] = errors;
  return o;
}

// The first-pulse columns layers and contacts share; `value_unit` that of the measured signal.
template <class T>
void pulse_columns(Json& o, const std::vector<T>& rows, const char* value_unit) {
  o["peak_time"] = column(rows, &T::peak_time, "s");
  o["peak_value"] = column(rows, &T::peak_value, value_unit);
  o["half_peak_time"] = column(rows, &T::half_peak_time, "s");
  o["one_percent_time"] = column(rows, &T::one_percent_time, "s");
  o["duration"] = column(rows, &T::duration, "s");
}

Json speed(const SpeedFit& f, const char* range_key) {
  return {{"value", f.speed.value}, {"error", f.speed.error}, {"unit", "m/s"}, {range_key, {f.lo, f.hi}}, {"n", f.n}};
}

Json header(const TraceFile& f) {
  return {{"schema", "granwave-analyze/1"}, {"file", f.path},        {"code", f.code},
          {"code_version", f.code_version}, {"case_name", f.case_name}, {"time_convention", f.time_convention},
          {"model", f.model}};
}

}  // namespace

Json to_json(const TraceFile& f, const CrystalAnalysis& a) {
  Json o = header(f);
  o["mode"] = std::string(1, a.mode);
  o["mode_source"] = a.mode_source;
  o["measure_field"] = a.measure_field;
  o["polarity"] = a.polarity;
  o["period_reading"] = to_string(a.period_reading);
  o["period_reading_source"] = a.period_source;
  o["wavenumber_speed_reading"] = to_string(a.wavenumber_speed);
  o["wavenumber_speed_reading_source"] = a.wavenumber_speed_source;
  o["wavenumber_speed_field"] = a.wavenumber_speed_field;
  o["l0"] = qty(a.l0, "m");
  o["output_interval"] = qty(a.dt, "s");
  o["last_free_layer_z_over_l0"] = a.last_free;
  o["fit_range"] = {{"z_over_l0", {a.v_first_peak.lo, a.v_first_peak.hi}},
                    {"requested", {a.requested_lo, a.requested_hi}},
                    {"shortened", a.shortened},
                    {"note", a.note}};
  o["v_first_peak"] = speed(a.v_first_peak, "z_over_l0");
  o["v_half_peak"] = speed(a.v_half_peak, "z_over_l0");
  o["v_one_percent"] = speed(a.v_one_percent, "z_over_l0");
  const auto& d = a.dispersion;
  o["omega_0"] = qty(Measured{d.omega0, d.omega0_error}, "1/s");
  o["v_k0"] = qty(Measured{d.v_k0, d.v_k0_error}, "m/s");
  Json slope = qty(Measured{d.small_k_slope, d.small_k_slope_error}, "m/s");
  slope["label"] = "small-k slope: omega_max = V k through the origin, k dz <= 0.5, no model of the branch";
  slope["k_max"] = qty(d.small_k_max, "1/m");
  slope["resolution"] = qty(d.small_k_resolution, "m/s");
  slope["n"] = d.small_k_n;
  o["small_k_slope"] = slope;
  Json fronts = Json::array();
  auto front_fit = [](const SpeedFit& f) {
    return Json{{"value", f.speed.value}, {"error", f.speed.error}, {"unit", "m/s"}, {"z_over_l0", {f.lo, f.hi}}, {"n", f.n}};
  };
  for (const auto& f : a.pulse_fronts) {
    Json j = {{"duration", qty(f.duration, "s")}, {"travel_layers", f.travel_layers}};
    if (f.error.empty()) {
      j["v_first_peak"] = front_fit(f.first_peak);
      j["v_half_peak"] = front_fit(f.half_peak);
    } else {
      j["error"] = f.error;
    }
    fronts.push_back(j);
  }
  {
    std::vector<double> zq, ef, ec, share, window;
    for (const auto& L : a.layers) {
      if (!L.arrived || !std::isfinite(L.front_energy)) continue;
      zq.push_back(L.z_over_l0), ef.push_back(L.front_energy), ec.push_back(L.coda_energy);
      window.push_back(L.coda_window);
      share.push_back(L.coda_energy / (L.front_energy + L.coda_energy));
    }
    o["front_and_coda"] = {{"label", "energies sum y^2 dt of the measured signal: the coherent front (1 % arrival, for the "
                                     "leading pulse's duration) and the coda after it, until the front could return "
                                     "from the top wall or the record ends"},
                           {"z_over_l0", zq},
                           {"front_energy", ef},
                           {"coda_energy", ec},
                           {"coda_fraction", share},
                           {"coda_window", {{"unit", "s"}, {"values", window}}}};
  }
  o["pulse_fronts"] = {{"label", "front speeds of the trace's source history smoothed by a Hann window of duration T "
                                 "(linear response: the trace a source pulse of that duration would give)"},
                       {"durations", fronts}};
  const LongWaveFit& w = a.long_wave;
  o["dispersion_model"] = w.model;
  Json lw = {{"model", w.model}, {"reason", w.reason}, {"value", w.value}, {"error", w.error}, {"unit", "m/s"}};
  if (!w.branch.empty()) {
    lw["branch"] = w.branch;
    lw["v_lattice"] = qty(w.v_lattice, "m/s");
    lw["sine_deviation"] = w.sine_deviation;
  }
  if (w.model == "lattice_branch")
    lw["ridge"] = {{"scale", {{"value", w.scale}, {"error", w.scale_error}}},
                   {"columns", w.columns},
                   {"with_ridge", w.with_ridge},
                   {"within_one_bin", w.within_one_bin},
                   {"median_offset_bins", w.median_offset_bins}};
  o["long_wave"] = lw;
  o["dispersion"] = {{"field", a.dispersion_field},
                     {"nt", d.nt},
                     {"nz", d.nz},
                     {"domega", qty(d.domega, "1/s")},
                     {"dk", qty(d.dk, "1/m")},
                     {"n_fit", d.n_fit},
                     {"fit_rms", qty(d.fit_rms, "1/s")},
                     {"k", {{"unit", "1/m"}, {"values", d.k}}},
                     {"omega_max", {{"unit", "1/s"}, {"values", d.omega_max}}}};
  o["local_speed"] = {{"method", "slowness = (1,2,2,1)/6-weighted mean of the 4 first-peak delays over layers i-2..i+2"},
                      {"delay_samples", a.delay_samples}};
  // The seed's wavelength table (sec. 3.4) at z/l0 = 10, 15, 20, 80, 150.
  Json table = Json::array();
  for (int zq : {10, 15, 20, 80, 150}) {
    for (const auto& L : a.layers) {
      if (std::lround(L.z_over_l0) != zq) continue;
      const double k = L.k_from_speed.value, ke = L.k_from_speed.error;
      const double two_pi = 2.0 * std::acos(-1.0);
      Measured lk{std::isfinite(k) ? two_pi / k / a.l0 : kNaN, std::isfinite(k) ? two_pi * ke / (k * k) / a.l0 : kNaN};
      table.push_back(
          {{"z_over_l0", zq},
           {"local_speed", qty(L.local_speed, "m/s")},
           {"duration", qty(L.duration, "s")},
           {"period", qty(L.period, "s")},
           {"oscillation_length_over_l0", qty(Measured{L.oscillation_length.value / a.l0, L.oscillation_length.error / a.l0}, "1")},
           {"lambda_vt_over_l0", qty(Measured{L.lambda_vt.value / a.l0, L.lambda_vt.error / a.l0}, "1")},
           {"k_speed", qty(L.k_speed, "m/s")},
           {"lambda_k_over_l0", qty(lk, "1")}});
    }
  }
  o["wavelength_at"] = table;
  const auto& Ls = a.layers;
  const char* su = a.measure_field.find("stress") != std::string::npos ? "Pa" : "m/s";
  using LM = LayerMeasures;
  Json& c = o["layers"] = {{"layer", list(Ls, [](const LM& L) { return L.layer; })},
                           {"z_over_l0", list(Ls, [](const LM& L) { return L.z_over_l0; })},
                           {"arrived", list(Ls, [](const LM& L) { return L.arrived; })}};
  pulse_columns(c, Ls, su);
  c["period"] = column(Ls, &LM::period, "s");
  c["oscillation_length"] = column(Ls, &LM::oscillation_length, "m", false);
  c["leading_max"] = column(Ls, &LM::leading_max, su);
  c["local_speed"] = column(Ls, &LM::local_speed, "m/s");
  c["lambda_vt"] = column(Ls, &LM::lambda_vt, "m");
  c["displacement_peak_time"] = column(Ls, &LM::displacement_peak_time, "s");
  c["k_speed"] = column(Ls, &LM::k_speed, "m/s");
  c["k_from_speed"] = column(Ls, &LM::k_from_speed, "1/m");
  return o;
}

Json to_json(const TraceFile& f, const ChainAnalysis& a) {
  Json o = header(f);
  o["fit_range"] = {{"contacts", {a.lo, a.hi}}, {"shortened", a.shortened}, {"note", a.note}};
  o["v_first_peak"] = qty(a.v_first_peak, "m/s");
  o["v_half_peak"] = qty(a.v_half_peak, "m/s");
  o["v_first_peak_contacts"] = qty(a.v_first_peak_contacts, "contacts/s");
  o["v_half_peak_contacts"] = qty(a.v_half_peak_contacts, "contacts/s");
  const auto& Cs = a.contacts;
  using CM = ContactMeasures;
  Json& c = o["contacts"] = {{"contact", list(Cs, [](const CM& x) { return x.contact; })},
                             {"position", {{"unit", "m"}, {"values", list(Cs, [](const CM& x) { return x.position; })}}},
                             {"arrived", list(Cs, [](const CM& x) { return x.arrived; })}};
  pulse_columns(c, Cs, "N");
  c["leading_max"] = column(Cs, &CM::leading_max, "N");
  return o;
}

}  // namespace granwave::analysis
