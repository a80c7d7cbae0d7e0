// The compression of a random packing's gas to its target pressure (packing/random_packing.hpp):
// a stress-controlled periodic cell, Berendsen's barostat on the box, normal contacts of the case's
// law with a dashpot, leapfrog steps; near the target, FIRE on the enthalpy over the centres and the
// box's strain; stopped when the pressure is reached and the packing static.
// docs/random-packing.md has the rule and its sources. The law's closed form inline (a template per
// form); the pairs evaluated in parallel, each particle's forces gathered in the pairs' order and the
// sums over pairs taken serially in that order: the same bits for any number of threads.
#include <algorithm>
#include <chrono>
#include <cmath>
#include <numbers>
#include <sstream>
#include <type_traits>

#ifdef _OPENMP
#include <omp.h>
#else
inline int omp_get_max_threads() { return 1; }
#endif

#include "core/error.hpp"
#include "core/fire.hpp"
#include "core/format.hpp"
#include "packing/contacts.hpp"
#include "packing/friction_pairs.hpp"
#include "packing/random_packing.hpp"
#include "packing/verlet_pairs.hpp"

namespace granwave::packing {

namespace {

// One touching pair's normal contact from its branch b = r_j - r_i (nearest image), v_j - v_i, r2 = |b|^2,
// the radii and masses: the law's elastic force, the total with the dashpot on the relative normal
// velocity (the box's affine part, rate |b|, included; no tension), the unit vector and the pair's terms
// of the sums. The one formula of both the chunked (vectorised) and the pair-by-pair evaluation.
struct NormalPair {
  contact::NormalForce elastic;
  double f_total, r, u[3];
  double virial, stiffness, energy, overlap;  // f |b|, k |b|^2, f delta / (n + 1) for f ~ delta^n, delta / min(a)
};

template <class Law>
inline NormalPair normal_pair(const Law& law, const double (&b)[3], const double (&dv)[3], double r2, double a_i, double a_j,
                              double m_i, double m_j, double rate, double zeta) {
  NormalPair p;
  p.r = std::sqrt(r2);
  const double delta = (a_i + a_j) - p.r;
  const contact::NormalForce nc = law(a_i, a_j, delta);
  double vn = rate * p.r;
  for (int d = 0; d < 3; ++d) vn += dv[d] * b[d] / p.r;
  const double ms = m_i * m_j / (m_i + m_j);
  p.elastic = nc;
  p.f_total = std::max(0.0, nc.f - 2.0 * zeta * std::sqrt(ms * nc.k) * vn);
  for (int d = 0; d < 3; ++d) p.u[d] = b[d] / p.r;
  p.virial = nc.f * p.r;
  p.stiffness = nc.k * r2;
  p.energy = nc.f * nc.f * delta / (nc.k * delta + nc.f);
  p.overlap = delta / std::min(a_i, a_j);
  return p;
}

// The overlap at which the law's force between two spheres of radius a reaches f (bisection).
template <class Law>
double overlap_at_force(const Law& law, double a, double f) {
  double lo = 0.0, hi = a;
  for (int it = 0; it < 200 && law(a, a, hi).f < f; ++it) hi *= 2.0;
  for (int it = 0; it < 100; ++it) {
    const double mid = 0.5 * (lo + hi);
    (law(a, a, mid).f < f ? lo : hi) = mid;
  }
  return hi;
}

// Fric: with Coulomb friction at spec.friction (the tangential springs of packing/friction_pairs.hpp,
// the rotations integrated, no FIRE finish); without, not one operation of the frictionless path changes.
template <bool Fric, class Law>
Preparation compress_with(Packing& gas, const RandomSpec& spec, const Law& law,
                          const std::function<void(const std::string&)>& progress) {
  const std::size_t n = gas.particles.size();
  std::vector<double> x(3 * n), v(3 * n, 0.0), a(n), m(n), fe(3 * n), ft(3 * n);
  // With friction: angular velocities, elastic and total torques, moments of inertia (2/5 m a^2).
  std::vector<double> w_rot(Fric ? 3 * n : 0, 0.0), te(Fric ? 3 * n : 0), tt(Fric ? 3 * n : 0), inertia(Fric ? n : 0);
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
    if constexpr (Fric) inertia[q] = 0.4 * m[q] * a[q] * a[q];
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
  double zeta = spec.damping;  // 0 once FIRE minimises the enthalpy
  // A background drag on every particle's velocity (relative to the box's affine motion), decay
  // time t_inertial / background_damping: a rattler's cage is wide and its collisions rare, and
  // the contacts' dashpots alone would leave it rattling long after the rest is static.
  const double drag = 1.0 / (1.0 + spec.background_damping * dt / t_inertial);

  // Threads only for a large packing: a step of a small one is shorter than a team's barriers.
  const bool threaded = n >= spec.parallel_min_particles && omp_get_max_threads() > 1;
  VerletPairs pl;
  std::vector<double> pf, pft, pu, pterm;  // per pair: elastic and total normal force (-1: apart), unit vector, terms
  double scale = 1.0;  // the box's linear scale since the start
  pl.build(x, a, L, a_max, skin, scale);
  FrictionPairs fp;
  if constexpr (Fric) fp.resize(pl.i.size());
  double rate = -rate_max;
  // The finish (docs/random-packing.md step 5): FIRE on H = E_pot + p_target V over the centres and the
  // box's isotropic strain, whose generalised force is -dH/dstrain = 3 V (p - p_target) and whose mass,
  // n m d^2 / 2, gives its affine stiffness sum k |b|^2 a particle's frequency (z k / m); w its rate.
  bool minimising = false;
  long handover = -1;
  // First at a preload: the pressure whose mean contact force presses two mean spheres by
  // preload_overlap of their diameter (never below the target), where the jammed packing is found fast;
  // then, from it, at the target (docs/random-packing.md step 5). Each stage's FIRE from its own
  // contact time (1/25 of the time step's rule at 4 mean contact forces of the stage).
  const double p_pre = std::max(p_t, law(0.5 * d_mean, 0.5 * d_mean, spec.preload_overlap * d_mean).f * 6.0 * 0.64 /
                                         (std::numbers::pi * d_mean * d_mean));
  const auto contact_time = [&](double pressure) {
    const double f4 = 4.0 * std::numbers::pi * d_mean * d_mean * pressure / (6.0 * 0.64);
    return std::numbers::pi * std::sqrt(0.5 * m_min / law(a_max, a_max, overlap_at_force(law, a_max, f4)).k);
  };
  double p_goal = spec.start_static ? p_t : p_pre;
  Fire fire(contact_time(p_goal));
  double w = 0.0;
  const double box_mass = 0.5 * static_cast<double>(n) * m_mean * d_mean * d_mean;
  Preparation res;
  res.time_step = dt;
  auto clock_last = std::chrono::steady_clock::now();
  const auto state = [&](long s, double p, double ratio, double unb) {
    std::ostringstream o;
    o << "step " << s << (minimising ? " (FIRE)" : "") << ": p/p_target " << p / p_t << ", E_kin/E_pot " << ratio;
    if (std::isfinite(unb)) o << ", unbalanced " << unb;  // measured once the other two hold
    if constexpr (Fric) {
      long sliding = 0;
      for (std::size_t c = 0; c < pl.i.size(); ++c) sliding += pf[c] >= 0.0 && fp.sliding[c];
      o << ", sliding contacts " << sliding;
    }
    o << ", solid fraction " << [&] {
           double vs = 0.0;
           for (double r : a) vs += 4.0 / 3.0 * std::numbers::pi * r * r * r;
           return vs / (L[0] * L[1] * L[2]);
         }();
    return o.str();
  };
  // One FIRE step over the centres and the box's strain: the mixing from P = F.v, |v|^2 and |F|^2 in
  // mass-weighted coordinates (summed serially, particle by particle), then a semi-implicit Euler step
  // of FIRE's time step, the box and every centre scaled by (1 + w dt) as in the compression.
  const auto fire_step = [&](double volume, double p_now) {
    const double f_box = 3.0 * volume * (p_now - p_goal);
    double power = f_box * w, v2 = box_mass * w * w, f2 = f_box * f_box / box_mass;
    for (std::size_t q = 0; q < n; ++q)
      for (int d = 0; d < 3; ++d) {
        const double f = fe[3 * q + d], u = v[3 * q + d];
        power += f * u, v2 += m[q] * u * u, f2 += f * f / m[q];
      }
    const Fire::Mix mix = fire.next(power, v2, f2);
    const double h = fire.dt;
    w = (mix.moving ? mix.keep * w + mix.scale * f_box / box_mass : 0.0) + h * f_box / box_mass;
    const double grow = 1.0 + h * w;
    for (int d = 0; d < 3; ++d) L[d] *= grow;
    scale *= grow;
#pragma omp parallel for schedule(static) if (threaded)
    for (std::size_t q = 0; q < n; ++q)
      for (int d = 0; d < 3; ++d) {
        const double a_q = fe[3 * q + d] / m[q];
        double& u = v[3 * q + d];
        u = (mix.moving ? mix.keep * u + mix.scale * a_q : 0.0) + h * a_q;
        double& xq = x[3 * q + d];
        xq = (xq + h * u) * grow;
        xq -= L[d] * std::floor(xq / L[d]);
      }
  };
  double p = 0.0, ratio = INFINITY, unb = INFINITY;
  for (long s = 0; s <= spec.max_steps; ++s) {
    // Forces: the law's elastic normal force, and with it the dashpot (the relative normal velocity
    // includes the box's affine one, rate |b|); no tension.
    const double inv[3] = {1.0 / L[0], 1.0 / L[1], 1.0 / L[2]};
    const std::size_t npairs = pl.i.size();
    if (!threaded) std::fill(fe.begin(), fe.end(), 0.0), std::fill(ft.begin(), ft.end(), 0.0);
    if constexpr (Fric)
      if (!threaded) std::fill(te.begin(), te.end(), 0.0), std::fill(tt.begin(), tt.end(), 0.0);
    if (pf.size() < npairs) pf.resize(npairs), pft.resize(npairs), pu.resize(3 * npairs), pterm.resize(4 * npairs);
    // Each touching pair's normal forces and terms (normal_pair) added as it comes on one thread (Serial:
    // the pairs come in order, the order of the gather and of the sums below, the same bits without
    // storing a pair's unit vector and terms and reading them back), stored for them with threads.
    double virial = 0.0, stiff = 0.0, e_pot = 0.0, f_sum = 0.0, worst = 0.0;
    std::size_t contacts = 0;
    const auto add_normal = [&]<bool Serial>(std::size_t c, const NormalPair& p, std::bool_constant<Serial>) {
      pf[c] = p.elastic.f;
      pft[c] = p.f_total;
      if constexpr (Serial) {
        const std::size_t i = pl.i[c], j = pl.j[c];
        for (int d = 0; d < 3; ++d) {
          fe[3 * i + d] -= p.elastic.f * p.u[d], fe[3 * j + d] += p.elastic.f * p.u[d];
          ft[3 * i + d] -= p.f_total * p.u[d], ft[3 * j + d] += p.f_total * p.u[d];
        }
      } else {
        for (int d = 0; d < 3; ++d) pu[3 * c + d] = p.u[d];
      }
    };
    const auto add_terms = [&]<bool Serial>(std::size_t c, const NormalPair& p, double energy, std::bool_constant<Serial>) {
      if constexpr (Serial) {
        virial += p.virial;
        stiff += p.stiffness;
        e_pot += energy;
        f_sum += p.elastic.f;
        worst = std::max(worst, p.overlap);
        ++contacts;
      } else {
        pterm[4 * c] = p.virial, pterm[4 * c + 1] = p.stiffness, pterm[4 * c + 2] = energy, pterm[4 * c + 3] = p.overlap;
      }
    };
    // Frictionless, a chunk of pairs at a time: the particle values each pair reads copied into columns
    // (the image shift, r_j - r_i and v_j - v_i), normal_pair over the columns in a loop without branches,
    // which the compiler vectorises (ten divisions and three roots a pair, a lane each: the same IEEE
    // operations in the same order, so the same bits), then the touching pairs in order.
    constexpr std::size_t kChunk = 128;
    const auto chunk_step = [&]<bool Serial>(std::size_t c0, std::bool_constant<Serial> serial) {
      const std::size_t nb = std::min(kChunk, npairs - c0);
      alignas(64) double cb[3][kChunk], cdv[3][kChunk], cai[kChunk], caj[kChunk], cmi[kChunk], cmj[kChunk];
      for (std::size_t k = 0; k < nb; ++k) {
        const std::size_t i = pl.i[c0 + k], j = pl.j[c0 + k];
        for (int d = 0; d < 3; ++d) {
          double b = x[3 * j + d] - x[3 * i + d];
          b -= L[d] * std::nearbyint(b * inv[d]);
          cb[d][k] = b;
          cdv[d][k] = v[3 * j + d] - v[3 * i + d];
        }
        cai[k] = a[i], caj[k] = a[j], cmi[k] = m[i], cmj[k] = m[j];
      }
      // The results as columns too (an array of NormalPair would stop the vectorisation: measured 2x slower).
      alignas(64) double cf[kChunk], cft[kChunk], cu[3][kChunk], cterm[4][kChunk], ctouch[kChunk];
      for (std::size_t k = 0; k < nb; ++k) {
        const double b[3] = {cb[0][k], cb[1][k], cb[2][k]}, dv[3] = {cdv[0][k], cdv[1][k], cdv[2][k]};
        double r2 = 0.0;
        for (int d = 0; d < 3; ++d) r2 += b[d] * b[d];
        const double reach = cai[k] + caj[k];
        ctouch[k] = r2 >= reach * reach ? 0.0 : 1.0;
        const NormalPair p = normal_pair(law, b, dv, r2, cai[k], caj[k], cmi[k], cmj[k], rate, zeta);
        cf[k] = p.elastic.f, cft[k] = p.f_total;
        for (int d = 0; d < 3; ++d) cu[d][k] = p.u[d];
        cterm[0][k] = p.virial, cterm[1][k] = p.stiffness, cterm[2][k] = p.energy, cterm[3][k] = p.overlap;
      }
      for (std::size_t k = 0; k < nb; ++k) {
        if (ctouch[k] == 0.0) {
          pf[c0 + k] = -1.0;  // not touching
          continue;
        }
        NormalPair p;
        p.elastic.f = cf[k], p.f_total = cft[k];
        for (int d = 0; d < 3; ++d) p.u[d] = cu[d][k];
        p.virial = cterm[0][k], p.stiffness = cterm[1][k], p.energy = cterm[2][k], p.overlap = cterm[3][k];
        add_normal(c0 + k, p, serial);
        add_terms(c0 + k, p, p.energy, serial);
      }
    };
    // With friction, pair by pair: the normal part as above, then the tangential spring.
    const auto friction_pair_step = [&]<bool Serial>(std::size_t c, std::bool_constant<Serial> serial) {
      const std::size_t i = pl.i[c], j = pl.j[c];
      double b[3], dv[3], r2 = 0.0;
      for (int d = 0; d < 3; ++d) {
        b[d] = x[3 * j + d] - x[3 * i + d];
        b[d] -= L[d] * std::nearbyint(b[d] * inv[d]);
        r2 += b[d] * b[d];
        dv[d] = v[3 * j + d] - v[3 * i + d];
      }
      const double reach = a[i] + a[j];
      if (r2 >= reach * reach) {
        pf[c] = -1.0;  // not touching
        fp.apart(c);
        return;
      }
      const NormalPair p = normal_pair(law, b, dv, r2, a[i], a[j], m[i], m[j], rate, zeta);
      add_normal(c, p, serial);
      // The tangential spring: v_ij of i's contact point against j's (the affine part is normal).
      const contact::Vec3 nv{p.u[0], p.u[1], p.u[2]};
      const contact::Vec3 vi{v[3 * i], v[3 * i + 1], v[3 * i + 2]}, vj{v[3 * j], v[3 * j + 1], v[3 * j + 2]};
      const contact::Vec3 wi{w_rot[3 * i], w_rot[3 * i + 1], w_rot[3 * i + 2]};
      const contact::Vec3 wj{w_rot[3 * j], w_rot[3 * j + 1], w_rot[3 * j + 2]};
      const contact::Vec3 v_ij = vi - vj - nv * (rate * p.r) + (wi * a[i] + wj * a[j]).cross(nv);
      const double kt = spec.tangential(p.elastic);
      // No tangential dashpot (Agnolin & Roux damp the normal motion only): a dashpot of the normal's
      // fraction of critical on z contacts of a sphere's rotation (I = 2/5 m a^2) nears the explicit
      // step's limit and kept 300 spheres ringing at E_kin/E_pot 2e-3; friction and the drag dissipate.
      const double energy = p.energy + fp.touch(c, nv, p.elastic.f, kt, 0.0, spec.friction, v_ij, dt);
      if constexpr (Serial) {
        const double* o = &fp.out[12 * c];
        for (int d = 0; d < 3; ++d) {
          fe[3 * i + d] += o[d], fe[3 * j + d] -= o[d];
          ft[3 * i + d] += o[3 + d], ft[3 * j + d] -= o[3 + d];
          te[3 * i + d] += a[i] * o[6 + d], te[3 * j + d] += a[j] * o[6 + d];
          tt[3 * i + d] += a[i] * o[9 + d], tt[3 * j + d] += a[j] * o[9 + d];
        }
      }
      add_terms(c, p, energy, serial);
    };
    if constexpr (!Fric) {
      const std::size_t chunks = (npairs + kChunk - 1) / kChunk;
      if (threaded) {
#pragma omp parallel for schedule(static)
        for (std::size_t h = 0; h < chunks; ++h) chunk_step(h * kChunk, std::false_type{});
      } else {
        for (std::size_t h = 0; h < chunks; ++h) chunk_step(h * kChunk, std::true_type{});
      }
    } else if (threaded) {
#pragma omp parallel for schedule(static)
      for (std::size_t c = 0; c < npairs; ++c) friction_pair_step(c, std::false_type{});
    } else {
      for (std::size_t c = 0; c < npairs; ++c) friction_pair_step(c, std::true_type{});
    }
    // Threads: each particle's forces gathered from its pairs, in the order of a serial sweep over the pairs.
#pragma omp parallel for schedule(static) if (threaded)
    for (std::size_t q = 0; q < (threaded ? n : 0); ++q) {
      double e[3] = {0.0, 0.0, 0.0}, t[3] = {0.0, 0.0, 0.0}, te_q[3] = {0.0, 0.0, 0.0}, tt_q[3] = {0.0, 0.0, 0.0};
      const std::uint32_t mid = pl.start[q] + pl.as_j[q];
      for (std::uint32_t k = pl.start[q]; k < pl.start[q + 1]; ++k) {
        const std::uint32_t c = pl.by[k];
        if (pf[c] < 0.0) continue;
        const double* u = &pu[3 * c];
        if (k < mid)
          for (int d = 0; d < 3; ++d) e[d] += pf[c] * u[d], t[d] += pft[c] * u[d];
        else
          for (int d = 0; d < 3; ++d) e[d] -= pf[c] * u[d], t[d] -= pft[c] * u[d];
        if constexpr (Fric) {  // the pair's tangential force and torques right after its normal force, as serially
          const double* o = &fp.out[12 * c];
          if (k < mid)  // q is j: the force on i reversed
            for (int d = 0; d < 3; ++d) e[d] -= o[d], t[d] -= o[3 + d];
          else
            for (int d = 0; d < 3; ++d) e[d] += o[d], t[d] += o[3 + d];
          for (int d = 0; d < 3; ++d) te_q[d] += a[q] * o[6 + d], tt_q[d] += a[q] * o[9 + d];
        }
      }
      for (int d = 0; d < 3; ++d) fe[3 * q + d] = e[d], ft[3 * q + d] = t[d];
      if constexpr (Fric)
        for (int d = 0; d < 3; ++d) te[3 * q + d] = te_q[d], tt[3 * q + d] = tt_q[d];
    }
    // With threads, the sums serially in the pairs' order.
    for (std::size_t c = 0; c < (threaded ? npairs : 0); ++c) {
      if (pf[c] < 0.0) continue;
      virial += pterm[4 * c];
      stiff += pterm[4 * c + 1];
      e_pot += pterm[4 * c + 2];
      f_sum += pf[c];
      worst = std::max(worst, pterm[4 * c + 3]);
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
    if constexpr (Fric)  // and the rotations'
      for (std::size_t q = 0; q < n; ++q)
        e_kin += 0.5 * inertia[q] *
                 (w_rot[3 * q] * w_rot[3 * q] + w_rot[3 * q + 1] * w_rot[3 * q + 1] + w_rot[3 * q + 2] * w_rot[3 * q + 2]);
    ratio = e_pot > 0.0 ? e_kin / e_pot : INFINITY;
    // The largest net elastic force on a particle over the mean contact force (measured only when asked:
    // it is the one criterion that reads every particle).
    const auto unbalanced = [&] {
      double net = 0.0;
      for (std::size_t q = 0; q < n; ++q) net = std::max(net, std::hypot(fe[3 * q], fe[3 * q + 1], fe[3 * q + 2]));
      return net / (f_sum / contacts);
    };
    // With friction also the largest net elastic torque over (mean contact force x mean radius).
    const auto unbalanced_torque = [&] {
      double net = 0.0;
      for (std::size_t q = 0; q < n; ++q) net = std::max(net, std::hypot(te[3 * q], te[3 * q + 1], te[3 * q + 2]));
      return net / (f_sum / contacts * (a_sum / n));
    };
    if (contacts && std::abs(p - p_t) <= spec.pressure_tolerance * p_t && ratio <= spec.kinetic_ratio) {
      unb = unbalanced();
      if constexpr (Fric) res.unbalanced_torque = unbalanced_torque();
      if (unb <= spec.unbalanced_force && (!Fric || res.unbalanced_torque <= spec.unbalanced_force)) {
        res.steps = s;
        break;
      }
    }
    // Near the target the finish takes over, from rest (docs/random-packing.md step 5); a frictional
    // packing is no enthalpy minimum: the damped servo to the end.
    if (!Fric && !minimising &&
        (spec.start_static || (spec.minimise_from > 0.0 && contacts && std::abs(p - p_t) <= spec.minimise_from * p_t))) {
      minimising = true;
      handover = s;
      zeta = 0.0;
      rate = 0.0;
      std::fill(v.begin(), v.end(), 0.0);
    }
    if (minimising && p_goal > p_t && std::abs(p - p_goal) <= spec.pressure_tolerance * p_goal) {
      // The preload reached when static by the same criterion: then the target, from rest.
      if (unbalanced() <= spec.unbalanced_force) {
        p_goal = p_t;
        fire = Fire(contact_time(p_t));
        w = 0.0;
        std::fill(v.begin(), v.end(), 0.0);
      }
    }
    if (s == spec.max_steps)
      throw InputError("random.max_steps = " + std::to_string(spec.max_steps) + ": the compression did not reach its target (" +
                       (minimising && p_goal > p_t ? "stopped at the preload p* = " + fmt("%g", p_goal) + " Pa, " : std::string()) +
                       state(s, p, ratio, unb) +
                       (Fric ? ", unbalanced torque " + fmt("%g", res.unbalanced_torque) : std::string()) +
                       "; wanted |p/p_target - 1| <= " + fmt("%g", spec.pressure_tolerance) +
                       ", E_kin/E_pot <= " + fmt("%g", spec.kinetic_ratio) + ", unbalanced <= " +
                       fmt("%g", spec.unbalanced_force) + (Fric ? " (force and torque)" : "") +
                       "); allowed: a larger max_steps or looser tolerances");
    if (minimising) {
      fire_step(volume, p);
    } else {
      // The servo: proportional to the pressure's relative error, rate = rate_max (p - p_target) /
      // p_target, the bound rate_max being the inertia number's; never faster than Berendsen's barostat
      // with relaxation time tau, rate = (p - p_target) / (S tau), S = (1/3V) sum k |b|^2 the affine
      // stiffness (dp/dt = -S rate), so that p cannot overshoot within a step.
      const double S = stiff / (3.0 * volume);
      const double error = std::clamp((p - p_t) / p_t, -1.0, 1.0);
      rate = rate_max * error;
      if (S > 0.0 && std::abs(rate) > std::abs(p - p_t) / (S * tau)) rate = (p - p_t) / (S * tau);
      const double grow = 1.0 + rate * dt;
      // Leapfrog, then the box and every centre scaled affinely by (1 + rate dt).
      for (int d = 0; d < 3; ++d) L[d] *= grow;
      scale *= grow;
#pragma omp parallel for schedule(static) if (threaded)
      for (std::size_t q = 0; q < n; ++q)
        for (int d = 0; d < 3; ++d) {
          v[3 * q + d] = (v[3 * q + d] + dt * ft[3 * q + d] / m[q]) * drag;
          double& xq = x[3 * q + d];
          xq = (xq + dt * v[3 * q + d]) * grow;
          xq -= L[d] * std::floor(xq / L[d]);
          if constexpr (Fric) w_rot[3 * q + d] = (w_rot[3 * q + d] + dt * tt[3 * q + d] / inertia[q]) * drag;
        }
    }
    if (pl.stale(x, L, a_max, skin, scale, threaded)) {
      if constexpr (Fric) {  // the springs carried to the new list by their pairs
        const std::vector<std::uint32_t> old_i = pl.i, old_j = pl.j;
        pl.build(x, a, L, a_max, skin, scale);
        fp.carry(old_i, old_j, pl);
      } else {
        pl.build(x, a, L, a_max, skin, scale);
      }
    }
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
  const PackingStats st = measure(gas, Fric ? 2 : 4);
  if constexpr (Fric)  // the springs of the touching pairs, the history the system file keeps
    for (std::size_t c = 0; c < pl.i.size(); ++c) {
      if (pf[c] < 0.0) continue;
      SpringHistory h;
      h.i = pl.i[c], h.j = pl.j[c];
      for (int d = 0; d < 3; ++d) h.xi[d] = fp.xi[3 * c + d];
      res.springs.push_back(h);
      res.sliding += fp.sliding[c];
    }
  res.pressure = p;
  res.minimise_steps = handover < 0 ? 0 : res.steps - handover;
  res.kinetic_ratio = ratio;
  res.unbalanced_force = unb;
  res.solid_fraction = st.solid_fraction;
  res.coordination = st.mean_coordination;
  res.coordination_backbone = st.mean_coordination_nonrattler;
  res.rattlers = static_cast<long>(st.rattlers);
  return res;
}

}  // namespace

Preparation compress(Packing& gas, const RandomSpec& spec, const contact::NormalForm& law,
                     const std::function<void(const std::string&)>& progress) {
  return contact::with_normal(law, [&](const auto& form) {
    return spec.friction > 0.0 ? compress_with<true>(gas, spec, form, progress) : compress_with<false>(gas, spec, form, progress);
  });
}

}  // namespace granwave::packing
