#include "analysis/trace_analysis.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <limits>
#include <sstream>

#include "config/case.hpp"
#include "core/error.hpp"
#include "io/h5.hpp"

namespace granwave::analysis {
namespace {

// ---------- reading ----------

// A trace from elsewhere may hold NaN or infinities (a run that blew up, a damaged copy): refused,
// naming the dataset, the sample and the column, rather than measured.
void require_finite(const io::H5Reader& r, const std::string& path, const std::vector<double>& v, std::size_t ncols) {
  for (std::size_t i = 0; i < v.size(); ++i)
    if (!std::isfinite(v[i]))
      throw InputError(r.path() + ": " + path + " holds " + std::to_string(v[i]) + " at sample " +
                       std::to_string(ncols ? i / ncols : i) + (ncols > 1 ? ", column " + std::to_string(i % ncols) : "") +
                       ": only finite values can be measured");
}

std::vector<double> read_matrix(const io::H5Reader& r, const std::string& path, std::size_t nt, std::size_t ncols) {
  if (!r.has(path)) return {};
  std::vector<std::size_t> dims;
  auto v = r.read_double(path, &dims);
  if (dims.size() != 2 || dims[0] != nt || dims[1] != ncols)
    throw InputError(r.path() + ": " + path + " must have shape [nt, n] = [" + std::to_string(nt) + ", " +
                     std::to_string(ncols) + "]");
  require_finite(r, path, v, ncols);
  return v;
}

// Provenance text is informative: an unreadable attribute must not stop the measurement.
std::string root_attr(const io::H5Reader& r, const std::string& name) {
  if (!r.has_attr("/", name)) return {};
  try {
    return r.attr_string("/", name);
  } catch (const InputError&) {
    return "(unreadable)";
  }
}

double median_spacing(const std::vector<double>& x) {
  std::vector<double> d;
  for (std::size_t i = 1; i < x.size(); ++i) d.push_back(x[i] - x[i - 1]);
  if (d.empty()) return 0.0;
  std::nth_element(d.begin(), d.begin() + d.size() / 2, d.end());
  return d[d.size() / 2];
}

double max_abs_change(const std::vector<double>& f, std::size_t nt, std::size_t n) {
  double m = 0.0;
  for (std::size_t i = 0; i < nt; ++i)
    for (std::size_t p = 0; p < n; ++p) m = std::max(m, std::abs(f[i * n + p] - f[p]));
  return m;
}

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

// ---------- reading ----------

TraceFile read_trace(const std::string& path) {
  io::H5Reader r(path);
  TraceFile f;
  f.path = path;
  f.code = root_attr(r, "code");
  f.code_version = root_attr(r, "code_version");
  f.case_name = root_attr(r, "case_name");
  f.time_convention = root_attr(r, "time_convention");
  if (!r.has("/time")) throw InputError(path + ": no /time dataset (not a granwave trace file, SCHEMA.md §3)");
  const auto time = r.read_double("/time");
  const std::size_t nt = time.size();
  if (nt < 3) throw InputError(path + ": /time has fewer than 3 samples");
  require_finite(r, "/time", time, 1);
  for (std::size_t i = 1; i < nt; ++i)
    if (!(time[i] > time[i - 1]))
      throw InputError(path + ": /time is not strictly increasing (sample " + std::to_string(i) + ")");

  if (r.has("/crystal/layer_z")) {
    f.model = "crystal";
    auto& c = f.crystal;
    c.time = time;
    c.nt = nt;
    c.layer_z = r.read_double("/crystal/layer_z");
    c.nlayers = c.layer_z.size();
    if (c.nlayers < 4) throw InputError(path + ": /crystal/layer_z has fewer than 4 layers");
    require_finite(r, "/crystal/layer_z", c.layer_z, 1);
    c.stress_zz = read_matrix(r, "/crystal/layer_stress_zz", nt, c.nlayers);
    c.stress_zx = read_matrix(r, "/crystal/layer_stress_zx", nt, c.nlayers);
    c.displacement_z = read_matrix(r, "/crystal/layer_displacement_z", nt, c.nlayers);
    c.displacement_x = read_matrix(r, "/crystal/layer_displacement_x", nt, c.nlayers);
    c.velocity_z = read_matrix(r, "/crystal/layer_velocity_z", nt, c.nlayers);
    c.velocity_x = read_matrix(r, "/crystal/layer_velocity_x", nt, c.nlayers);
    if (r.has("/crystal/coordination")) c.coordination = r.read_double("/crystal/coordination");
    c.l0 = r.has_attr("/system", "l0") ? r.attr_double("/system", "l0") : median_spacing(c.layer_z);
    if (!(c.l0 > 0.0 && std::isfinite(c.l0)))
      throw InputError(path + ": the layer spacing l0 = " + std::to_string(c.l0) +
                       " (/system attribute l0, or the median spacing of /crystal/layer_z) is not a positive number");
    if (r.has_attr("/system", "fixed_layers")) {
      const double fl = r.attr_double("/system", "fixed_layers");
      if (!(std::abs(fl) < 1e9))
        throw InputError(path + ": /system attribute fixed_layers = " + std::to_string(fl) + " is not a layer count");
      c.fixed_layers = static_cast<int>(std::lround(fl));
    } else {  // layer_z = 0 is the innermost driven layer: the ones below it are driven too
      int below = 0;
      for (double z : c.layer_z) below += z < -0.5 * c.l0;
      c.fixed_layers = below + 1;
    }
    // Driven layers at each end; the measured ones, from the innermost driven layer at the source
    // to the last free one (at least 2), must be layers.
    if (c.fixed_layers < 1 || 2 * static_cast<std::size_t>(c.fixed_layers) + 1 > c.nlayers)
      throw InputError(path + ": " + std::to_string(c.fixed_layers) + " fixed layers at each end of " +
                       std::to_string(c.nlayers) + " layers (/system attribute fixed_layers, or layer_z below 0) "
                       "leave fewer than 2 layers to measure");
    // Excitation mode: from the case text every trace carries; else from which field moved.
    const std::string toml = root_attr(r, "case_toml");
    bool known = false;
    if (!toml.empty()) {
      try {
        const auto cs = config::parse_case(toml, path + ":/case_toml");
        c.mode = cs.excitation.mode == config::Excitation::Mode::S ? 'S' : 'P';
        c.mode_source = "case_toml";
        if (!cs.analysis.period.empty()) c.period = parse_period_reading(cs.analysis.period);
        if (!cs.analysis.wavenumber_speed.empty()) c.wavenumber_speed = parse_wavenumber_speed(cs.analysis.wavenumber_speed);
        known = true;
      } catch (const std::exception&) {
      }
    }
    if (!known) {
      auto pick = [&](const std::vector<double>& zf, const std::vector<double>& xf) {
        if (zf.empty() || xf.empty()) return 0;
        return max_abs_change(xf, nt, c.nlayers) > max_abs_change(zf, nt, c.nlayers) ? 2 : 1;
      };
      int v = pick(c.displacement_z, c.displacement_x);
      if (!v) v = pick(c.velocity_z, c.velocity_x);
      if (!v) v = pick(c.stress_zz, c.stress_zx);
      c.mode = v == 2 ? 'S' : 'P';
      c.mode_source = "inferred";
    }
  } else if (r.has("/chain/contact_force")) {
    f.model = "chain";
    auto& c = f.chain;
    c.time = time;
    c.nt = nt;
    std::vector<std::size_t> dims;
    c.contact_force = r.read_double("/chain/contact_force", &dims);
    if (dims.size() != 2 || dims[0] != nt || dims[1] == 0)
      throw InputError(path + ": /chain/contact_force must be [nt, ncontacts] with nt = " + std::to_string(nt) +
                       " (the samples of /time) and ncontacts > 0");
    require_finite(r, "/chain/contact_force", c.contact_force, dims[1]);
    c.ncontacts = dims[1];
    c.contact_position.assign(c.ncontacts, kNaN);
    if (r.has("/system/position")) {
      std::vector<std::size_t> pd;
      const auto pos = r.read_double("/system/position", &pd);
      std::vector<double> rad;
      if (r.has("/system/radius")) rad = r.read_double("/system/radius");
      const std::size_t nb = pd.size() == 2 && pd[1] == 3 ? pd[0] : 0;  // [n, 3], else not used
      // Contact j touches bead j on its far side: x_j + a_j (the wall contact too).
      for (std::size_t j = 0; j < c.ncontacts && j < nb; ++j)
        c.contact_position[j] = pos[j * 3] + (rad.size() == nb ? rad[j] : 0.0);
    }
  } else {
    throw InputError(path + ": neither /crystal/layer_z nor /chain/contact_force (SCHEMA.md §3)");
  }
  return f;
}

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

CrystalAnalysis analyze_crystal(const CrystalTrace& tr, const CrystalAnalysisOptions& opt) {
  CrystalAnalysis a;
  a.mode = tr.mode;
  a.mode_source = tr.mode_source;
  a.l0 = tr.l0;
  if (opt.period) {
    a.period_reading = *opt.period;
    a.period_source = "option";
  } else if (tr.period) {
    a.period_reading = *tr.period;
    a.period_source = "case_toml";
  }
  if (opt.wavenumber_speed) {
    a.wavenumber_speed = *opt.wavenumber_speed;
    a.wavenumber_speed_source = "option";
  } else if (tr.wavenumber_speed) {
    a.wavenumber_speed = *tr.wavenumber_speed;
    a.wavenumber_speed_source = "case_toml";
  }
  const std::size_t nl = tr.nlayers;
  std::size_t nt = tr.nt;
  if (opt.t_max >= 0.0) nt = std::upper_bound(tr.time.begin(), tr.time.end(), opt.t_max) - tr.time.begin();
  if (nt < 8) throw InputError("analyze: fewer than 8 samples before t_max");
  const std::span<const double> t(tr.time.data(), nt);
  a.dt = (t[nt - 1] - t[0]) / (nt - 1);

  // Measures on sigma - sigma(0) (docs/design.md §2.4): sigma_zz for P, sigma_zx for S.
  const bool S = tr.mode == 'S';
  const std::vector<double>* mf = S ? &tr.stress_zx : &tr.stress_zz;
  a.measure_field = S ? "layer_stress_zx" : "layer_stress_zz";
  if (mf->empty()) {  // a trace without stresses: the layer velocity is the next best pulse
    mf = S ? &tr.velocity_x : &tr.velocity_z;
    a.measure_field = S ? "layer_velocity_x" : "layer_velocity_z";
  }
  if (mf->empty()) throw InputError("analyze: the trace has neither the layer stress nor the layer velocity");

  const int last_index = static_cast<int>(nl) - 1 - tr.fixed_layers;
  a.last_free = static_cast<int>(std::lround(tr.layer_z[last_index] / tr.l0));
  auto column = [&](const std::vector<double>& f, std::size_t p) {
    std::vector<double> y(nt);
    for (std::size_t i = 0; i < nt; ++i) y[i] = f[i * nl + p] - f[p];
    return y;
  };

  // Default fit range (sec. 3.3): z/l0 = 10 .. min(150, last - 20).
  a.requested_lo = opt.lo >= 0 ? opt.lo : 10;
  a.requested_hi = opt.hi >= 0 ? opt.hi : std::min(150, a.last_free - 20);
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
    a.dispersion = dispersion(field, ntd, nz, a.dt, tr.l0, opt.dispersion);
  }

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

// ---------- text ----------
namespace {

// printf into a string (the report used to be printed straight to stdout by `analyze`).
template <class... T>
std::string sfmt(const char* f, T... x) {
  const int n = std::snprintf(nullptr, 0, f, x...);
  std::string out(static_cast<std::size_t>(std::max(n, 0)) + 1, '\0');
  std::snprintf(out.data(), out.size(), f, x...);
  out.pop_back();
  return out;
}

std::string measured_line(const char* name, const Measured& m, const char* unit) {
  return sfmt("%-16s %.6g +- %.2g %s\n", name, m.value, m.error, unit);
}

}  // namespace

std::string to_text(const TraceFile& f, const ChainAnalysis& a, bool table) {
  std::string o;
  o += sfmt("%s: chain trace of %s (%s), %zu contacts, %zu samples\n", f.path.c_str(), f.code.c_str(), f.case_name.c_str(),
            f.chain.ncontacts, f.chain.nt);
  if (a.shortened) o += sfmt("note: %s\n", a.note.c_str());
  o += sfmt("front speed over contacts %d..%d:\n", a.lo, a.hi);
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
      o += c.arrived ? sfmt(" contact %zu %.6g N at %.6g s;", j, c.peak_value.value, c.peak_time.value)
                     : sfmt(" contact %zu not arrived;", j);
    }
    o.back() = '\n';
    return o;
  }
  o += sfmt("%8s %12s %12s %12s %12s %12s\n", "contact", "t_peak(s)", "F_peak(N)", "t_half(s)", "F_lead(N)", "T(s)");
  for (const auto& c : a.contacts)
    o += sfmt("%8zu %12.6g %12.6g %12.6g %12.6g %12.6g\n", c.contact, c.peak_time.value, c.peak_value.value,
              c.half_peak_time.value, c.leading_max.value, c.duration.value);
  return o;
}

std::string to_text(const TraceFile& f, const CrystalAnalysis& a, bool table) {
  std::string o;
  o += sfmt("%s: crystal trace of %s (%s), %c wave (%s), %zu layers, %zu samples, dt = %.4g s, l0 = %.6g m\n",
            f.path.c_str(), f.code.c_str(), f.case_name.c_str(), a.mode, a.mode_source.c_str(), f.crystal.nlayers,
            f.crystal.nt, a.dt, a.l0);
  o += sfmt("measures on %s - its t=0 value (polarity %+g)\n", a.measure_field.c_str(), a.polarity);
  if (a.shortened) o += sfmt("note: %s\n", a.note.c_str());
  o += sfmt("speeds over z/l0 = %d..%d (n = %zu):\n", a.v_first_peak.lo, a.v_first_peak.hi, a.v_first_peak.n);
  o += measured_line("  first peak", a.v_first_peak.speed, "m/s");
  o += measured_line("  half peak", a.v_half_peak.speed, "m/s");
  o += measured_line("  1 % arrival", a.v_one_percent.speed, "m/s");
  const auto& d = a.dispersion;
  o += sfmt("dispersion (%s, %zu x %zu, domega = %.4g 1/s, %zu k bins, rms %.4g 1/s):\n", a.dispersion_field.c_str(), d.nt,
            d.nz, d.domega, d.n_fit, d.fit_rms);
  o += measured_line("  omega_0", {d.omega0, d.omega0_error}, "1/s");
  o += measured_line("  V(k->0)", {d.v_k0, d.v_k0_error}, "m/s");
  o += sfmt("local speeds need (l0/V)/dt = %.3g samples per layer delay here\n", a.delay_samples);
  o += sfmt("wavelength V T: T = %s (period = \"%s\", %s)\n",
            a.period_reading == PeriodReading::pulse ? "the leading pulse, 1 % arrival to the next 1 % crossing"
                                                     : "the full first oscillation, 1 % arrival to the third 1 % crossing",
            to_string(a.period_reading), a.period_source == "case_toml" ? "from the case" : a.period_source.c_str());
  o += sfmt("wavenumber k = (2/l0) arccos(V_k/V(k->0)): V_k = the local speed of the first peaks of %s "
            "(wavenumber_speed = \"%s\", %s)\n",
            a.wavenumber_speed_field.c_str(), to_string(a.wavenumber_speed),
            a.wavenumber_speed_source == "case_toml" ? "from the case" : a.wavenumber_speed_source.c_str());
  if (!table) return o;
  o += sfmt("%6s %12s %12s %12s %12s %12s %10s %9s %9s %10s %9s\n", "z/l0", "t_peak(s)", "peak", "t_half(s)",
            "T_pulse(s)", "T_osc(s)", "V(m/s)", "VT/l0", "Losc/l0", "V_k(m/s)", "2pi/kl0");
  for (const auto& L : a.layers) {
    const double lk = std::isfinite(L.k_from_speed.value) ? 2 * M_PI / L.k_from_speed.value / a.l0 : NAN;
    o += sfmt("%6.0f %12.6g %12.6g %12.6g %12.6g %12.6g %10.4g %9.3g %9.3g %10.4g %9.3g\n", L.z_over_l0,
              L.peak_time.value, L.peak_value.value, L.half_peak_time.value, L.duration.value, L.period.value,
              L.local_speed.value, L.lambda_vt.value / a.l0, L.oscillation_length.value / a.l0, L.k_speed.value, lk);
  }
  return o;
}

FileReport report_file(const std::string& path) {
  FileReport r;
  const TraceFile f = read_trace(path);
  try {
    if (f.model == "chain") {
      const ChainAnalysis a = analyze_chain(f.chain);
      r.text = to_text(f, a, false);
      r.json = to_json(f, a);
    } else {
      const CrystalAnalysis a = analyze_crystal(f.crystal);
      r.text = to_text(f, a, false);
      r.json = to_json(f, a);
    }
  } catch (const InputError& e) {
    r.error = e.what();
    r.text.clear();
    r.json.clear();
  }
  const std::string head = "measures (granwave analyze " + path + ", the same code; per-" +
                           (f.model == "chain" ? "contact" : "layer") + " table there):\n";
  r.text = r.error.empty() ? head + r.text : "measures: none, " + r.error + "\n";
  return r;
}

// ---------- JSON ----------
namespace {

std::string num(double v) {
  if (!std::isfinite(v)) return "null";
  char buf[40];
  std::snprintf(buf, sizeof buf, "%.10g", v);
  return buf;
}
std::string str(const std::string& s) {
  std::string o = "\"";
  for (char c : s) {
    if (c == '"' || c == '\\') o += '\\', o += c;
    else if (c == '\n') o += "\\n";
    else if (static_cast<unsigned char>(c) < 0x20) o += ' ';
    else o += c;
  }
  return o + "\"";
}
std::string qty(const Measured& m, const char* unit) {
  return "{\"value\": " + num(m.value) + ", \"error\": " + num(m.error) + ", \"unit\": \"" + unit + "\"}";
}
std::string qty(double v, const char* unit) { return "{\"value\": " + num(v) + ", \"unit\": \"" + unit + "\"}"; }
template <class T, class F>
std::string column_json(const std::vector<T>& rows, F get, const char* unit, bool with_error) {
  std::ostringstream o;
  o << "{\"unit\": \"" << unit << "\", \"values\": [";
  for (std::size_t i = 0; i < rows.size(); ++i) o << (i ? ", " : "") << num(get(rows[i]).value);
  o << "]";
  if (with_error) {
    o << ", \"errors\": [";
    for (std::size_t i = 0; i < rows.size(); ++i) o << (i ? ", " : "") << num(get(rows[i]).error);
    o << "]";
  }
  o << "}";
  return o.str();
}
std::string speed_json(const SpeedFit& f, const char* range_key) {
  std::ostringstream o;
  o << "{\"value\": " << num(f.speed.value) << ", \"error\": " << num(f.speed.error) << ", \"unit\": \"m/s\", \""
    << range_key << "\": [" << f.lo << ", " << f.hi << "], \"n\": " << f.n << "}";
  return o.str();
}
std::string header_json(const TraceFile& f) {
  return "  \"schema\": \"granwave-analyze/1\",\n  \"file\": " + str(f.path) + ",\n  \"code\": " + str(f.code) +
         ",\n  \"code_version\": " + str(f.code_version) + ",\n  \"case_name\": " + str(f.case_name) +
         ",\n  \"time_convention\": " + str(f.time_convention) + ",\n  \"model\": " + str(f.model) + ",\n";
}

}  // namespace

std::string to_json(const TraceFile& f, const CrystalAnalysis& a) {
  std::ostringstream o;
  o << "{\n" << header_json(f);
  o << "  \"mode\": " << str(std::string(1, a.mode)) << ",\n  \"mode_source\": " << str(a.mode_source) << ",\n";
  o << "  \"measure_field\": " << str(a.measure_field) << ",\n  \"polarity\": " << num(a.polarity) << ",\n";
  o << "  \"period_reading\": " << str(to_string(a.period_reading)) << ",\n  \"period_reading_source\": "
    << str(a.period_source) << ",\n";
  o << "  \"wavenumber_speed_reading\": " << str(to_string(a.wavenumber_speed))
    << ",\n  \"wavenumber_speed_reading_source\": " << str(a.wavenumber_speed_source)
    << ",\n  \"wavenumber_speed_field\": " << str(a.wavenumber_speed_field) << ",\n";
  o << "  \"l0\": " << qty(a.l0, "m") << ",\n  \"output_interval\": " << qty(a.dt, "s") << ",\n";
  o << "  \"last_free_layer_z_over_l0\": " << a.last_free << ",\n";
  o << "  \"fit_range\": {\"z_over_l0\": [" << a.v_first_peak.lo << ", " << a.v_first_peak.hi << "], \"requested\": ["
    << a.requested_lo << ", " << a.requested_hi << "], \"shortened\": " << (a.shortened ? "true" : "false")
    << ", \"note\": " << str(a.note) << "},\n";
  o << "  \"v_first_peak\": " << speed_json(a.v_first_peak, "z_over_l0") << ",\n";
  o << "  \"v_half_peak\": " << speed_json(a.v_half_peak, "z_over_l0") << ",\n";
  o << "  \"v_one_percent\": " << speed_json(a.v_one_percent, "z_over_l0") << ",\n";
  const auto& d = a.dispersion;
  o << "  \"omega_0\": " << qty(Measured{d.omega0, d.omega0_error}, "1/s") << ",\n";
  o << "  \"v_k0\": " << qty(Measured{d.v_k0, d.v_k0_error}, "m/s") << ",\n";
  o << "  \"dispersion\": {\"field\": " << str(a.dispersion_field) << ", \"nt\": " << d.nt << ", \"nz\": " << d.nz
    << ", \"domega\": " << qty(d.domega, "1/s") << ", \"dk\": " << qty(d.dk, "1/m") << ", \"n_fit\": " << d.n_fit
    << ", \"fit_rms\": " << qty(d.fit_rms, "1/s") << ",\n    \"k\": {\"unit\": \"1/m\", \"values\": [";
  for (std::size_t i = 0; i < d.k.size(); ++i) o << (i ? ", " : "") << num(d.k[i]);
  o << "]},\n    \"omega_max\": {\"unit\": \"1/s\", \"values\": [";
  for (std::size_t i = 0; i < d.omega_max.size(); ++i) o << (i ? ", " : "") << num(d.omega_max[i]);
  o << "]}},\n";
  o << "  \"local_speed\": {\"method\": \"slowness = (1,2,2,1)/6-weighted mean of the 4 first-peak delays over "
       "layers i-2..i+2\", \"delay_samples\": "
    << num(a.delay_samples) << "},\n";
  // The seed's wavelength table (sec. 3.4) at z/l0 = 10, 15, 20, 80, 150.
  o << "  \"wavelength_at\": [";
  bool first = true;
  for (int zq : {10, 15, 20, 80, 150}) {
    for (const auto& L : a.layers) {
      if (std::lround(L.z_over_l0) != zq) continue;
      const double k = L.k_from_speed.value, ke = L.k_from_speed.error;
      const double two_pi = 2.0 * std::acos(-1.0);
      Measured lk{std::isfinite(k) ? two_pi / k / a.l0 : kNaN, std::isfinite(k) ? two_pi * ke / (k * k) / a.l0 : kNaN};
      o << (first ? "" : ",") << "\n    {\"z_over_l0\": " << zq << ", \"local_speed\": " << qty(L.local_speed, "m/s")
        << ", \"duration\": " << qty(L.duration, "s") << ", \"period\": " << qty(L.period, "s")
        << ", \"oscillation_length_over_l0\": "
        << qty(Measured{L.oscillation_length.value / a.l0, L.oscillation_length.error / a.l0}, "1")
        << ", \"lambda_vt_over_l0\": " << qty(Measured{L.lambda_vt.value / a.l0, L.lambda_vt.error / a.l0}, "1")
        << ", \"k_speed\": " << qty(L.k_speed, "m/s") << ", \"lambda_k_over_l0\": " << qty(lk, "1") << "}";
      first = false;
    }
  }
  o << "],\n";
  const auto& Ls = a.layers;
  o << "  \"layers\": {\n    \"layer\": [";
  for (std::size_t i = 0; i < Ls.size(); ++i) o << (i ? ", " : "") << Ls[i].layer;
  o << "],\n    \"z_over_l0\": [";
  for (std::size_t i = 0; i < Ls.size(); ++i) o << (i ? ", " : "") << num(Ls[i].z_over_l0);
  o << "],\n    \"arrived\": [";
  for (std::size_t i = 0; i < Ls.size(); ++i) o << (i ? ", " : "") << (Ls[i].arrived ? "true" : "false");
  o << "],\n";
  const char* su = a.measure_field.find("stress") != std::string::npos ? "Pa" : "m/s";
  o << "    \"peak_time\": " << column_json(Ls, [](const LayerMeasures& L) { return L.peak_time; }, "s", true) << ",\n";
  o << "    \"peak_value\": " << column_json(Ls, [](const LayerMeasures& L) { return L.peak_value; }, su, true) << ",\n";
  o << "    \"half_peak_time\": " << column_json(Ls, [](const LayerMeasures& L) { return L.half_peak_time; }, "s", true) << ",\n";
  o << "    \"one_percent_time\": " << column_json(Ls, [](const LayerMeasures& L) { return L.one_percent_time; }, "s", true) << ",\n";
  o << "    \"duration\": " << column_json(Ls, [](const LayerMeasures& L) { return L.duration; }, "s", true) << ",\n";
  o << "    \"period\": " << column_json(Ls, [](const LayerMeasures& L) { return L.period; }, "s", true) << ",\n";
  o << "    \"oscillation_length\": " << column_json(Ls, [](const LayerMeasures& L) { return L.oscillation_length; }, "m", false) << ",\n";
  o << "    \"leading_max\": " << column_json(Ls, [](const LayerMeasures& L) { return L.leading_max; }, su, true) << ",\n";
  o << "    \"local_speed\": " << column_json(Ls, [](const LayerMeasures& L) { return L.local_speed; }, "m/s", true) << ",\n";
  o << "    \"lambda_vt\": " << column_json(Ls, [](const LayerMeasures& L) { return L.lambda_vt; }, "m", true) << ",\n";
  o << "    \"displacement_peak_time\": " << column_json(Ls, [](const LayerMeasures& L) { return L.displacement_peak_time; }, "s", true) << ",\n";
  o << "    \"k_speed\": " << column_json(Ls, [](const LayerMeasures& L) { return L.k_speed; }, "m/s", true) << ",\n";
  o << "    \"k_from_speed\": " << column_json(Ls, [](const LayerMeasures& L) { return L.k_from_speed; }, "1/m", true) << "\n";
  o << "  }\n}\n";
  return o.str();
}

std::string to_json(const TraceFile& f, const ChainAnalysis& a) {
  std::ostringstream o;
  o << "{\n" << header_json(f);
  o << "  \"fit_range\": {\"contacts\": [" << a.lo << ", " << a.hi << "], \"shortened\": " << (a.shortened ? "true" : "false")
    << ", \"note\": " << str(a.note) << "},\n";
  o << "  \"v_first_peak\": " << qty(a.v_first_peak, "m/s") << ",\n";
  o << "  \"v_half_peak\": " << qty(a.v_half_peak, "m/s") << ",\n";
  o << "  \"v_first_peak_contacts\": " << qty(a.v_first_peak_contacts, "contacts/s") << ",\n";
  o << "  \"v_half_peak_contacts\": " << qty(a.v_half_peak_contacts, "contacts/s") << ",\n";
  const auto& Cs = a.contacts;
  o << "  \"contacts\": {\n    \"contact\": [";
  for (std::size_t i = 0; i < Cs.size(); ++i) o << (i ? ", " : "") << Cs[i].contact;
  o << "],\n    \"position\": {\"unit\": \"m\", \"values\": [";
  for (std::size_t i = 0; i < Cs.size(); ++i) o << (i ? ", " : "") << num(Cs[i].position);
  o << "]},\n    \"arrived\": [";
  for (std::size_t i = 0; i < Cs.size(); ++i) o << (i ? ", " : "") << (Cs[i].arrived ? "true" : "false");
  o << "],\n";
  o << "    \"peak_time\": " << column_json(Cs, [](const ContactMeasures& c) { return c.peak_time; }, "s", true) << ",\n";
  o << "    \"peak_value\": " << column_json(Cs, [](const ContactMeasures& c) { return c.peak_value; }, "N", true) << ",\n";
  o << "    \"half_peak_time\": " << column_json(Cs, [](const ContactMeasures& c) { return c.half_peak_time; }, "s", true) << ",\n";
  o << "    \"one_percent_time\": " << column_json(Cs, [](const ContactMeasures& c) { return c.one_percent_time; }, "s", true) << ",\n";
  o << "    \"duration\": " << column_json(Cs, [](const ContactMeasures& c) { return c.duration; }, "s", true) << ",\n";
  o << "    \"leading_max\": " << column_json(Cs, [](const ContactMeasures& c) { return c.leading_max; }, "N", true) << "\n";
  o << "  }\n}\n";
  return o.str();
}

}  // namespace granwave::analysis
