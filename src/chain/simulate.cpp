// Time integration of eq. (13) and the observers.
#include <algorithm>
#include <cmath>
#include <limits>

#include "chain/chain.hpp"
#include "core/error.hpp"

namespace granwave::chain {

Stepper::Stepper(const ChainSystem& sys, config::Scheme scheme, double dt)
    : n_(sys.nbeads()), nc_(sys.ncontacts()), dt_(dt), scheme_(scheme) {
  if (!(dt > 0.0)) throw InputError("chain: dt must be > 0");
  u_.assign(n_ + 1, 0.0);  // u_[n] = 0: the wall does not move
  v_.assign(sys.velocity.begin(), sys.velocity.end());
  a_.assign(n_, 0.0);
  m_.assign(sys.mass.begin(), sys.mass.end());
  inv_m_.resize(n_);
  for (std::size_t i = 0; i < n_; ++i) inv_m_[i] = 1.0 / m_[i];
  // n contacts in the loop; a free end's last one has A = 0 (never pushes).
  A_.assign(n_, 0.0);
  g_.assign(n_, 0.0);
  for (std::size_t j = 0; j < nc_; ++j) {
    A_[j] = sys.hertz_constant[j];
    g_[j] = sys.initial_overlap[j];
  }
  // F_[0] is the force on the striker from the left: 0, or the static load F0 that holds a
  // precompressed chain against the wall (without it the striker would start in tension).
  F_.assign(n_ + 1, 0.0);
  F_[0] = sys.precompression;
  f_ext_ = sys.precompression;
  if (scheme_ == config::Scheme::rk4) {
    for (auto& k : ku_) k.assign(n_, 0.0);
    for (auto& k : kv_) k.assign(n_, 0.0);
    tmp_u_.assign(n_ + 1, 0.0);  // tmp_u_[n] = 0: the wall
  }
  accelerations(u_.data(), a_.data());
  // The resting region starts after the last bead that moves or is pushed; none exists when any
  // contact starts loaded (precompression), since a loaded bead's balance is only approximate.
  const bool unloaded = sys.precompression == 0.0 && std::all_of(g_.begin(), g_.end(), [](double g) { return g <= 0.0; });
  front_ = n_;
  if (unloaded) {
    front_ = 0;
    for (std::size_t i = 0; i < n_; ++i) {
      if (v_[i] != 0.0 || a_[i] != 0.0) front_ = i + 1;
    }
  }
}

// Eq. (13) with docs/design.md §2.2 indexing: m_i a_i = F_{i-1} - F_i, F_j = A_j max(delta_j, 0)^(3/2),
// delta_j = g_j + u_j - u_{j+1}. F_[0] stands for the striker's missing left neighbour (0, or the
// static load F0 of a precompressed chain).
inline void Stepper::accelerations(const double* __restrict u, double* __restrict a) {
  const std::size_t n = n_;
  const double* __restrict A = A_.data();
  const double* __restrict g = g_.data();
  const double* __restrict inv_m = inv_m_.data();
  double* __restrict F = F_.data();
  for (std::size_t j = 0; j < n; ++j) F[j + 1] = contact::hertz_force(A[j], g[j] + u[j] - u[j + 1]);
  for (std::size_t i = 0; i < n; ++i) a[i] = (F[i] - F[i + 1]) * inv_m[i];
}

void Stepper::step() {
  const std::size_t n = n_;
  const double dt = dt_;
  double* __restrict u = u_.data();
  double* __restrict v = v_.data();
  if (scheme_ == config::Scheme::verlet) {
    // Velocity Verlet: half kick, drift, force, half kick (positions, velocities and forces
    // are synchronous at the end of the step).
    double* __restrict a = a_.data();
    double* __restrict F = F_.data();
    const double* __restrict A = A_.data();
    const double* __restrict g = g_.data();
    const double* __restrict inv_m = inv_m_.data();
    const double h = 0.5 * dt;
    // Beads 0..moving-1 may move; the first resting bead can only be pushed by contact moving-1.
    const std::size_t moving = front_;
    const std::size_t pushed = std::min(moving + 1, n);
    for (std::size_t i = 0; i < moving; ++i) {
      v[i] += h * a[i];
      u[i] += dt * v[i];
    }
    for (std::size_t j = 0; j < moving; ++j)  // eq. (13), as in accelerations()
      F[j + 1] = contact::hertz_force(A[j], g[j] + u[j] - u[j + 1]);
    for (std::size_t i = 0; i < pushed; ++i) {
      a[i] = (F[i] - F[i + 1]) * inv_m[i];
      v[i] += h * a[i];
    }
    if (moving < n && (v[moving] != 0.0 || a[moving] != 0.0)) front_ = moving + 1;
  } else {
    // Classical RK4 on (u, v), as in seed 001's Appendix 1 and 4.
    double* __restrict tu = tmp_u_.data();
    const double h = 0.5 * dt;
    accelerations(u, kv_[0].data());
    std::copy(v, v + n, ku_[0].data());
    for (int s = 1; s < 4; ++s) {
      const double c = s == 3 ? dt : h;
      const double* __restrict kup = ku_[s - 1].data();
      const double* __restrict kvp = kv_[s - 1].data();
      double* __restrict kus = ku_[s].data();
      for (std::size_t i = 0; i < n; ++i) {
        tu[i] = u[i] + c * kup[i];
        kus[i] = v[i] + c * kvp[i];
      }
      accelerations(tu, kv_[s].data());
    }
    const double w = dt / 6.0;
    for (std::size_t i = 0; i < n; ++i) {
      u[i] += w * (ku_[0][i] + 2.0 * ku_[1][i] + 2.0 * ku_[2][i] + ku_[3][i]);
      v[i] += w * (kv_[0][i] + 2.0 * kv_[1][i] + 2.0 * kv_[2][i] + kv_[3][i]);
    }
  }
  ++steps_;
}

void Stepper::contact_forces(double* out) const {
  for (std::size_t j = 0; j < nc_; ++j) out[j] = contact_force(j);
}

void Stepper::bead_forces(double* out) const {
  for (std::size_t b = 0; b < n_; ++b) out[b] = bead_force(b);
}

double Stepper::kinetic_energy() const {
  double e = 0.0;
  for (std::size_t i = 0; i < n_; ++i) e += 0.5 * m_[i] * v_[i] * v_[i];
  return e;
}

double Stepper::potential_energy() const {
  double e = 0.0;
  for (std::size_t j = 0; j < nc_; ++j) e += contact::hertz_energy(A_[j], overlap(j));
  return e;
}

double Stepper::momentum() const {
  double p = 0.0;
  for (std::size_t i = 0; i < n_; ++i) p += m_[i] * v_[i];
  return p;
}

// ---- options ----

double resolve_dt(const config::Case& c, const ChainSystem& sys) {
  if (c.integrator.dt) return *c.integrator.dt;
  if (c.integrator.dt_over_tc) return *c.integrator.dt_over_tc * shortest_contact_time(sys);
  throw InputError(c.path + ": [integrator]: give dt or dt_over_tc");
}

SimOptions sim_options(const config::Case& c, const ChainSystem& sys) {
  SimOptions o;
  o.scheme = c.integrator.scheme;
  o.dt = resolve_dt(c, sys);
  o.t_end = c.integrator.t_end;
  o.stride = c.output.interval > 0.0 ? static_cast<std::size_t>(std::max(1.0, std::round(c.output.interval / o.dt))) : 1;
  if (!c.output.fields.empty()) {
    o.store_contact_force = o.store_bead_force = o.store_energy = false;
    for (const auto& f : c.output.fields) {
      if (f == "contact_force") o.store_contact_force = true;
      else if (f == "bead_force") o.store_bead_force = true;
      else if (f == "energy" || f == "kinetic" || f == "potential") o.store_energy = true;
      else
        throw InputError(c.path + ": [output].fields: '" + f +
                         "' is not a chain field (allowed: contact_force, bead_force, energy)");
    }
  }
  for (int b : c.output.full_rate_beads)
    if (b < 0 || static_cast<std::size_t>(b) >= sys.nbeads())
      throw InputError(c.path + ": [output].full_rate_beads: bead " + std::to_string(b) + " is outside the chain (0.." +
                       std::to_string(sys.nbeads() - 1) + ")");
  o.full_rate_beads = c.output.full_rate_beads;
  o.stop = c.stop;
  if (o.stop.enabled && (o.stop.after_bead < 0 || static_cast<std::size_t>(o.stop.after_bead) >= sys.nbeads()))
    throw InputError(c.path + ": [stop].after_bead: bead " + std::to_string(o.stop.after_bead) +
                     " is outside the chain (0.." + std::to_string(sys.nbeads() - 1) + ")");
  return o;
}

// ---- the run ----

namespace {
// Largest sample of one signal on the output grid and the samples either side of it, kept as
// the run goes (first occurrence of the maximum; no stored series). At the end, the vertex of
// the parabola through the three, when they are equally spaced and the middle one is a maximum.
struct RunningPeak {
  double best = -1.0;  // bead forces are >= 0: the first sample always replaces it
  double before = 0.0, after = 0.0, t_before = 0.0, t_best = 0.0, t_after = 0.0;
  bool has_before = false, has_after = false;

  void add(double f, double t, double f_prev, double t_prev, bool has_prev) {
    if (f > best) {
      best = f;
      t_best = t;
      before = f_prev;
      t_before = t_prev;
      has_before = has_prev;
      has_after = false;
    } else if (!has_after) {  // the sample right after the current maximum
      after = f;
      t_after = t;
      has_after = true;
    }
  }
  double refined() const {
    if (!has_before || !has_after) return best;
    const double h0 = t_best - t_before, h1 = t_after - t_best;
    if (!(std::abs(h0 - h1) < 1e-6 * h0)) return best;
    const double den = before - 2.0 * best + after;
    return den < 0.0 ? best - (before - after) * (before - after) / (8.0 * den) : best;
  }
};
}  // namespace

ChainTrace simulate(const ChainSystem& sys, const SimOptions& opt) {
  Stepper st(sys, opt.scheme, opt.dt);
  ChainTrace tr;
  tr.nbeads = sys.nbeads();
  tr.ncontacts = sys.ncontacts();
  tr.dt = opt.dt;
  tr.stride = std::max<std::size_t>(1, opt.stride);
  tr.full_rate_beads = opt.full_rate_beads;
  const std::size_t nc = tr.ncontacts, nb = tr.nbeads;
  const std::size_t nprofile = std::min(opt.peak_profile_beads, nb);
  const std::size_t nsensors = opt.full_rate_beads.size();

  const double t_stop = opt.stop.enabled ? opt.stop.max_time.value_or(opt.t_end) : opt.t_end;
  const auto nsteps = static_cast<std::size_t>(std::llround(t_stop / opt.dt));
  const std::size_t nt_guess = nsteps / tr.stride + 2;
  tr.time.reserve(nt_guess);
  if (opt.store_contact_force) tr.contact_force.reserve(nt_guess * nc);
  if (opt.store_bead_force) tr.bead_force.reserve(nt_guess * nb);
  if (nsensors > 0 && opt.store_full_rate) {
    tr.full_rate_time.reserve(nsteps + 1);
    tr.full_rate_bead_force.reserve((nsteps + 1) * nsensors);
  }
  tr.full_rate_peak.assign(nsensors, -std::numeric_limits<double>::infinity());
  tr.full_rate_peak_time.assign(nsensors, 0.0);

  std::vector<double> buf(std::max(nb, nc));
  std::vector<RunningPeak> profile(nprofile);
  std::vector<double> profile_prev(nprofile, 0.0);
  double t_prev = 0.0;
  bool has_prev = false;
  std::size_t nsamples = 0, profile_live = 0;  // beads >= profile_live have had force 0 at every sample
  // A bead beyond the front's neighbour has no force; it joins with the state that its
  // all-zero samples so far would have left (its largest is 0 and has no sample before it).
  auto bring_live = [&](std::size_t live) {
    for (; profile_live < live; ++profile_live) {
      RunningPeak& p = profile[profile_live];
      if (nsamples >= 1) p.best = 0.0;
      p.has_after = nsamples >= 2;
    }
  };
  auto sample = [&] {
    const double t = st.time();
    tr.time.push_back(t);
    if (opt.store_energy) tr.work_in.push_back(st.work_in());
    if (opt.store_contact_force) {
      st.contact_forces(buf.data());
      tr.contact_force.insert(tr.contact_force.end(), buf.begin(), buf.begin() + nc);
    }
    if (opt.store_bead_force) {
      st.bead_forces(buf.data());
      tr.bead_force.insert(tr.bead_force.end(), buf.begin(), buf.begin() + nb);
    }
    const std::size_t live = std::min(nprofile, st.resting_from() + 1);
    bring_live(live);
    for (std::size_t b = 0; b < live; ++b) {
      const double f = st.bead_force(b);
      profile[b].add(f, t, profile_prev[b], t_prev, has_prev);
      profile_prev[b] = f;
    }
    t_prev = t;
    has_prev = true;
    ++nsamples;
    if (opt.store_energy) {
      tr.kinetic.push_back(st.kinetic_energy());
      tr.potential.push_back(st.potential_energy());
      if (!std::isfinite(tr.kinetic.back()) || !std::isfinite(tr.potential.back()))
        throw RunError("chain: the state is no longer finite at t = " + std::to_string(st.time()) +
                       " s (dt too large?)");
    }
  };
  auto sample_full = [&] {
    if (nsensors == 0) return;
    const double t = st.time();
    if (opt.store_full_rate) tr.full_rate_time.push_back(t);
    for (std::size_t k = 0; k < nsensors; ++k) {
      const double f = st.bead_force(static_cast<std::size_t>(opt.full_rate_beads[k]));
      if (opt.store_full_rate) tr.full_rate_bead_force.push_back(f);
      if (f > tr.full_rate_peak[k]) {
        tr.full_rate_peak[k] = f;
        tr.full_rate_peak_time[k] = t;
      }
    }
  };
  // Stop rule: the front is the furthest contact whose dynamic force has exceeded
  // front_threshold x the striker contact's peak (running) dynamic force.
  const double F_static = sys.precompression;
  std::size_t front = 0, target = nc;
  double peak0 = 0.0;
  if (opt.stop.enabled && nc > 0)
    target = std::min<std::size_t>(static_cast<std::size_t>(opt.stop.after_bead + opt.stop.margin_beads), nc - 1);

  sample();
  sample_full();
  for (std::size_t k = 1; k <= nsteps; ++k) {
    st.step();
    sample_full();
    const bool on_grid = k % tr.stride == 0;
    if (on_grid) {
      sample();
      if (opt.progress) opt.progress(static_cast<long>(k), static_cast<long>(nsteps));
    }
    if (opt.stop.enabled) {
      peak0 = std::max(peak0, st.contact_force(0) - F_static);
      const double thr = opt.stop.front_threshold * peak0;
      while (front + 1 < nc && st.contact_force(front + 1) - F_static > thr && thr > 0.0) ++front;
      if (front >= target) {
        if (!on_grid) sample();
        tr.stopped_early = true;
        break;
      }
    }
  }
  tr.steps = st.steps();
  bring_live(nprofile);
  tr.bead_peak.resize(nprofile);
  for (std::size_t b = 0; b < nprofile; ++b) tr.bead_peak[b] = profile[b].refined();
  return tr;
}

// ---- trace helpers ----

namespace {
std::vector<double> column(const std::vector<double>& data, std::size_t ncols, std::size_t j) {
  std::vector<double> out;
  if (ncols == 0) return out;
  const std::size_t nt = data.size() / ncols;
  out.reserve(nt);
  for (std::size_t k = 0; k < nt; ++k) out.push_back(data[k * ncols + j]);
  return out;
}
}  // namespace

std::vector<double> ChainTrace::contact_series(std::size_t j) const { return column(contact_force, ncontacts, j); }
std::vector<double> ChainTrace::bead_series(std::size_t b) const { return column(bead_force, nbeads, b); }
std::vector<double> ChainTrace::full_rate_series(std::size_t k) const {
  return column(full_rate_bead_force, full_rate_beads.size(), k);
}

double ChainTrace::energy_error() const {
  if (kinetic.empty()) return 0.0;
  // The static load's work counts: K + P - W is conserved. Relative to the energy put in by the
  // striker (K0), not to the static elastic energy of a precompressed chain.
  const double e0 = kinetic[0] + potential[0] - work_in[0];
  double err = 0.0;
  for (std::size_t k = 0; k < kinetic.size(); ++k)
    err = std::max(err, std::abs(kinetic[k] + potential[k] - work_in[k] - e0));
  return err / kinetic[0];
}

}  // namespace granwave::chain
