// Ensemble statistics of the studies: per-group summaries, the M_c hinge fits with their bootstrap
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

// M_c of seed 001 (sec. 3, Figs. 6-7): a plateau at low M, then a rise; M_c is the threshold between
// the two regimes. Two continuous hinges, one per law of the rise above x_c:
//   line:        y = plateau + slope (x - x_c)_+            (the seed's two straight regimes)
//   exponential: y = plateau exp(slope (x - x_c)_+)          (Appendix 3: above M_c each reversed
//                dimer passes a fraction of the pulse, F ~ T^((3/5) n) with n ~ N_total (1 - M), so
//                ln F rises linearly in M; fitted as the line hinge on ln y)
// The rise of the ensembles is curved (convex): the straight hinge then puts its knee where the
// line through the upper rise meets the plateau, later than where the data leave the plateau (Fig. 7,
// N_total = 256: 0.896 against 0.854), and its bootstrap interval, which measures resampling only,
// excludes the other law's threshold by many widths. So the uncertainty of M_c is reported as the
// union of both laws' resampling intervals: when the rise is straight the laws agree and the union
// is the resampling interval; when it is curved the union stretches over the gap that the misfit
// opens. Which law fits is measured by the lack-of-fit ratio (below); the headline M_c is that of
// the law whose residuals are less structured.
enum class Rise { line, exponential };

struct HingeFit {
  bool ok = false;
  Rise rise = Rise::line;
  double x_c = 0.0, plateau = 0.0, slope = 0.0;
  double sse = 0.0;  // over every point, in the fitted scale (y for line, ln y for exponential)
  // Lack of fit: [sum_g n_g (mean_g - fit(x_g))^2 / (G - 3)] / [pure error / (n - G)], groups g =
  // points of equal x (the configurations of one M). About 1 when the law describes the group means
  // to within their scatter; NaN without replicates or with fewer than 4 distinct x.
  double lack_of_fit = 0.0;
};
// Least squares over every point: for fixed x_c the law is linear in (plateau or ln plateau, slope);
// x_c is found by a grid over [lowest, second-highest distinct x] then golden-section refinement.
// The exponential law needs y > 0 (ok = false otherwise).
HingeFit fit_hinge(std::span<const double> x, std::span<const double> y, Rise rise = Rise::line);
double hinge_value(const HingeFit& f, double x);

struct HingeBootstrap {
  HingeFit fit;                // the headline: the law with the smaller lack-of-fit ratio
  HingeFit line, exponential;  // both laws fitted to the data themselves
  double lo = 0.0, hi = 0.0;   // the reported interval: union of the two laws' intervals
  double line_lo = 0.0, line_hi = 0.0, exp_lo = 0.0, exp_hi = 0.0;  // each law's resampling interval
  double sd = 0.0;             // standard deviation of the headline law's x_c over the replicas
  std::size_t replicas = 0;
};
// Bootstrap over configurations within each x (points with equal x form a group; each replica
// redraws every group with replacement from CounterRng(seed, replica)) and refits both laws.
// `level` = 0.95 gives each law's 2.5 % and 97.5 % percentiles.
HingeBootstrap bootstrap_hinge(std::span<const double> x, std::span<const double> y, std::size_t replicas,
                               std::uint64_t seed, double level = 0.95);
const char* rise_name(Rise r);

// F = F0 exp(-x / gamma) by least squares on ln F (points with F <= 0 skipped): decay rate
// kappa = 1/gamma with its standard error.
struct DecayFit {
  bool ok = false;
  double kappa = 0.0, kappa_error = 0.0, ln_f0 = 0.0;
  std::size_t n = 0;
};
DecayFit fit_exponential_decay(std::span<const double> x, std::span<const double> f);

}  // namespace granwave::sweep
