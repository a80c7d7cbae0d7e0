// Dispersion relation from a (t, z) field, seed 002 sec. 3.4: 2D FFT (FFTW), the power-weighted
// frequency of each wavenumber, omega_max(k) = sum |F|^phi omega / sum |F|^phi (phi = 4), and the
// least-squares sine fit omega(k) = omega_0 sin(k l0/2), giving V(k -> 0) = omega_0 l0/2.
//
// Conventions. The field u(t_n, z_p) is sampled at t_n = n dt (n < nt), z_p = p dz (p < nz). Its
// transform is F(omega, k) = sum_n sum_p u e^{-i omega t_n + i k z_p}, so a wave travelling towards
// +z (u ~ cos(k z - omega t)) appears at omega > 0, k > 0. omega_m = m domega with
// domega = 2 pi/(nt dt) (the record length is nt dt, not (nt - 1) dt), k_q = q dk with
// dk = 2 pi/(nz dz); indices above half the length are the negative frequencies / wavenumbers
// (they are moved to their signed values, never left at 2 pi/dt - ...). Real input: only
// omega >= 0 is kept (F(-omega, -k) = conj F(omega, k)).
#pragma once
#include <cstddef>
#include <vector>

namespace granwave::analysis {

// The small-k range of DispersionResult::small_k_slope: a sine branch omega_0 sin(k dz/2) is within
// 1.1 % of its slope there ((k dz)^2/24 at 0.5).
inline constexpr double kSmallKdz = 0.5;

struct DispersionOptions {
  double phi = 4.0;             // power of |F| in the weighted average (seed: 4)
  // Wavenumbers used by the sine fit, as fractions of the zone edge pi/dz: (k_min, k_max].
  double k_min_fraction = 0.0;
  double k_max_fraction = 1.0;
  bool keep_spectrum = false;   // store |F| (for figures)
};

struct DispersionResult {
  std::size_t nt = 0, nz = 0;
  double dt = 0.0, dz = 0.0;         // s, m
  double domega = 0.0, dk = 0.0;     // 1/s, 1/m: the FFT resolution
  // omega_max at each positive wavenumber bin k_q, q = 1..nz/2
  std::vector<double> k;             // 1/m
  std::vector<double> omega_max;     // 1/s
  std::vector<double> weight;        // sum over omega of |F|^2 at that k (relative signal power)
  // Sine fit over the bins in (k_min, k_max]
  double omega0 = 0.0, omega0_error = 0.0;  // 1/s, standard error from the residuals
  double v_k0 = 0.0, v_k0_error = 0.0;      // omega_0 dz/2 (m/s)
  double fit_rms = 0.0;                     // rms residual of omega_max (1/s)
  std::size_t n_fit = 0;
  // The small-k slope (issue 39): omega_max = V k through the origin over the bins with
  // k dz <= kSmallKdz, least squares; NaN with fewer than two such bins (a record too short in z).
  // No model of the branch: the speed a disordered packing's long waves show, beside the sine's v_k0.
  double small_k_slope = 0.0, small_k_slope_error = 0.0;  // m/s
  double small_k_max = 0.0;                                // the largest k used (1/m)
  // (domega/2) sum k / sum k^2: the slope's worst case when every omega_max sits half a frequency
  // bin off its tone (a short record: at the smallest k, omega may be below one bin)
  double small_k_resolution = 0.0;                         // m/s
  std::size_t small_k_n = 0;
  // Optional |F| on omega_m >= 0 (rows, m = 0..nt/2) by signed k (columns, ascending from
  // -(nz-1)/2 dk .. nz/2 dk), row-major; k_axis, omega_axis give the axes.
  std::vector<double> spectrum, k_axis, omega_axis;
};

// `field` is row-major [nt, nz]: field[n * nz + p] = u(t_n, z_p), already baseline-subtracted.
DispersionResult dispersion(const std::vector<double>& field, std::size_t nt, std::size_t nz, double dt, double dz,
                            const DispersionOptions& options = {});

// k(z) = (2/l0) arccos(V(z)/V(k->0)) (seed 002 sec. 3.4): the wavenumber whose group speed on the
// sine branch, d omega/dk = V(k->0) cos(k l0/2), equals the measured local speed V(z).
// NaN when V > V(k->0) or V <= 0.
double wavenumber_from_speed(double v, double v_k0, double l0);

}  // namespace granwave::analysis
