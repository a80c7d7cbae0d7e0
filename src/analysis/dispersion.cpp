// The dispersion relation from a (t, z) field by 2D FFT (analysis/dispersion.hpp).
#include "analysis/dispersion.hpp"

#include <fftw3.h>

#include <algorithm>
#include <cmath>
#include <complex>
#include <memory>
#include <mutex>
#include <numbers>
#include <string>

#include "core/error.hpp"

namespace granwave::analysis {
namespace {
// FFTW's planner and fftw_destroy_plan are not thread-safe (only fftw_execute is), and studies
// measure their members on several OpenMP threads at once.
std::mutex fftw_planner_mutex;

struct PlanDeleter {
  void operator()(fftw_plan_s* p) const {
    const std::lock_guard<std::mutex> lock(fftw_planner_mutex);
    fftw_destroy_plan(p);
  }
};
struct FftwFree {
  void operator()(void* p) const { fftw_free(p); }
};
}  // namespace

DispersionResult dispersion(const std::vector<double>& field, std::size_t nt, std::size_t nz, double dt, double dz,
                            const DispersionOptions& opt) {
  if (nt < 4 || nz < 4) throw InputError("dispersion: the (t, z) field needs at least 4 x 4 samples");
  if (field.size() != nt * nz) throw InputError("dispersion: field size differs from nt * nz");
  if (!(dt > 0.0) || !(dz > 0.0)) throw InputError("dispersion: dt and dz must be > 0");
  constexpr double two_pi = 2.0 * std::numbers::pi;
  DispersionResult r;
  r.nt = nt;
  r.nz = nz;
  r.dt = dt;
  r.dz = dz;
  r.domega = two_pi / (static_cast<double>(nt) * dt);
  r.dk = two_pi / (static_cast<double>(nz) * dz);

  // FFTW r2c halves the last dimension: put time last, [nz][nt] -> [nz][nt/2 + 1].
  const std::size_t nw = nt / 2 + 1;
  const std::unique_ptr<double, FftwFree> in_buf(fftw_alloc_real(nt * nz));
  const std::unique_ptr<fftw_complex, FftwFree> out_buf(fftw_alloc_complex(nz * nw));
  double* in = in_buf.get();
  fftw_complex* out = out_buf.get();
  if (!in || !out) throw RunError("dispersion: FFTW allocation failed");
  std::unique_ptr<fftw_plan_s, PlanDeleter> plan;
  {
    const std::lock_guard<std::mutex> lock(fftw_planner_mutex);
    plan.reset(fftw_plan_dft_r2c_2d(static_cast<int>(nz), static_cast<int>(nt), in, out, FFTW_ESTIMATE));
  }
  if (!plan) throw RunError("dispersion: FFTW could not plan the transform");
  for (std::size_t n = 0; n < nt; ++n)
    for (std::size_t p = 0; p < nz; ++p) in[p * nt + n] = field[n * nz + p];
  fftw_execute(plan.get());
  // |F| once for every (k, omega), in place of the real parts (the spectrum, the maximum and the
  // weights below read each several times).
  double amax = 0.0;
  for (std::size_t i = 0; i < nz * nw; ++i) {
    out[i][0] = std::hypot(out[i][0], out[i][1]);
    amax = std::max(amax, out[i][0]);
  }
  // |F(omega_m, k_s)| for signed s: FFTW's forward sign is e^{-i k z}; ours is e^{+i k z}, so the
  // column of wavenumber s is FFTW's row (-s) mod nz.
  auto amp = [&](long s, std::size_t m) {
    const long q = ((-s) % static_cast<long>(nz) + static_cast<long>(nz)) % static_cast<long>(nz);
    return out[static_cast<std::size_t>(q) * nw + m][0];
  };

  if (opt.keep_spectrum) {
    const long s_lo = -static_cast<long>((nz - 1) / 2), s_hi = static_cast<long>(nz / 2);
    for (long s = s_lo; s <= s_hi; ++s) r.k_axis.push_back(s * r.dk);
    for (std::size_t m = 0; m < nw; ++m) r.omega_axis.push_back(m * r.domega);
    r.spectrum.resize(nw * r.k_axis.size());
    for (std::size_t m = 0; m < nw; ++m)
      for (long s = s_lo; s <= s_hi; ++s) r.spectrum[m * r.k_axis.size() + (s - s_lo)] = amp(s, m);
  }

  // omega_max(k) = sum |F|^phi omega / sum |F|^phi over omega >= 0, for each k > 0.
  const std::size_t q_max = nz / 2;
  for (std::size_t q = 1; q <= q_max; ++q) {
    double num = 0.0, den = 0.0, power = 0.0;
    for (std::size_t m = 0; m < nw; ++m) {
      const double a = amax > 0.0 ? amp(static_cast<long>(q), m) / amax : 0.0;
      const double w = std::pow(a, opt.phi);
      num += w * (m * r.domega);
      den += w;
      power += a * a;
    }
    r.k.push_back(q * r.dk);
    r.omega_max.push_back(den > 0.0 ? num / den : 0.0);
    r.weight.push_back(power);
  }
  plan.reset();

  // The small-k slope: omega_max = V k through the origin.
  {
    double kk = 0.0, kw = 0.0, ks = 0.0;
    std::vector<std::size_t> small;
    for (std::size_t i = 0; i < r.k.size(); ++i)
      if (r.k[i] * dz <= kSmallKdz + 1e-12 && r.weight[i] > 0.0) {
        kk += r.k[i] * r.k[i], kw += r.k[i] * r.omega_max[i], ks += r.k[i];
        small.push_back(i);
        r.small_k_max = r.k[i];
      }
    r.small_k_n = small.size();
    if (r.small_k_n >= 2) {
      r.small_k_slope = kw / kk;
      double rss = 0.0;
      for (auto i : small) rss += std::pow(r.omega_max[i] - r.small_k_slope * r.k[i], 2);
      r.small_k_slope_error = std::sqrt(rss / (r.small_k_n - 1) / kk);
      r.small_k_resolution = 0.5 * r.domega * ks / kk;
    } else {
      r.small_k_slope = r.small_k_slope_error = r.small_k_resolution = std::nan("");
    }
  }

  // Least squares omega_max = omega_0 s_k, s_k = sin(k dz/2): linear in omega_0.
  const double k_edge = std::numbers::pi / dz;
  double ss = 0.0, sw = 0.0;
  std::vector<std::size_t> used;
  for (std::size_t i = 0; i < r.k.size(); ++i) {
    const double f = r.k[i] / k_edge;
    if (f <= opt.k_min_fraction || f > opt.k_max_fraction + 1e-12) continue;
    if (!(r.weight[i] > 0.0)) continue;
    const double s = std::sin(0.5 * r.k[i] * dz);
    ss += s * s;
    sw += s * r.omega_max[i];
    used.push_back(i);
  }
  r.n_fit = used.size();
  if (r.n_fit < 2 || ss == 0.0) return r;
  r.omega0 = sw / ss;
  double rss = 0.0;
  for (auto i : used) {
    const double res = r.omega_max[i] - r.omega0 * std::sin(0.5 * r.k[i] * dz);
    rss += res * res;
  }
  r.fit_rms = std::sqrt(rss / r.n_fit);
  r.omega0_error = std::sqrt(rss / (r.n_fit - 1) / ss);
  r.v_k0 = 0.5 * r.omega0 * dz;
  r.v_k0_error = 0.5 * r.omega0_error * dz;
  return r;
}

double wavenumber_from_speed(double v, double v_k0, double l0) {
  if (!(v > 0.0) || !(v_k0 > 0.0) || v > v_k0) return std::nan("");
  return (2.0 / l0) * std::acos(v / v_k0);
}

}  // namespace granwave::analysis
