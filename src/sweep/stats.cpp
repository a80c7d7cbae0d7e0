#include "sweep/stats.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <map>

#include "analysis/measures.hpp"
#include "core/rng.hpp"

namespace granwave::sweep {

namespace {
constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();
}

double quantile(std::vector<double> v, double q) {
  if (v.empty()) return kNaN;
  std::sort(v.begin(), v.end());
  const double h = q * static_cast<double>(v.size() - 1);
  const auto lo = static_cast<std::size_t>(std::floor(h));
  const std::size_t hi = std::min(lo + 1, v.size() - 1);
  return v[lo] + (h - static_cast<double>(lo)) * (v[hi] - v[lo]);
}

Summary summarize(std::span<const double> v) {
  Summary s;
  s.count = v.size();
  if (v.empty()) {
    s.mean = s.median = s.stderr_mean = s.q25 = s.q75 = s.min = s.max = kNaN;
    return s;
  }
  std::vector<double> c(v.begin(), v.end());
  double sum = 0.0;
  for (double x : c) sum += x;
  s.mean = sum / static_cast<double>(c.size());
  double ss = 0.0;
  for (double x : c) ss += (x - s.mean) * (x - s.mean);
  s.stderr_mean = c.size() > 1 ? std::sqrt(ss / static_cast<double>(c.size() - 1) / static_cast<double>(c.size())) : 0.0;
  s.median = quantile(c, 0.5);
  s.q25 = quantile(c, 0.25);
  s.q75 = quantile(c, 0.75);
  s.min = *std::min_element(c.begin(), c.end());
  s.max = *std::max_element(c.begin(), c.end());
  return s;
}

namespace {

// Linear least squares y = a + b h(x), h = max(x - xc, 0), closed form.
HingeFit hinge_at(std::span<const double> x, std::span<const double> y, double xc) {
  const std::size_t n = x.size();
  double sh = 0, shh = 0, sy = 0, shy = 0;
  for (std::size_t i = 0; i < n; ++i) {
    const double h = std::max(x[i] - xc, 0.0);
    sh += h;
    shh += h * h;
    sy += y[i];
    shy += h * y[i];
  }
  const double nn = static_cast<double>(n);
  const double det = nn * shh - sh * sh;
  HingeFit f;
  f.x_c = xc;
  if (!(det > 1e-300)) return f;
  f.slope = (nn * shy - sh * sy) / det;
  f.plateau = (sy - f.slope * sh) / nn;
  double sse = 0;
  for (std::size_t i = 0; i < n; ++i) {
    const double r = y[i] - f.plateau - f.slope * std::max(x[i] - xc, 0.0);
    sse += r * r;
  }
  f.sse = sse;
  f.ok = true;
  return f;
}

}  // namespace

HingeFit fit_hinge(std::span<const double> x, std::span<const double> y) {
  std::vector<double> xs(x.begin(), x.end());
  std::sort(xs.begin(), xs.end());
  xs.erase(std::unique(xs.begin(), xs.end()), xs.end());
  HingeFit best;
  if (xs.size() < 3 || x.size() != y.size()) return best;
  // x_c from the lowest x to the second-highest: at least two distinct x on the rise.
  const double lo = xs.front(), hi = xs[xs.size() - 2];
  const int ngrid = 400;
  double best_sse = std::numeric_limits<double>::infinity();
  int kbest = 0;
  for (int k = 0; k <= ngrid; ++k) {
    const double xc = lo + (hi - lo) * k / ngrid;
    auto f = hinge_at(x, y, xc);
    if (f.ok && f.sse < best_sse) {
      best_sse = f.sse;
      best = f;
      kbest = k;
    }
  }
  if (!best.ok) return best;
  // Golden section in the bracket around the best grid point (SSE is continuous in x_c).
  double a = lo + (hi - lo) * std::max(kbest - 1, 0) / ngrid, b = lo + (hi - lo) * std::min(kbest + 1, ngrid) / ngrid;
  const double g = 0.5 * (std::sqrt(5.0) - 1.0);
  double c = b - g * (b - a), d = a + g * (b - a);
  auto sse = [&](double xc) {
    auto f = hinge_at(x, y, xc);
    return f.ok ? f.sse : std::numeric_limits<double>::infinity();
  };
  double fc = sse(c), fd = sse(d);
  for (int it = 0; it < 60; ++it) {
    if (fc < fd) {
      b = d; d = c; fd = fc; c = b - g * (b - a); fc = sse(c);
    } else {
      a = c; c = d; fc = fd; d = a + g * (b - a); fd = sse(d);
    }
  }
  auto f = hinge_at(x, y, 0.5 * (a + b));
  if (f.ok && f.sse <= best.sse) best = f;
  return best;
}

HingeBootstrap bootstrap_hinge(std::span<const double> x, std::span<const double> y, std::size_t replicas, std::uint64_t seed,
                               double level) {
  HingeBootstrap out;
  out.fit = fit_hinge(x, y);
  if (!out.fit.ok || replicas == 0) return out;
  std::map<double, std::vector<double>> groups;  // x -> the y of its configurations
  for (std::size_t i = 0; i < x.size(); ++i) groups[x[i]].push_back(y[i]);
  std::vector<double> bx, by, xcs;
  bx.reserve(x.size());
  by.reserve(x.size());
  for (std::size_t r = 0; r < replicas; ++r) {
    CounterRng rng(seed, r);
    bx.clear();
    by.clear();
    for (const auto& [xv, ys] : groups)
      for (std::size_t k = 0; k < ys.size(); ++k) {
        bx.push_back(xv);
        by.push_back(ys[rng.below(ys.size())]);
      }
    auto f = fit_hinge(bx, by);
    if (f.ok) xcs.push_back(f.x_c);
  }
  out.replicas = xcs.size();
  if (xcs.empty()) return out;
  out.lo = quantile(xcs, 0.5 * (1.0 - level));
  out.hi = quantile(xcs, 1.0 - 0.5 * (1.0 - level));
  out.sd = summarize(xcs).stderr_mean * std::sqrt(static_cast<double>(xcs.size()));
  return out;
}

DecayFit fit_exponential_decay(std::span<const double> x, std::span<const double> f) {
  std::vector<double> xs, ls;
  for (std::size_t i = 0; i < x.size() && i < f.size(); ++i)
    if (f[i] > 0.0 && std::isfinite(f[i])) {
      xs.push_back(x[i]);
      ls.push_back(std::log(f[i]));
    }
  DecayFit d;
  d.n = xs.size();
  if (xs.size() < 3) return d;
  const auto line = analysis::fit_line(xs, ls);
  d.kappa = -line.slope;
  d.kappa_error = line.slope_error;
  d.ln_f0 = line.intercept;
  d.ok = true;
  return d;
}

}  // namespace granwave::sweep
