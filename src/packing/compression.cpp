// The compression of a random packing's gas to its target pressure (packing/random_packing.hpp):
// a stress-controlled periodic cell, Berendsen's barostat on the box, normal contacts of the case's
// law with a dashpot, leapfrog steps; stopped when the pressure is reached and the packing static.
// docs/random-packing.md has the rule and its sources. Serial on purpose: the same bits for any
// number of threads.
#include <algorithm>
#include <chrono>
#include <cmath>
#include <numbers>
#include <sstream>

#include "core/error.hpp"
#include "core/format.hpp"
#include "packing/contacts.hpp"
#include "packing/random_packing.hpp"

namespace granwave::packing {

namespace {

// Pairs closer than a_i + a_j + skin (nearest image), from a cell list over the box.
struct PairList {
  std::vector<std::uint32_t> i, j;
  std::vector<double> x0;  // centres when built
  double scale0 = 1.0;     // the box's scale when built
};

void build_pairs(PairList& pl, const std::vector<double>& x, const std::vector<double>& a, const std::array<double, 3>& L,
                 double a_max, double skin, double scale) {
  const std::size_t n = a.size();
  pl.i.clear();
  pl.j.clear();
  pl.x0 = x;
  pl.scale0 = scale;
  const auto near = [&](std::size_t p, std::size_t q) {
    double r2 = 0.0;
    for (int d = 0; d < 3; ++d) {
      double b = x[3 * q + d] - x[3 * p + d];
      b -= L[d] * std::nearbyint(b / L[d]);
      r2 += b * b;
    }
    const double reach = a[p] + a[q] + skin;
    return r2 < reach * reach;
  };
  std::array<int, 3> nc{};
  for (int d = 0; d < 3; ++d) nc[d] = static_cast<int>(std::floor(L[d] / (2.0 * a_max + skin)));
  if (std::min({nc[0], nc[1], nc[2]}) < 3) {  // a small box: every pair
    for (std::size_t p = 0; p < n; ++p)
      for (std::size_t q = p + 1; q < n; ++q)
        if (near(p, q)) pl.i.push_back(static_cast<std::uint32_t>(p)), pl.j.push_back(static_cast<std::uint32_t>(q));
    return;
  }
  const auto cell_of = [&](std::size_t p, int d) {
    return std::clamp(static_cast<int>(std::floor(x[3 * p + d] / L[d] * nc[d])), 0, nc[d] - 1);
  };
  const std::size_t ncell = static_cast<std::size_t>(nc[0]) * nc[1] * nc[2];
  std::vector<std::size_t> start(ncell + 1, 0), members(n), cell(n);
  for (std::size_t p = 0; p < n; ++p) {
    cell[p] = (static_cast<std::size_t>(cell_of(p, 2)) * nc[1] + cell_of(p, 1)) * nc[0] + cell_of(p, 0);
    ++start[cell[p] + 1];
  }
  for (std::size_t c = 0; c < ncell; ++c) start[c + 1] += start[c];
  std::vector<std::size_t> fill(start.begin(), start.end() - 1);
  for (std::size_t p = 0; p < n; ++p) members[fill[cell[p]]++] = p;
  for (std::size_t p = 0; p < n; ++p) {
    const int cx = cell_of(p, 0), cy = cell_of(p, 1), cz = cell_of(p, 2);
    for (int dz = -1; dz <= 1; ++dz)
      for (int dy = -1; dy <= 1; ++dy)
        for (int dx = -1; dx <= 1; ++dx) {
          const int kx = (cx + dx + nc[0]) % nc[0], ky = (cy + dy + nc[1]) % nc[1], kz = (cz + dz + nc[2]) % nc[2];
          const std::size_t c = (static_cast<std::size_t>(kz) * nc[1] + ky) * nc[0] + kx;
          for (std::size_t s = start[c]; s < start[c + 1]; ++s) {
            const std::size_t q = members[s];
            if (q > p && near(p, q)) pl.i.push_back(static_cast<std::uint32_t>(p)), pl.j.push_back(static_cast<std::uint32_t>(q));
          }
        }
  }
  // The order the pairs are summed in fixes the bits: sort them.
  std::vector<std::size_t> order(pl.i.size());
  for (std::size_t k = 0; k < order.size(); ++k) order[k] = k;
  std::sort(order.begin(), order.end(), [&](std::size_t u, std::size_t w) {
    return pl.i[u] != pl.i[w] ? pl.i[u] < pl.i[w] : pl.j[u] < pl.j[w];
  });
  PairList sorted;
  for (std::size_t k : order) sorted.i.push_back(pl.i[k]), sorted.j.push_back(pl.j[k]);
  pl.i.swap(sorted.i);
  pl.j.swap(sorted.j);
}

// The overlap at which the law's force between two spheres of radius a reaches f (bisection).
double overlap_at_force(const NormalLaw& law, double a, double f) {
  double lo = 0.0, hi = a;
  for (int it = 0; it < 200 && law(a, a, hi).f < f; ++it) hi *= 2.0;
  for (int it = 0; it < 100; ++it) {
    const double mid = 0.5 * (lo + hi);
    (law(a, a, mid).f < f ? lo : hi) = mid;
  }
  return hi;
}

}  // namespace

Preparation compress(Packing& gas, const RandomSpec& spec, const NormalLaw& law,
                     const std::function<void(const std::string&)>& progress) {
  const std::size_t n = gas.particles.size();
  std::vector<double> x(3 * n), v(3 * n, 0.0), a(n), m(n), fe(3 * n), ft(3 * n);
  std::array<double, 3> L{gas.box.length(0), gas.box.length(1), gas.box.length(2)};
  double a_min = 1e300, a_max = 0.0, m_min = 1e300, a_sum = 0.0, m_sum = 0.0;
  for (std::size_t q = 0; q < n; ++q) {
    const Particle& p = gas.particles[q];
    x[3 * q] = p.centre.x() - gas.box.lo[0];
    x[3 * q + 1] = p.centre.y() - gas.box.lo[1];
    x[3 * q + 2] = p.centre.z() - gas.box.lo[2];
    a[q] = p.radius;
    m[q] = p.mass;
    a_min = std::min(a_min, a[q]), a_max = std::max(a_max, a[q]), m_min = std::min(m_min, m[q]);
    a_sum += a[q], m_sum += m[q];
  }
  const double d_mean = 2.0 * a_sum / n, m_mean = m_sum / n, p_t = spec.pressure;
  // The inertial time at the target pressure, sqrt(m/(d p)): the inertia number I = |strain rate| of it.
  const double t_inertial = std::sqrt(m_mean / (d_mean * p_t));
  const double rate_max = spec.inertia_number / t_inertial;
  // The time step: 1/25 of the contact time of the lightest pair at the stiffness of the largest
  // spheres pressed by 4 mean contact forces at the target (f = pi d^2 p / (z Phi), z 6, Phi 0.64).
  const double f_mean = std::numbers::pi * d_mean * d_mean * p_t / (6.0 * 0.64);
  const double k_max = law(a_max, a_max, overlap_at_force(law, a_max, 4.0 * f_mean)).k;
  const double dt = std::numbers::pi * std::sqrt(0.5 * m_min / k_max) / 25.0;
  const double tau = std::max(spec.servo_time * t_inertial, 10.0 * dt);  // a step cannot overshoot
  const double skin = 0.2 * d_mean;
  const double zeta = spec.damping;
  // A background drag on every particle's velocity (relative to the box's affine motion), decay
  // time t_inertial / background_damping: a rattler's cage is wide and its collisions rare, and
  // the contacts' dashpots alone would leave it rattling long after the rest is static.
  const double drag = 1.0 / (1.0 + spec.background_damping * dt / t_inertial);

  PairList pl;
  double scale = 1.0;  // the box's linear scale since the start
  build_pairs(pl, x, a, L, a_max, skin, scale);
  double rate = -rate_max;
  Preparation res;
  res.time_step = dt;
  auto clock_last = std::chrono::steady_clock::now();
  const auto state = [&](long s, double p, double ratio, double unb) {
    std::ostringstream o;
    o << "step " << s << ": p/p_target " << p / p_t << ", E_kin/E_pot " << ratio;
    if (std::isfinite(unb)) o << ", unbalanced " << unb;  // measured once the other two hold
    o << ", solid fraction " << [&] {
           double vs = 0.0;
           for (double r : a) vs += 4.0 / 3.0 * std::numbers::pi * r * r * r;
           return vs / (L[0] * L[1] * L[2]);
         }();
    return o.str();
  };
  double p = 0.0, ratio = INFINITY, unb = INFINITY;
  for (long s = 0; s <= spec.max_steps; ++s) {
    // Forces: the law's elastic normal force, and with it the dashpot (the relative normal velocity
    // includes the box's affine one, rate |b|); no tension.
    std::fill(fe.begin(), fe.end(), 0.0);
    std::fill(ft.begin(), ft.end(), 0.0);
    double virial = 0.0, stiff = 0.0, e_pot = 0.0, f_sum = 0.0, worst = 0.0;
    const double inv[3] = {1.0 / L[0], 1.0 / L[1], 1.0 / L[2]};
    std::size_t contacts = 0;
    for (std::size_t c = 0; c < pl.i.size(); ++c) {
      const std::size_t i = pl.i[c], j = pl.j[c];
      double b[3], r2 = 0.0;
      for (int d = 0; d < 3; ++d) {
        b[d] = x[3 * j + d] - x[3 * i + d];
        b[d] -= L[d] * std::nearbyint(b[d] * inv[d]);
        r2 += b[d] * b[d];
      }
      const double reach = a[i] + a[j];
      if (r2 >= reach * reach) continue;
      const double r = std::sqrt(r2), delta = reach - r;
      worst = std::max(worst, delta / std::min(a[i], a[j]));
      const NormalContact nc = law(a[i], a[j], delta);
      double vn = rate * r;
      for (int d = 0; d < 3; ++d) vn += (v[3 * j + d] - v[3 * i + d]) * b[d] / r;
      const double ms = m[i] * m[j] / (m[i] + m[j]);
      const double f_tot = std::max(0.0, nc.f - 2.0 * zeta * std::sqrt(ms * nc.k) * vn);
      for (int d = 0; d < 3; ++d) {
        const double u = b[d] / r;
        fe[3 * i + d] -= nc.f * u, fe[3 * j + d] += nc.f * u;
        ft[3 * i + d] -= f_tot * u, ft[3 * j + d] += f_tot * u;
      }
      virial += nc.f * r;
      stiff += nc.k * r2;
      e_pot += nc.f * nc.f * delta / (nc.k * delta + nc.f);  // f delta / (n + 1) for f ~ delta^n
      f_sum += nc.f;
      ++contacts;
    }
    const double volume = L[0] * L[1] * L[2];
    p = virial / (3.0 * volume);
    if (!std::isfinite(p) || worst > 0.5)
      throw InputError("random.inertia_number = " + fmt("%g", spec.inertia_number) + ": the compression overshot (an overlap of " +
                       fmt("%g", worst) + " of the smaller radius at step " + std::to_string(s) +
                       "); allowed: a smaller inertia number or a larger servo_time");
    double e_kin = 0.0;
    for (std::size_t q = 0; q < n; ++q)
      e_kin += 0.5 * m[q] * (v[3 * q] * v[3 * q] + v[3 * q + 1] * v[3 * q + 1] + v[3 * q + 2] * v[3 * q + 2]);
    ratio = e_pot > 0.0 ? e_kin / e_pot : INFINITY;
    if (contacts && std::abs(p - p_t) <= spec.pressure_tolerance * p_t && ratio <= spec.kinetic_ratio) {
      double net = 0.0;
      for (std::size_t q = 0; q < n; ++q) net = std::max(net, std::hypot(fe[3 * q], fe[3 * q + 1], fe[3 * q + 2]));
      unb = net / (f_sum / contacts);
      if (unb <= spec.unbalanced_force) {
        res.steps = s;
        break;
      }
    }
    if (s == spec.max_steps)
      throw InputError("random.max_steps = " + std::to_string(spec.max_steps) + ": the compression did not reach its target (" +
                       state(s, p, ratio, unb) + "; wanted |p/p_target - 1| <= " + fmt("%g", spec.pressure_tolerance) +
                       ", E_kin/E_pot <= " + fmt("%g", spec.kinetic_ratio) + ", unbalanced <= " +
                       fmt("%g", spec.unbalanced_force) + "); allowed: a larger max_steps or looser tolerances");
    // The servo: proportional to the pressure's relative error, rate = rate_max (p - p_target) /
    // p_target, the bound rate_max being the inertia number's; never faster than Berendsen's barostat
    // with relaxation time tau, rate = (p - p_target) / (S tau), S = (1/3V) sum k |b|^2 the affine
    // stiffness (dp/dt = -S rate), so that p cannot overshoot within a step.
    const double S = stiff / (3.0 * volume);
    const double error = std::clamp((p - p_t) / p_t, -1.0, 1.0);
    rate = rate_max * error;
    if (S > 0.0 && std::abs(rate) > std::abs(p - p_t) / (S * tau)) rate = (p - p_t) / (S * tau);
    // Leapfrog, then the box and every centre scaled affinely by (1 + rate dt).
    const double grow = 1.0 + rate * dt;
    for (std::size_t q = 0; q < n; ++q)
      for (int d = 0; d < 3; ++d) {
        v[3 * q + d] = (v[3 * q + d] + dt * ft[3 * q + d] / m[q]) * drag;
        double& xq = x[3 * q + d];
        xq = (xq + dt * v[3 * q + d]) * grow;
      }
    for (int d = 0; d < 3; ++d) L[d] *= grow;
    scale *= grow;
    for (std::size_t q = 0; q < n; ++q)
      for (int d = 0; d < 3; ++d) x[3 * q + d] -= L[d] * std::floor(x[3 * q + d] / L[d]);
    // A new list when a pair outside it may touch: the largest non-affine displacement u and the
    // box's shrinking since the build (a pair's distance falls by at most 2u + (1 - s) 2 a_max).
    const double ratio_s = scale / pl.scale0;
    double u2 = 0.0;
    for (std::size_t q = 0; q < n; ++q) {
      double w2 = 0.0;
      for (int d = 0; d < 3; ++d) {
        double u = x[3 * q + d] - pl.x0[3 * q + d] * ratio_s;
        u -= L[d] * std::nearbyint(u / L[d]);
        w2 += u * u;
      }
      u2 = std::max(u2, w2);
    }
    if (2.0 * std::sqrt(u2) + 2.0 * a_max * std::max(0.0, 1.0 - ratio_s) >= skin * std::min(1.0, ratio_s))
      build_pairs(pl, x, a, L, a_max, skin, scale);
    if (progress && s % 2000 == 0) {
      const auto now = std::chrono::steady_clock::now();
      if (now - clock_last > std::chrono::seconds(2)) {
        clock_last = now;
        progress(state(s, p, ratio, unb));
      }
    }
  }
  for (std::size_t q = 0; q < n; ++q) gas.particles[q].centre = Vec3(x[3 * q], x[3 * q + 1], x[3 * q + 2]);
  gas.box.lo = {0.0, 0.0, 0.0};
  gas.box.hi = L;
  const PackingStats st = measure(gas);
  res.pressure = p;
  res.kinetic_ratio = ratio;
  res.unbalanced_force = unb;
  res.solid_fraction = st.solid_fraction;
  res.coordination = st.mean_coordination;
  res.coordination_backbone = st.mean_coordination_nonrattler;
  res.rattlers = static_cast<long>(st.rattlers);
  return res;
}

}  // namespace granwave::packing
