// Front speeds against pulse duration (analysis/pulse_fronts.hpp).
#include "analysis/pulse_fronts.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <numbers>

#include "core/error.hpp"

namespace granwave::analysis {

namespace {

// y[n, p] = sum over j ascending of w[j] v[max(n - j, 0), p]: every output's terms in this order,
// from 0.0 (the smoothing's definition, and the sums' bits).
void convolve_rows(const std::vector<double>& v, std::vector<double>& y, std::size_t nt, std::size_t nl,
                   const std::vector<double>& w) {
  for (std::size_t n = 0; n < nt; ++n)
    for (std::size_t j = 0; j < w.size(); ++j) {
      const double wj = w[j];
      const double* row = &v[(n >= j ? n - j : 0) * nl];
      double* out = &y[n * nl];
      for (std::size_t p = 0; p < nl; ++p) out[p] += wj * row[p];
    }
}

// The same for kRows samples from n0 and kCols layers from p0, the sums held in registers (GCC's
// vector type: with plain arrays it kept them in memory): the rows are visited newest first, which
// is each output's j ascending, so that one load of a row serves the kRows outputs it enters (the
// plain order loads each row once per output, and was bound by the L2).
using Lanes = double __attribute__((vector_size(64), aligned(8)));  // eight doubles, unaligned loads
#ifdef __AVX512F__
constexpr std::size_t kRows = 8, kLanes = 2;  // 16 zmm of sums
#else
constexpr std::size_t kRows = 4, kLanes = 1;  // 4 x 2 ymm of sums
#endif
constexpr std::size_t kCols = 8 * kLanes;
void convolve_block(const double* v, double* y, std::size_t nl, std::size_t n0, std::size_t p0, const std::vector<double>& w) {
  const long m = static_cast<long>(w.size()), first = static_cast<long>(n0);
  Lanes acc[kRows][kLanes] = {};
  for (long r = first + static_cast<long>(kRows) - 1; r > first - m; --r) {
    const Lanes* row = reinterpret_cast<const Lanes*>(v + static_cast<std::size_t>(std::max(r, 0L)) * nl + p0);
#pragma GCC unroll 8
    for (std::size_t b = 0; b < kRows; ++b) {
      const long j = first + static_cast<long>(b) - r;  // output n0 + b's term of row r
      if (j < 0 || j >= m) continue;
      const double wj = w[static_cast<std::size_t>(j)];
#pragma GCC unroll 2
      for (std::size_t q = 0; q < kLanes; ++q) acc[b][q] += wj * row[q];
    }
  }
  for (std::size_t b = 0; b < kRows; ++b)
    for (std::size_t q = 0; q < kLanes; ++q)
      for (std::size_t p = 0; p < 8; ++p) y[(n0 + b) * nl + p0 + 8 * q + p] = acc[b][q][p];
}

}  // namespace

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
  y.assign(nt * nl, 0.0);
  if (nt < kRows || nl < kCols) {
    convolve_rows(v, y, nt, nl, w);
  } else {
    // Blocks of kRows samples by kCols layers; the last block of each kind overlaps the one before
    // (its outputs made again, the same bits) so that every block is whole.
    for (std::size_t n0 = 0;; n0 += kRows) {
      const std::size_t n = std::min(n0, nt - kRows);
      for (std::size_t p0 = 0;; p0 += kCols) {
        convolve_block(v.data(), y.data(), nl, n, std::min(p0, nl - kCols), w);
        if (p0 + kCols >= nl) break;
      }
      if (n0 + kRows >= nt) break;
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
