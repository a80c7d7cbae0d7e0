// Ensemble statistics of the studies: per-group summaries, the M_c hinge fit with its bootstrap
// interval, exponential decay fits.
#pragma once
#include <cstdint>
#include <span>
#include <vector>

namespace granwave::sweep {

// Sample quantile, linear interpolation between order statistics (R's type 7); NaN when empty.
double quantile(std::vector<double> v, double q);

struct Summary {
  std::size_t count = 0;
  double mean = 0.0, median = 0.0, stderr_mean = 0.0, q25 = 0.0, q75 = 0.0, min = 0.0, max = 0.0;
};
// stderr_mean = sample standard deviation / sqrt(n) (0 for n = 1).
Summary summarize(std::span<const double> v);

// Continuous hinge: y = plateau for x <= x_c, plateau + slope (x - x_c) above (seed 001 sec. 3:
// a plateau at low M, then a rise above the threshold M_c).
struct HingeFit {
  bool ok = false;
  double x_c = 0.0, plateau = 0.0, slope = 0.0, sse = 0.0;
};
// Least squares over every point: for fixed x_c the model is linear in (plateau, slope); x_c is
// found by a grid over [lowest, second-highest distinct x] then golden-section refinement.
HingeFit fit_hinge(std::span<const double> x, std::span<const double> y);

struct HingeBootstrap {
  HingeFit fit;               // the fit of the data themselves
  double lo = 0.0, hi = 0.0;  // central interval of x_c over the bootstrap replicas
  double sd = 0.0;            // standard deviation of x_c over the replicas
  std::size_t replicas = 0;
};
// Bootstrap over configurations within each x (points with equal x form a group; each replica
// redraws every group with replacement from CounterRng(seed, replica)). `level` = 0.95 gives the
// 2.5 % and 97.5 % percentiles.
HingeBootstrap bootstrap_hinge(std::span<const double> x, std::span<const double> y, std::size_t replicas,
                               std::uint64_t seed, double level = 0.95);

// F = F0 exp(-x / gamma) by least squares on ln F (points with F <= 0 skipped): decay rate
// kappa = 1/gamma with its standard error.
struct DecayFit {
  bool ok = false;
  double kappa = 0.0, kappa_error = 0.0, ln_f0 = 0.0;
  std::size_t n = 0;
};
DecayFit fit_exponential_decay(std::span<const double> x, std::span<const double> f);

}  // namespace granwave::sweep
