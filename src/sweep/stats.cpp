// Ensemble statistics of the studies (sweep/stats.hpp): group summaries, the M_c hinge fits, decay fits.
#include "sweep/stats.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <map>

#include "analysis/measures.hpp"
#include "core/rng.hpp"
#include "core/numbers.hpp"

namespace granwave::sweep {

namespace {
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

// The points grouped by x (the configurations of one M). The least-squares fit over every point
// depends on each group's count and mean only: SSE = pure error + sum_g n_g (mean_g - fit(x_g))^2.
struct Grouped {
  std::vector<double> x, n, mean;  // distinct x, ascending
  double pure_error = 0.0;         // sum over the points of (y - its group's mean)^2
  std::size_t points = 0;
};

// One group from its values (two passes: the pure error of near-identical values stays exact).
void add_group(Grouped& g, double x, std::span<const double> v) {
  double mean = 0.0;
  for (double y : v) mean += y;
  mean /= static_cast<double>(v.size());
  double ss = 0.0;
  for (double y : v) ss += (y - mean) * (y - mean);
  g.x.push_back(x);
  g.n.push_back(static_cast<double>(v.size()));
  g.mean.push_back(mean);
  g.pure_error += ss;
  g.points += v.size();
}

struct LineAt {
  bool ok = false;
  double a = 0.0, b = 0.0, misfit = 0.0;  // misfit = sum_g n_g (mean_g - a - b h_g)^2
};

// Weighted least squares of the group means on h = (x - xc)_+, closed form.
LineAt line_at(const Grouped& g, double xc) {
  double sw = 0, sh = 0, shh = 0, sy = 0, shy = 0;
  for (std::size_t k = 0; k < g.x.size(); ++k) {
    const double h = std::max(g.x[k] - xc, 0.0), w = g.n[k];
    sw += w;
    sh += w * h;
    shh += w * h * h;
    sy += w * g.mean[k];
    shy += w * h * g.mean[k];
  }
  LineAt f;
  const double det = sw * shh - sh * sh;
  if (!(det > 1e-14 * sw * shh)) return f;  // no point on the rise
  f.b = (sw * shy - sh * sy) / det;
  f.a = (sy - f.b * sh) / sw;
  for (std::size_t k = 0; k < g.x.size(); ++k) {
    const double r = g.mean[k] - f.a - f.b * std::max(g.x[k] - xc, 0.0);
    f.misfit += g.n[k] * r * r;
  }
  f.ok = true;
  return f;
}

HingeFit fit_grouped(const Grouped& g, Rise rise) {
  HingeFit best;
  best.rise = rise;
  if (g.x.size() < 3) return best;
  // x_c from the lowest x to the second-highest: at least two distinct x on the rise.
  const double lo = g.x.front(), hi = g.x[g.x.size() - 2];
  const int ngrid = 400;
  double best_misfit = std::numeric_limits<double>::infinity(), best_xc = lo;
  int kbest = -1;
  for (int k = 0; k <= ngrid; ++k) {
    const double xc = lo + (hi - lo) * k / ngrid;
    const auto f = line_at(g, xc);
    if (f.ok && f.misfit < best_misfit) {
      best_misfit = f.misfit;
      best_xc = xc;
      kbest = k;
    }
  }
  if (kbest < 0) return best;
  // Golden section in the bracket around the best grid point (SSE is continuous in x_c).
  double a = lo + (hi - lo) * std::max(kbest - 1, 0) / ngrid, b = lo + (hi - lo) * std::min(kbest + 1, ngrid) / ngrid;
  const double gr = 0.5 * (std::sqrt(5.0) - 1.0);
  auto misfit = [&](double xc) {
    const auto f = line_at(g, xc);
    return f.ok ? f.misfit : std::numeric_limits<double>::infinity();
  };
  double c = b - gr * (b - a), d = a + gr * (b - a);
  double fc = misfit(c), fd = misfit(d);
  for (int it = 0; it < 60; ++it) {
    if (fc < fd) {
      b = d; d = c; fd = fc; c = b - gr * (b - a); fc = misfit(c);
    } else {
      a = c; c = d; fc = fd; d = a + gr * (b - a); fd = misfit(d);
    }
  }
  if (misfit(0.5 * (a + b)) <= best_misfit) best_xc = 0.5 * (a + b);
  const auto f = line_at(g, best_xc);
  best.ok = true;
  best.x_c = best_xc;
  best.plateau = rise == Rise::exponential ? std::exp(f.a) : f.a;
  best.slope = f.b;
  best.sse = g.pure_error + f.misfit;
  const double G = static_cast<double>(g.x.size()), n = static_cast<double>(g.points);
  best.lack_of_fit = (G > 3.0 && n > G && g.pure_error > 0.0) ? (f.misfit / (G - 3.0)) / (g.pure_error / (n - G))
                                                               : std::numeric_limits<double>::quiet_NaN();
  return best;
}

// The points of each distinct x (ascending), as indices into the data.
std::vector<std::pair<double, std::vector<std::size_t>>> groups_of(std::span<const double> x) {
  std::map<double, std::vector<std::size_t>> m;
  for (std::size_t i = 0; i < x.size(); ++i) m[x[i]].push_back(i);
  return {m.begin(), m.end()};
}

// The law whose residuals are less structured; the straight one when that cannot be told.
const HingeFit& headline(const HingeFit& line, const HingeFit& exponential) {
  if (!exponential.ok) return line;
  if (!line.ok) return exponential;
  if (std::isfinite(line.lack_of_fit) && std::isfinite(exponential.lack_of_fit) &&
      exponential.lack_of_fit < line.lack_of_fit)
    return exponential;
  return line;
}

}  // namespace

const char* rise_name(Rise r) { return r == Rise::line ? "line" : "exponential"; }

double hinge_value(const HingeFit& f, double x) {
  const double h = std::max(x - f.x_c, 0.0);
  return f.rise == Rise::line ? f.plateau + f.slope * h : f.plateau * std::exp(f.slope * h);
}

HingeFit fit_hinge(std::span<const double> x, std::span<const double> y, Rise rise) {
  HingeFit bad;
  bad.rise = rise;
  if (x.size() != y.size()) return bad;
  Grouped g;
  std::vector<double> v;
  for (const auto& [xv, idx] : groups_of(x)) {
    v.clear();
    for (std::size_t i : idx) {
      if (rise == Rise::exponential && (!(y[i] > 0.0) || !std::isfinite(y[i]))) return bad;
      v.push_back(rise == Rise::exponential ? std::log(y[i]) : y[i]);
    }
    add_group(g, xv, v);
  }
  return fit_grouped(g, rise);
}

HingeBootstrap bootstrap_hinge(std::span<const double> x, std::span<const double> y, std::size_t replicas, std::uint64_t seed,
                               double level) {
  HingeBootstrap out;
  out.line = fit_hinge(x, y, Rise::line);
  out.exponential = fit_hinge(x, y, Rise::exponential);
  out.fit = headline(out.line, out.exponential);
  if (!out.fit.ok || replicas == 0) return out;
  const auto groups = groups_of(x);
  std::vector<double> xc_line, xc_exp, xc_head;
  const bool use_exp = out.exponential.ok;  // ln y exists for every point
  std::vector<double> vy, vl;
  for (std::size_t r = 0; r < replicas; ++r) {
    CounterRng rng(seed, r);
    Grouped gl, ge;
    for (const auto& [xv, idx] : groups) {
      vy.clear();
      vl.clear();
      for (std::size_t k = 0; k < idx.size(); ++k) {
        const std::size_t i = idx[rng.below(idx.size())];
        vy.push_back(y[i]);
        if (use_exp) vl.push_back(std::log(y[i]));
      }
      add_group(gl, xv, vy);
      if (use_exp) add_group(ge, xv, vl);
    }
    const auto fl = fit_grouped(gl, Rise::line);
    if (fl.ok) xc_line.push_back(fl.x_c);
    if (use_exp) {
      const auto fe = fit_grouped(ge, Rise::exponential);
      if (fe.ok) xc_exp.push_back(fe.x_c);
      if (out.fit.rise == Rise::exponential && fe.ok) xc_head.push_back(fe.x_c);
    }
    if (out.fit.rise == Rise::line && fl.ok) xc_head.push_back(fl.x_c);
  }
  out.replicas = xc_head.size();
  const double plo = 0.5 * (1.0 - level), phi = 1.0 - 0.5 * (1.0 - level);
  out.line_lo = quantile(xc_line, plo);
  out.line_hi = quantile(xc_line, phi);
  out.exp_lo = quantile(xc_exp, plo);
  out.exp_hi = quantile(xc_exp, phi);
  out.lo = out.line_lo;
  out.hi = out.line_hi;
  if (!xc_exp.empty()) {
    out.lo = xc_line.empty() ? out.exp_lo : std::min(out.lo, out.exp_lo);
    out.hi = xc_line.empty() ? out.exp_hi : std::max(out.hi, out.exp_hi);
  }
  if (!xc_head.empty()) out.sd = summarize(xc_head).stderr_mean * std::sqrt(static_cast<double>(xc_head.size()));
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
