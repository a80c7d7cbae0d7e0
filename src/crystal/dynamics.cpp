// 256-bit vectors for the contact loop (4 contacts per instruction; lane-wise IEEE: the same results
// at any width). With AVX-512 this still uses its masks and 32 registers; 512-bit vectors were
// slower on the AMD EPYC (Zen 4) development machine, end to end (CPU time, 3200-particle crystal,
// 6000 steps, alternating runs): friction 2.18 s at 512 bits against 1.90 s at 256, frictionless
// 0.92 against 0.86 (its 512-bit gathers and roots do not pay for their width).
#pragma GCC target("prefer-vector-width=256")
#include "crystal/dynamics.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <numeric>
#include <string>
#include <type_traits>

#include "contact/hooke.hpp"
#include "contact/linear_luding.hpp"
#include "core/error.hpp"
#include "crystal/kernel.hpp"
#include "crystal/neighbors.hpp"

namespace granwave::crystal {

std::shared_ptr<const ContactModel> case_model(const config::ContactParams& cp) {
  const contact::LinearSpringDashpotParams normal{cp.kn, cp.gamma_n, cp.normal_tension == config::NormalTension::clip};
  const contact::TangentialSpringParams tangential{cp.kt, cp.gamma_t, cp.mu_static, cp.mu_dynamic,
                                                   cp.coulomb_normal == config::CoulombNormal::magnitude};
  normal.validate();
  tangential.validate();
  const bool contact_point = cp.lever_arm == config::LeverArm::contact_point;
  const bool dashpots = normal.gamma_n > 0.0 || tangential.gamma_t > 0.0;
  const bool hysteresis = tangential.mu_static != tangential.mu_dynamic;
  if (tangential.active()) {
    if (dashpots && hysteresis) return model_of(contact::LinearLudingLaw<true, true>(normal, tangential, contact_point));
    if (dashpots) return model_of(contact::LinearLudingLaw<true, false>(normal, tangential, contact_point));
    if (hysteresis) return model_of(contact::LinearLudingLaw<false, true>(normal, tangential, contact_point));
    return model_of(contact::LinearLudingLaw<false, false>(normal, tangential, contact_point));
  }
  if (normal.gamma_n > 0.0) return model_of(contact::HookeLaw<true>(normal));
  return model_of(contact::HookeLaw<false>(normal));
}

Dynamics::Dynamics(const Packing& packing, const config::ContactParams& cp, double dt)
    : Dynamics(packing, case_model(cp), dt) {}

Dynamics::Dynamics(const Packing& packing, std::shared_ptr<const ContactModel> model, double dt)
    : packing_(packing), model_(std::move(model)), dt_(dt) {
  friction_ = model_->torques();
  arm_shift_ = model_->arm_shift();
  if (!(dt > 0.0)) throw InputError("integrator.dt must be > 0");
  const std::size_t n = packing.size();
  x = x0 = packing.x;
  y = y0 = packing.y;
  z = z0 = packing.z;
  for (auto* v : {&vx, &vy, &vz, &wx, &wy, &wz, &fx, &fy, &fz, &tx, &ty, &tz}) v->assign(n, 0.0);
  radius = packing.radius;
  mass = packing.mass;
  inertia = packing.inertia;
  inv_mass.resize(n);
  inv_inertia.resize(n);
  mobile.resize(n);
  for (std::size_t p = 0; p < n; ++p) {
    inv_mass[p] = 1.0 / mass[p];
    inv_inertia[p] = 1.0 / inertia[p];
    mobile[p] = packing.fixed[p] ? 0 : 1;
  }
  // Not kept twice (memory): x0, y0, z0, radius, mass and inertia hold them.
  for (auto* v : {&packing_.x, &packing_.y, &packing_.z, &packing_.radius, &packing_.mass, &packing_.inertia})
    *v = std::vector<double>();
  // Skin: 5 % of a diameter keeps next-nearest FCC neighbours (sqrt(2) d away) out of the
  // list while small-amplitude waves never trigger a rebuild.
  const double a_mean = std::accumulate(radius.begin(), radius.end(), 0.0) / std::max<std::size_t>(1, n);
  skin_ = 0.1 * a_mean;
  rebuild();
  compute_forces(dt_, true);
}

void Dynamics::set_mobile(std::size_t p, bool on) {
  if (mobile[p] == static_cast<std::uint8_t>(on)) return;
  mobile[p] = on;
  rebuild();  // pairs of two non-mobile particles are not in the list
}

double Dynamics::max_displacement_since_build() const {
  double m2 = 0.0;
  for (std::size_t p = 0; p < size(); ++p) {
    const double dx = (x[p] - x0[p]) - x_build_[p], dy = (y[p] - y0[p]) - y_build_[p],
                 dz = (z[p] - z0[p]) - z_build_[p];
    m2 = std::max(m2, dx * dx + dy * dy + dz * dz);
  }
  return std::sqrt(m2);
}

void Dynamics::rebuild() {
  const std::size_t n = size();
  std::vector<std::uint8_t> skip(n);
  for (std::size_t p = 0; p < n; ++p) skip[p] = !mobile[p];
  PairList pairs = find_pairs(x.data(), y.data(), z.data(), radius.data(), n, packing_.box_x, packing_.box_y, skin_,
                              skip.data());
  ContactList& old = contacts;
  for (double e : old.dissipated) dissipated_before_ += e;
  ContactList fresh;
  const std::size_t nc = pairs.size();
  fresh.i = std::move(pairs.i);
  fresh.j = std::move(pairs.j);
  fresh.image_x = std::move(pairs.image_x);
  fresh.image_y = std::move(pairs.image_y);
  for (auto* v : {&fresh.delta, &fresh.f_x, &fresh.f_y, &fresh.f_z, &fresh.dissipated}) v->assign(nc, 0.0);
  const bool torques = model_->torques();
  if (torques)
    for (auto* v : {&fresh.nf_x, &fresh.nf_y, &fresh.nf_z}) v->assign(nc, 0.0);
  const std::size_t nh = model_->history_columns();
  fresh.history_columns = nh;
  fresh.history.assign(nh * nc, 0.0);
  auto key_less = [](const ContactList& a, std::size_t u, const ContactList& b, std::size_t v) {
    if (a.i[u] != b.i[v]) return a.i[u] < b.i[v];
    if (a.j[u] != b.j[v]) return a.j[u] < b.j[v];
    if (a.image_x[u] != b.image_x[v]) return a.image_x[u] < b.image_x[v];
    return a.image_y[u] < b.image_y[v];
  };
  // Both lists are sorted by (i, j, image): carry the history of persisting pairs over.
  std::size_t u = 0;
  for (std::size_t c = 0; c < nc; ++c) {
    while (u < old.size() && key_less(old, u, fresh, c)) ++u;
    if (u < old.size() && !key_less(fresh, c, old, u)) {
      for (std::size_t k = 0; k < nh; ++k) fresh.history_column(k)[c] = old.history_column(k)[u];
      fresh.delta[c] = old.delta[u];
      fresh.f_x[c] = old.f_x[u];
      fresh.f_y[c] = old.f_y[u];
      fresh.f_z[c] = old.f_z[u];
      if (torques) {
        fresh.nf_x[c] = old.nf_x[u];
        fresh.nf_y[c] = old.nf_y[u];
        fresh.nf_z[c] = old.nf_z[u];
      }
    }  // else a new pair: no spring yet ("if the spring is new, [its] length is zero")
  }
  // Per-particle contact lists in contact order, for the deterministic gather: the contacts
  // where the particle is j (a CSR list), then the range where it is i (the list is sorted by i).
  fresh.j_first.assign(n + 1, 0);
  fresh.i_first.assign(n + 1, 0);
  for (std::size_t c = 0; c < nc; ++c) {
    ++fresh.j_first[fresh.j[c] + 1];
    ++fresh.i_first[fresh.i[c] + 1];
  }
  std::partial_sum(fresh.j_first.begin(), fresh.j_first.end(), fresh.j_first.begin());
  std::partial_sum(fresh.i_first.begin(), fresh.i_first.end(), fresh.i_first.begin());
  fresh.j_contacts.resize(nc);
  {
    std::vector<std::int32_t> fill(fresh.j_first.begin(), fresh.j_first.end() - 1);
    for (std::size_t c = 0; c < nc; ++c) fresh.j_contacts[fill[fresh.j[c]]++] = static_cast<std::int32_t>(c);
  }
  contacts = std::move(fresh);
  x_build_.resize(n);
  y_build_.resize(n);
  z_build_.resize(n);
  for (std::size_t p = 0; p < n; ++p) {
    x_build_[p] = static_cast<float>(x[p] - x0[p]);
    y_build_[p] = static_cast<float>(y[p] - y0[p]);
    z_build_[p] = static_cast<float>(z[p] - z0[p]);
  }
  ++rebuilds;
}

// Sum of each particle's contact forces and torques in contact order; with Kick, the half
// kick of velocity Verlet follows at once (the forces are then still in cache). The torque of
// contact c on p is -arm n x f^t with arm = a_p (eq. (4)), or a_p - delta_c/2 with
// ContactPointArm: then -a_p sum(n x f^t) + (1/2) sum(delta_c n x f^t).
template <bool Kick, bool Torques, bool ContactPointArm>
void Dynamics::particle_pass(double h) {
  const ContactList& C = contacts;
  const std::int64_t n = static_cast<std::int64_t>(size());
  constexpr bool fr = Torques;
  const std::int32_t* __restrict j_first = C.j_first.data();
  const std::int32_t* __restrict j_contacts = C.j_contacts.data();
  const std::int32_t* __restrict i_first = C.i_first.data();
  const double* __restrict cfx = C.f_x.data();
  const double* __restrict cfy = C.f_y.data();
  const double* __restrict cfz = C.f_z.data();
  const double* __restrict cnx = C.nf_x.data();
  const double* __restrict cny = C.nf_y.data();
  const double* __restrict cnz = C.nf_z.data();
  const double* __restrict cdelta = C.delta.data();
#pragma omp parallel for schedule(static) if (threaded())
  for (std::int64_t p = 0; p < n; ++p) {
    double sx = 0.0, sy = 0.0, sz = 0.0, nx = 0.0, ny = 0.0, nz = 0.0;
    double dnx = 0.0, dny = 0.0, dnz = 0.0;  // sum(delta_c n x f^t), ContactPointArm only
    // Both spheres feel -a n x f^t (contact::tangential_torque); j gets -f (s + (-f) is s - f).
    auto add = [&](std::int32_t c, auto as_j) __attribute__((always_inline)) {
      if constexpr (decltype(as_j)::value) {
        sx -= cfx[c];
        sy -= cfy[c];
        sz -= cfz[c];
      } else {
        sx += cfx[c];
        sy += cfy[c];
        sz += cfz[c];
      }
      if constexpr (fr) {
        nx += cnx[c];
        ny += cny[c];
        nz += cnz[c];
        if constexpr (ContactPointArm) {
          dnx += cdelta[c] * cnx[c];
          dny += cdelta[c] * cny[c];
          dnz += cdelta[c] * cnz[c];
        }
      }
    };
    for (std::int32_t k = j_first[p]; k < j_first[p + 1]; ++k) add(j_contacts[k], std::true_type{});
    for (std::int32_t c = i_first[p]; c < i_first[p + 1]; ++c) add(c, std::false_type{});
    fx[p] = sx;
    fy[p] = sy;
    fz[p] = sz;
    if constexpr (ContactPointArm) {
      tx[p] = -radius[p] * nx + 0.5 * dnx;
      ty[p] = -radius[p] * ny + 0.5 * dny;
      tz[p] = -radius[p] * nz + 0.5 * dnz;
    } else {
      tx[p] = -radius[p] * nx;
      ty[p] = -radius[p] * ny;
      tz[p] = -radius[p] * nz;
    }
    if (Kick && mobile[p]) {
      vx[p] += h * sx * inv_mass[p];
      vy[p] += h * sy * inv_mass[p];
      vz[p] += h * sz * inv_mass[p];
      if constexpr (fr) {
        wx[p] += h * tx[p] * inv_inertia[p];
        wy[p] += h * ty[p] * inv_inertia[p];
        wz[p] += h * tz[p] * inv_inertia[p];
      }
    }
  }
}

void Dynamics::compute_forces(double inc, bool dashpots, bool kick) {
  model_->contact_pass(*this, inc, dashpots);
  if (!friction_)
    kick ? particle_pass<true, false, false>(0.5 * dt_) : particle_pass<false, false, false>(0.0);
  else if (arm_shift_ != 0.0)
    kick ? particle_pass<true, true, true>(0.5 * dt_) : particle_pass<false, true, true>(0.0);
  else
    kick ? particle_pass<true, true, false>(0.5 * dt_) : particle_pass<false, true, false>(0.0);
}

void Dynamics::step() {
  const double h = 0.5 * dt_;
  const std::int64_t n = static_cast<std::int64_t>(size());
  // First half kick and drift (translation; sphere orientation is not needed), with the
  // largest displacement since the list was built (a max: exact in any order).
  double m2 = 0.0;
#pragma omp parallel for schedule(static) reduction(max : m2) if (threaded())
  for (std::int64_t p = 0; p < n; ++p) {
    if (mobile[p]) {
      vx[p] += h * fx[p] * inv_mass[p];
      vy[p] += h * fy[p] * inv_mass[p];
      vz[p] += h * fz[p] * inv_mass[p];
      x[p] += dt_ * vx[p];
      y[p] += dt_ * vy[p];
      z[p] += dt_ * vz[p];
      if (friction_) {
        wx[p] += h * tx[p] * inv_inertia[p];
        wy[p] += h * ty[p] * inv_inertia[p];
        wz[p] += h * tz[p] * inv_inertia[p];
      }
    }
    const double dx = (x[p] - x0[p]) - x_build_[p], dy = (y[p] - y0[p]) - y_build_[p],
                 dz = (z[p] - z0[p]) - z_build_[p];
    m2 = std::max(m2, dx * dx + dy * dy + dz * dz);
  }
  time += dt_;
  ++steps;
  if (std::sqrt(m2) > 0.5 * skin_) rebuild();
  compute_forces(dt_, true, true);  // forces at t + dt and the second half kick
}

void Dynamics::displace(const std::vector<std::size_t>& which, double dx, double dy, double dz) {
  const double before = potential_energy() + dissipated_energy();
  // Static update with every particle at rest: the step is a jump of position, not a motion, so
  // the tangential springs (eq. (6) integrates v_t dt) do not see it and f_t = 0 at t = 0, as
  // seed 002 sec. 3.5 prepares its runs and as YADE and LIGGGHTS do; no dashpots.
  const auto keep = std::array{vx, vy, vz, wx, wy, wz};
  for (auto* v : {&vx, &vy, &vz, &wx, &wy, &wz}) std::fill(v->begin(), v->end(), 0.0);
  for (std::size_t p : which) {
    x[p] += dx;
    y[p] += dy;
    z[p] += dz;
  }
  if (max_displacement_since_build() > 0.5 * skin_) rebuild();
  compute_forces(1.0, false);
  vx = keep[0];
  vy = keep[1];
  vz = keep[2];
  wx = keep[3];
  wy = keep[4];
  wz = keep[5];
  work_in += potential_energy() + dissipated_energy() - before;
}

double Dynamics::kinetic_energy() const {
  double e = 0.0;
  for (std::size_t p = 0; p < size(); ++p) {
    if (!mobile[p]) continue;
    e += 0.5 * mass[p] * (vx[p] * vx[p] + vy[p] * vy[p] + vz[p] * vz[p]) +
         0.5 * inertia[p] * (wx[p] * wx[p] + wy[p] * wy[p] + wz[p] * wz[p]);
  }
  return e;
}

double Dynamics::potential_energy() const { return model_->stored_energy(contacts); }

double Dynamics::dissipated_energy() const {
  double e = dissipated_before_;
  // A law that never dissipates leaves every entry +0.0: the sum would return e unchanged.
  if (!model_->dissipates()) return e;
  for (double d : contacts.dissipated) e += d;
  return e;
}

double Dynamics::verlet_correction() const {
  double s = 0.0;
  for (std::size_t p = 0; p < size(); ++p) {
    if (!mobile[p]) continue;
    s += (fx[p] * fx[p] + fy[p] * fy[p] + fz[p] * fz[p]) * inv_mass[p] +
         (tx[p] * tx[p] + ty[p] * ty[p] + tz[p] * tz[p]) * inv_inertia[p];
  }
  return dt_ * dt_ / 8.0 * s;
}

int Dynamics::touching_contacts_of(std::size_t p) const {
  const ContactList& C = contacts;
  int k = 0;
  for (std::int32_t e = C.j_first[p]; e < C.j_first[p + 1]; ++e) k += C.delta[C.j_contacts[e]] > 0.0;
  for (std::int32_t c = C.i_first[p]; c < C.i_first[p + 1]; ++c) k += C.delta[c] > 0.0;
  return k;
}

// ---- relaxation ----

RelaxResult relax(Packing& packing, double kn, double tolerance, long max_steps) {
  config::ContactParams cp;
  cp.kn = kn;
  cp.kt = 0.0;
  cp.gamma_n = 0.0;
  // FIRE parameters of Bitzek et al., PRL 97, 170201 (2006).
  const double m_min = *std::min_element(packing.mass.begin(), packing.mass.end());
  const double t_c = contact::contact_time({kn, 0.0, false}, 0.5 * m_min);
  const double dt_max = 0.1 * t_c, f_inc = 1.1, f_dec = 0.5, alpha_0 = 0.1, f_alpha = 0.99;
  const int n_min = 5, n_quiet = 50;
  double dt = 0.02 * t_c, alpha = alpha_0;
  Dynamics dyn(packing, cp, dt);
  const std::size_t n = dyn.size();
  long since_reset = 0, quiet = 0;
  RelaxResult res;
  for (long s = 0; s < max_steps; ++s) {
    // FIRE mixing: power P = F.v over the mobile particles.
    double power = 0.0, v2 = 0.0, f2 = 0.0;
    for (std::size_t p = 0; p < n; ++p) {
      if (!dyn.mobile[p]) continue;
      power += dyn.fx[p] * dyn.vx[p] + dyn.fy[p] * dyn.vy[p] + dyn.fz[p] * dyn.vz[p];
      v2 += dyn.vx[p] * dyn.vx[p] + dyn.vy[p] * dyn.vy[p] + dyn.vz[p] * dyn.vz[p];
      f2 += dyn.fx[p] * dyn.fx[p] + dyn.fy[p] * dyn.fy[p] + dyn.fz[p] * dyn.fz[p];
    }
    if (power > 0.0) {
      const double scale = f2 > 0.0 ? alpha * std::sqrt(v2 / f2) : 0.0;
      for (std::size_t p = 0; p < n; ++p) {
        if (!dyn.mobile[p]) continue;
        dyn.vx[p] = (1.0 - alpha) * dyn.vx[p] + scale * dyn.fx[p];
        dyn.vy[p] = (1.0 - alpha) * dyn.vy[p] + scale * dyn.fy[p];
        dyn.vz[p] = (1.0 - alpha) * dyn.vz[p] + scale * dyn.fz[p];
      }
      if (++since_reset > n_min) {
        dt = std::min(dt * f_inc, dt_max);
        alpha *= f_alpha;
      }
    } else {
      for (auto* v : {&dyn.vx, &dyn.vy, &dyn.vz}) std::fill(v->begin(), v->end(), 0.0);
      dt *= f_dec;
      alpha = alpha_0;
      since_reset = 0;
    }
    dyn.set_dt(dt);
    dyn.step();
    const double ratio = dyn.kinetic_energy() / dyn.potential_energy();
    quiet = (ratio < tolerance && since_reset > 0) ? quiet + 1 : 0;
    if (quiet >= n_quiet) {
      res.steps = s + 1;
      res.ratio = ratio;
      for (std::size_t p = 0; p < n; ++p) {
        packing.x[p] = dyn.x[p] - std::floor(dyn.x[p] / packing.box_x) * packing.box_x;
        packing.y[p] = dyn.y[p] - std::floor(dyn.y[p] / packing.box_y) * packing.box_y;
        packing.z[p] = dyn.z[p];
      }
      return res;
    }
  }
  throw RunError("relaxation did not reach E_kin/E_pot < " + std::to_string(tolerance) + " within " +
                 std::to_string(max_steps) + " steps");
}

}  // namespace granwave::crystal
