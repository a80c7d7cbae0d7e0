// Front speeds against pulse duration (analysis/pulse_fronts.hpp).
#include "analysis/pulse_fronts.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <numbers>

#include "core/error.hpp"

namespace granwave::analysis {

CrystalTrace smoothed(const CrystalTrace& trace, double duration, const CrystalAnalysisOptions& options) {
  const PulseSeries ps = pulse_series(trace, options);
  const std::vector<double>& v = trace.*ps.member;
  CrystalTrace out;
  static_cast<CrystalTraceHeader&>(out) = trace;  // only the measured series is carried
  std::vector<double>& y = out.*ps.member;
  const std::size_t nt = trace.nt, nl = trace.nlayers;
  const std::size_t m = nt < 2 ? 0 : static_cast<std::size_t>(std::lround(duration / (trace.time[1] - trace.time[0])));
  if (m < 2 || v.size() != nt * nl) {
    y = v;
    return out;
  }
  // Hann window over m samples, sin^2(pi (j + 1/2) / m), normalised to unit sum.
  std::vector<double> w(m);
  double sum = 0.0;
  for (std::size_t j = 0; j < m; ++j) sum += w[j] = std::pow(std::sin(std::numbers::pi * (j + 0.5) / m), 2);
  for (double& x : w) x /= sum;
  // Each (n, p) sums w[j] v[n - j] over j ascending; p innermost runs along a contiguous row, a block
  // of kBlock layers' sums held in registers through the j loop (loads of v only, no stores per j).
  constexpr std::size_t kBlock = 64;
  y.assign(nt * nl, 0.0);
  for (std::size_t n = 0; n < nt; ++n) {
    double* out_row = y.data() + n * nl;
    for (std::size_t p0 = 0; p0 < nl; p0 += kBlock) {
      if (p0 + kBlock <= nl) {
        double acc[kBlock] = {};
        for (std::size_t j = 0; j < m; ++j) {
          const double wj = w[j];
          const double* row = &v[(n >= j ? n - j : 0) * nl + p0];
          for (std::size_t p = 0; p < kBlock; ++p) acc[p] += wj * row[p];
        }
        std::copy(acc, acc + kBlock, out_row + p0);
      } else {
        for (std::size_t j = 0; j < m; ++j) {
          const double wj = w[j];
          const double* row = &v[(n >= j ? n - j : 0) * nl];
          for (std::size_t p = p0; p < nl; ++p) out_row[p] += wj * row[p];
        }
      }
    }
  }
  return out;
}

std::vector<PulseFront> pulse_fronts(const CrystalTrace& trace, const CrystalAnalysisOptions& options,
                                     const CrystalAnalysis& raw, const std::vector<double>& travel_layers) {
  std::vector<PulseFront> out;
  const double v = raw.v_first_peak.speed.value;
  if (!(v > 0.0) || !(raw.l0 > 0.0)) return out;
  CrystalAnalysisOptions o = options;
  o.lattice.reset();  // the fronts only: no ridge against a branch
  o.fronts_only = true;
  // The smoothed first peak comes about T/2 after the raw one: that must lie in the record at the
  // range's last layer; and the whole smoothed pulse must pass there before its reflection from the
  // top wall (one layer above the last free one) returns: T <= 2 (z_wall - z_hi) / V.
  double t_last = kNaN;
  for (const auto& L : raw.layers)
    if (std::lround(L.z_over_l0) == raw.v_first_peak.hi) t_last = L.peak_time.value;
  const double t_end = options.t_max >= 0.0 ? std::min(options.t_max, trace.time.back()) : trace.time.back();
  for (double m : travel_layers) {
    PulseFront f;
    f.travel_layers = m;
    f.duration = m * raw.l0 / v;
    const double t_back = 2.0 * (raw.last_free + 1 - raw.v_first_peak.hi) * raw.l0 / v;
    if (!(t_last + 0.5 * f.duration <= t_end) || !(f.duration <= t_back)) {
      char buf[240];
      std::snprintf(buf, sizeof buf,
                    "not measured: at z/l0 = %d the raw first peak (t = %.4g s) plus T/2 passes the record's end (%.4g "
                    "s), or T exceeds the %.4g s before the top wall's reflection returns",
                    raw.v_first_peak.hi, t_last, t_end, t_back);
      f.error = buf;
      out.push_back(f);
      continue;
    }
    try {
      const CrystalAnalysis a = analyze_crystal(smoothed(trace, f.duration, o), o);
      f.first_peak = a.v_first_peak;
      f.half_peak = a.v_half_peak;
    } catch (const InputError& e) {
      f.error = e.what();
    }
    out.push_back(f);
  }
  return out;
}

void add_pulse_fronts(const CrystalTrace& trace, const CrystalAnalysisOptions& options, CrystalAnalysis& a) {
  a.pulse_fronts = pulse_fronts(trace, options, a);
}

}  // namespace granwave::analysis
