#include "crystal/simulation.hpp"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <ctime>
#include <numbers>
#include <optional>
#include <sstream>
#include <tuple>

#include "config/contact_laws.hpp"
#include "contact/linear_spring_dashpot.hpp"
#include "contact/tangential_spring.hpp"
#include "core/error.hpp"
#include "io/h5.hpp"

namespace granwave::crystal {

ContactAt contact_at(const config::Case& c, double delta) {
  return contact_between(c, c.crystal->radius, c.crystal->radius, delta);
}

ContactAt contact_between(const config::Case& c, double a_i, double a_j, double delta) {
  return config::law_of(c.contact).at(c.contact, c.crystal->density, a_i, a_j, delta);
}

theory::LatticeCellOptions lattice_options(const config::Case& c, double tolerance) {
  theory::LatticeCellOptions opt;
  opt.tolerance = tolerance;
  opt.arm_shift = contact::arm_shift(c.contact.friction().lever_arm);
  opt.kr = c.contact.rolling().kr;
  opt.ko = c.contact.rolling().ko;
  opt.rolling_arm_shift = contact::rolling_shift(c.contact.rolling().rolling_lever, c.contact.friction().lever_arm);  // the law's a
  return opt;
}

theory::ContactNetwork contact_network(const config::Case& c, const Packing& pk) {
  const bool own_stiffness = config::law_of(c.contact).stiffness_of_overlap;
  const ContactAt k0 = contact_at(c, pk.delta);
  theory::ContactNetwork net;
  net.box_x = pk.box_x;
  net.box_y = pk.box_y;
  net.k = k0.kn;
  net.kt = k0.kt;
  for (std::size_t p = 0; p < pk.size(); ++p)
    net.particles.push_back({pk.mass[p], pk.layer[p], pk.z[p], pk.radius[p], pk.inertia[p]});
  for (const auto& q : list_contacts(pk, true)) {
    theory::NetworkContact nc{q.i, q.j, theory::Vec3(q.bx, q.by, q.bz),
                              static_normal_force(c, pk.radius[q.i], pk.radius[q.j], q.overlap)};
    if (own_stiffness) {  // each contact linearised at its own overlap
      const ContactAt kc = contact_between(c, pk.radius[q.i], pk.radius[q.j], q.overlap);
      nc.k = kc.kn;
      nc.kt = kc.kt;
    }
    net.contacts.push_back(nc);
  }
  return net;
}

double static_normal_force(const config::Case& c, double a_i, double a_j, double delta) {
  return contact_between(c, a_i, a_j, delta).f_n;
}

std::string contact_law_name(const contact::LawParams& cp) { return config::law_of(cp).name; }
std::string tangential_history_name(const contact::LawParams& cp) { return config::law_of(cp).history_name(cp); }

Derived derive(const config::Case& c) {
  if (!c.crystal) throw InputError(c.path + ": [crystal] is missing");
  const config::CrystalCase& k = *c.crystal;
  Derived d;
  const double a = k.radius;
  const double delta = 2.0 * a * k.overlap;
  // The law linearised at the static overlap (the linear law: its keys).
  const ContactAt k0 = contact_at(c, delta);
  d.kn = k0.kn;
  d.kt = k0.kt;
  d.gamma_n = k0.gamma_n;
  d.f0 = k0.f_n;
  const contact::LinearSpringDashpotParams normal{d.kn, d.gamma_n, c.contact.friction().clip()};
  const contact::TangentialSpringParams tangential{d.kt, k0.gamma_t, c.contact.friction().mu_static, c.contact.friction().mu_dynamic,
                                                   c.contact.friction().magnitude()};
  normal.validate();
  tangential.validate();
  d.mass = k.density * 4.0 / 3.0 * std::numbers::pi * a * a * a;
  d.m_ij = contact::reduced_mass(d.mass, d.mass);
  d.omega = contact::contact_frequency(normal, d.m_ij);
  if (!std::isfinite(d.omega))
    throw InputError(c.path + ": contact.gamma_n = " + std::to_string(c.contact.number("gamma_n").value_or(0.0)) +
                     " overdamps a contact (k/m_ij < eta_0^2): no contact time");
  d.t_c = contact::contact_time(normal, d.m_ij);
  d.restitution = contact::restitution(normal, d.m_ij);
  if (c.integrator.dt)
    d.dt = *c.integrator.dt;
  else if (c.integrator.dt_over_tc)
    d.dt = *c.integrator.dt_over_tc * d.t_c;
  else
    throw InputError(c.path + ": [integrator] needs dt or dt_over_tc");
  if (!(d.dt > 0.0)) throw InputError(c.path + ": integrator.dt must be > 0");
  if (c.integrator.scheme != config::Scheme::verlet)
    throw InputError(c.path + ": integrator.scheme: the crystal integrates with \"verlet\" only");
  // The largest overlap: the initial one plus what the source puts into one contact (a
  // displacement step |amplitude| d; a velocity |v| sqrt(m/k), an upper bound for Hertz too,
  // whose force grows faster than its tangent at delta_0).
  const double diameter = 2.0 * a;
  const bool velocity = c.excitation.drive == config::Excitation::Drive::velocity;
  d.delta_max = delta + (velocity ? std::abs(c.excitation.amplitude) * std::sqrt(d.mass / d.kn)
                                  : std::abs(c.excitation.amplitude) * diameter);
  // Stability of velocity Verlet: dt < 2/omega_max. Conservative (Gershgorin-type) bound on
  // the crystal's highest frequency: omega_max^2 <= 2 z (k + 3.5 k_t)/m_min with z = 12 contacts;
  // 3.5 = 1 + m a^2/I couples the tangential spring to rotation. With dashpots the explicit
  // limit shrinks to (sqrt(1 + zeta^2) - zeta) 2/omega_max, zeta = eta_max/omega_max.
  // Hertz: the stiffnesses and damping at the largest expected overlap delta_max.
  const double a_min = a - k.polydispersity * delta;
  const double m_min = k.density * 4.0 / 3.0 * std::numbers::pi * a_min * a_min * a_min;
  const double z = 12.0;
  // (polydisperse: the largest radii, whose overlaps start up to 2 polydispersity delta larger)
  const double a_max = a + k.polydispersity * delta;
  const ContactAt stiffest = contact_between(c, a_max, a_max, d.delta_max + 2.0 * k.polydispersity * delta);
  const double gamma_t = stiffest.gamma_t;
  const double omega_max = std::sqrt(2.0 * z * (stiffest.kn + 3.5 * stiffest.kt) / m_min);
  const double eta_max = z * (stiffest.gamma_n + gamma_t) / (2.0 * m_min);
  const double zeta = eta_max / omega_max;
  d.dt_stable = 2.0 / omega_max * (std::sqrt(1.0 + zeta * zeta) - zeta);
  const double d_prime = 2.0 * a - delta;
  // Isotropic prestress 2 sqrt(2) f0 / d'^2 (f0 = k delta: linear).
  d.sigma_0 = 2.0 * std::numbers::sqrt2 * d.f0 / (d_prime * d_prime);
  // Eq. (10) for the FCC network with branch d' (sum n_z^4 = 2, sum n_z^2 n_x^2 = 1 per
  // particle, volume d'^3/sqrt(2) per particle): V_pz = d' sqrt(k/m) sqrt(1 + k_t/k) (affine),
  // V_sz = d' sqrt(k/(2m)) (frictionless; rotations make the k_t term unreliable for S).
  d.v_p = d_prime * std::sqrt(d.kn / d.mass) * std::sqrt(1.0 + d.kt / d.kn);
  d.v_s = d_prime * std::sqrt(d.kn / (2.0 * d.mass));
  d.steps = std::llround(c.integrator.t_end / d.dt);
  d.sample_every = c.output.interval > 0.0 ? std::max(1LL, std::llround(c.output.interval / d.dt)) : 1;
  return d;
}

namespace {
// Per contact c of [c0, c1), the lever arms times u_z of its ends (Dynamics::end_arm) at 2c and
// 2c + 1, from the stored overlaps, u_z = (z_j - z_i)/((a_i + a_j) - delta) (see layer_stress);
// returns how many contacts are within the margin where that is exact. A loop that vectorises.
std::int64_t exact_end_arms(std::size_t c0, std::size_t c1, const std::int32_t* __restrict pi,
                            const std::int32_t* __restrict pj, const double* __restrict a, const double* __restrict z,
                            const double* __restrict delta, double* __restrict arm_u) {
  std::int64_t exact = 0;
  for (std::size_t c = c0; c < c1; ++c) {
    const double reach = a[pi[c]] + a[pj[c]];
    exact += Dynamics::distance_from_overlap_exact(delta[c], reach) ? 1 : 0;
    const double u_z = (z[pj[c]] - z[pi[c]]) / (reach - delta[c]);
    arm_u[2 * c] = Dynamics::end_arm(a[pi[c]], delta[c], u_z);
    arm_u[2 * c + 1] = Dynamics::end_arm(a[pj[c]], delta[c], u_z);
  }
  return exact;
}

// Every contact's end arms (end_arms' [2 c + end]): those the contact pass stored with the
// forces (Dynamics::end_arms, one thread), else made here into `scratch`.
const double* contact_end_arms(const Dynamics& dyn, std::vector<double>& scratch) {
  if (dyn.end_arms_stored) return dyn.end_arms.data();
  const Packing& pk = dyn.packing();
  const ContactList& C = dyn.contacts;
  const std::size_t nc = C.size();
  scratch.resize(2 * nc);
  const double* a = dyn.radius.data();
  const double *z = dyn.z.data(), *delta = C.delta.data();
  const std::int32_t *pi = C.i.data(), *pj = C.j.data();
  constexpr std::size_t kBlock = 256;
  for (std::size_t c0 = 0; c0 < nc; c0 += kBlock) {
    const std::size_t c1 = std::min(nc, c0 + kBlock);
    // The distance r = |r_j - r_i| from the overlap the contact pass stored at these positions,
    // delta = (a_i + a_j) - r: while r/2 <= a_i + a_j <= 2r that subtraction is exact (Sterbenz),
    // so (a_i + a_j) - delta gives the root's r bit for bit without x, y and the root. Checked
    // per block on the stored delta with a margin (-reach/2 <= delta <= reach/4); else the
    // block again with the root.
    if (exact_end_arms(c0, c1, pi, pj, a, z, delta, scratch.data()) != static_cast<std::int64_t>(c1 - c0)) {
      for (std::size_t c = c0; c < c1; ++c) {
        const int i = C.i[c], j = C.j[c];
        const double bx = dyn.x[j] + C.image_x[c] * pk.box_x - dyn.x[i];
        const double by = dyn.y[j] + C.image_y[c] * pk.box_y - dyn.y[i];
        const double bz = dyn.z[j] - dyn.z[i];
        const double u_z = bz / std::sqrt(bx * bx + by * by + bz * bz);
        scratch[2 * c] = Dynamics::end_arm(a[i], delta[c], u_z);
        scratch[2 * c + 1] = Dynamics::end_arm(a[j], delta[c], u_z);
      }
    }
  }
  return scratch.data();
}
}  // namespace

void layer_stress(const Dynamics& dyn, std::vector<double>& zz, std::vector<double>& zx,
                  std::vector<double>* particle_stress) {
  const Packing& pk = dyn.packing();
  const std::size_t nl = static_cast<std::size_t>(pk.layers);
  zz.assign(nl, 0.0);
  zx.assign(nl, 0.0);
  if (particle_stress) particle_stress->assign(9 * dyn.size(), 0.0);
  const ContactList& C = dyn.contacts;
  const double volume = pk.box_x * pk.box_y * pk.l0;  // of one layer
  if (particle_stress) {
    for (std::size_t c = 0; c < C.size(); ++c) {
      const double delta = C.delta[c];
      if (delta <= 0.0) continue;
      const int i = C.i[c], j = C.j[c];
      if (pk.fixed[i] && pk.fixed[j]) continue;
      const double bx = dyn.x[j] + C.image_x[c] * pk.box_x - dyn.x[i];
      const double by = dyn.y[j] + C.image_y[c] * pk.box_y - dyn.y[i];
      const double bz = dyn.z[j] - dyn.z[i];
      const double r = std::sqrt(bx * bx + by * by + bz * bz);
      const double u[3] = {bx / r, by / r, bz / r};  // from i towards j
      const double f[3] = {C.f_x[c], C.f_y[c], C.f_z[c]};  // on i; j gets -f
      // -(x_c - x_i) (x) f  with x_c - x_i = (a_i - delta/2) u;  -(x_c - x_j) (x) (-f) likewise
      const double arm_i = dyn.radius[i] - 0.5 * delta, arm_j = dyn.radius[j] - 0.5 * delta;
      zz[pk.layer[i]] -= arm_i * u[2] * f[2];
      zx[pk.layer[i]] -= arm_i * u[2] * f[0];
      zz[pk.layer[j]] -= arm_j * u[2] * f[2];
      zx[pk.layer[j]] -= arm_j * u[2] * f[0];
      double* si = particle_stress->data() + 9 * i;
      double* sj = particle_stress->data() + 9 * j;
      for (int a = 0; a < 3; ++a)
        for (int b = 0; b < 3; ++b) {
          si[3 * a + b] -= arm_i * u[a] * f[b];
          sj[3 * a + b] -= arm_j * u[a] * f[b];
        }
    }
  } else {
    // The same sums, faster (a sample costs about as much as a time step otherwise). First every
    // contact's (a_i - delta/2) u_z, (a_j - delta/2) u_z: stored by the contact pass with the
    // forces on one thread, else made here in loops that vectorise. Then each layer's sums over
    // the ends of its contacts in list order (Dynamics::LayerOrder::ends, i before j), the terms
    // arm u_z f_z, arm u_z f_x formed there, several layers side by side (layer_chains): the same
    // products and subtractions in the same order.
    static thread_local std::vector<double> arms;  // scratch of contact_end_arms
    const double* arm_u = contact_end_arms(dyn, arms);
    const double *f_z = C.f_z.data(), *f_x = C.f_x.data();
    layer_chains<2>(dyn.layer_order().ends, std::array{zz.data(), zx.data()},
                    [=](std::array<double, 2>& acc, std::int32_t e) {
                      acc[0] -= arm_u[e] * f_z[e >> 1];
                      acc[1] -= arm_u[e] * f_x[e >> 1];
                    });
  }
  for (std::size_t L = 0; L < nl; ++L) {
    zz[L] /= volume;
    zx[L] /= volume;
  }
  if (particle_stress) {
    const double share = volume / (static_cast<double>(pk.nx) * pk.ny);
    for (double& s : *particle_stress) s /= share;
  }
}

double coordination(const Dynamics& dyn) {
  // Each touching contact counts once for each of its particles that is owned and not fixed
  // (the count of Dynamics::touching_contacts_of over those particles, in one walk).
  const Dynamics::LayerOrder& o = dyn.layer_order();
  const double* delta = dyn.contacts.delta.data();
  const std::uint8_t* ends = o.counted_ends.data();
  long contacts = 0, particles = o.free_particles;
  const std::size_t nc = o.counted_ends.size();
  for (std::size_t c0 = 0; c0 < nc; c0 += 1 << 20) {  // 32-bit sums (narrower vectors), exact within a block
    std::int32_t block = 0;
    for (std::size_t c = c0; c < std::min(nc, c0 + (1 << 20)); ++c) block += delta[c] > 0.0 ? ends[c] : 0;
    contacts += block;
  }
  if (const SlabPlan* s = dyn.slab()) {  // whole numbers: exact in doubles and in any order
    std::vector<double> all;
    s->comm->allgather({static_cast<double>(contacts), static_cast<double>(particles)}, all);
    contacts = particles = 0;
    for (std::size_t r = 0; 2 * r < all.size(); ++r) {
      contacts += static_cast<long>(all[2 * r]);
      particles += static_cast<long>(all[2 * r + 1]);
    }
  }
  return particles ? static_cast<double>(contacts) / particles : 0.0;
}

namespace {

// Every observer is a sum per layer over the owned particles or contacts in index order (each
// layer's sums are complete on the rank owning it), or a total over layers in layer order
// (Dynamics::energies), or an integer count (coordination). Under a slab plan rank 0 gathers the
// rows; the other ranks keep the global series only.
void sample(const Dynamics& dyn, Traces& tr) {
  const std::size_t nl = tr.nlayers;
  tr.time.push_back(dyn.time);
  static thread_local std::vector<double> zz, zx, uz, ux, vz, vx, count;  // no allocation per sample
  layer_stress(dyn, zz, zx);
  for (auto* f : {&uz, &ux, &vz, &vx, &count}) f->assign(nl, 0.0);
  // The layers' sums side by side (layer_chains); the count of a layer's particles is the
  // length of its list (a sum of 1.0s: the same whole number).
  const double *z = dyn.z.data(), *z0 = dyn.z0.data(), *x = dyn.x.data(), *x0 = dyn.x0.data(),
               *v_z = dyn.vz.data(), *v_x = dyn.vx.data();
  const LayerLists& particles = dyn.layer_order().particles;
  layer_chains<2>(particles, std::array{uz.data(), ux.data(), vz.data(), vx.data()},
                  [=](std::array<double, 4>& acc, std::int32_t p) {
                    acc[0] += z[p] - z0[p];
                    acc[1] += x[p] - x0[p];
                    acc[2] += v_z[p];
                    acc[3] += v_x[p];
                  });
  for (std::size_t L = 0; L < nl; ++L) count[L] = static_cast<double>(particles.first[L + 1] - particles.first[L]);
  const SlabPlan* slab = dyn.slab();
  const std::size_t L0 = slab ? slab->first_layer[slab->rank] : 0, L1 = slab ? slab->first_layer[slab->rank + 1] : nl;
  static thread_local std::vector<double> rows;  // [6][L1 - L0]: this rank's layers, field by field
  rows.clear();
  for (const auto* f : {&zz, &zx}) rows.insert(rows.end(), f->begin() + L0, f->begin() + L1);
  for (const auto* f : {&uz, &ux, &vz, &vx})
    for (std::size_t L = L0; L < L1; ++L) rows.push_back((*f)[L] * (count[L] > 0.0 ? 1.0 / count[L] : 0.0));
  static thread_local std::vector<double> gathered;
  if (slab) slab->comm->gather(rows, gathered);
  const std::vector<double>& all = slab ? gathered : rows;
  if (!slab || slab->rank == 0)
    for (int r = 0; r < (slab ? slab->ranks : 1); ++r) {
      const std::size_t a = slab ? slab->first_layer[r] : 0, b = slab ? slab->first_layer[r + 1] : nl;
      const double* block = all.data() + 6 * a;  // the ranks' blocks follow each other in layer order
      const std::array out{&tr.stress_zz, &tr.stress_zx, &tr.displacement_z, &tr.displacement_x, &tr.velocity_z,
                           &tr.velocity_x};
      for (std::size_t k = 0; k < 6; ++k) out[k]->insert(out[k]->end(), block + k * (b - a), block + (k + 1) * (b - a));
    }
  tr.coordination.push_back(coordination(dyn));
  const Dynamics::Energies e = dyn.energies();
  tr.kinetic.push_back(e.kinetic);
  tr.potential.push_back(e.potential);
  tr.dissipated.push_back(e.dissipated);
  tr.work_in.push_back(dyn.work_in);
  tr.verlet_correction.push_back(e.verlet_correction);
}

double process_cpu_seconds() {  // all threads of the process
  timespec t{};
  clock_gettime(CLOCK_PROCESS_CPUTIME_ID, &t);
  return static_cast<double>(t.tv_sec) + 1e-9 * static_cast<double>(t.tv_nsec);
}

// The particle to blame for a blow-up: the first non-finite one, else the fastest (the lowest
// index of equals): (global index, vx, vy, vz).
std::array<double, 4> culprit(const Dynamics& dyn) {
  // This rank's candidate: non-finite (0/1), index, |v|^2, vx, vy, vz.
  std::vector<double> mine{0.0, 0.0, -1.0, 0.0, 0.0, 0.0};
  for (std::size_t p = dyn.own_begin(); p < dyn.own_end(); ++p) {
    const double v2 = dyn.vx[p] * dyn.vx[p] + dyn.vy[p] * dyn.vy[p] + dyn.vz[p] * dyn.vz[p];
    const bool bad = !std::isfinite(v2) || !std::isfinite(dyn.x[p] + dyn.y[p] + dyn.z[p]);
    if (bad || v2 > mine[2]) {
      mine = {bad ? 1.0 : 0.0, static_cast<double>(p + dyn.offset()), v2, dyn.vx[p], dyn.vy[p], dyn.vz[p]};
      if (bad) break;
    }
  }
  std::vector<double> all = mine;
  if (const SlabPlan* s = dyn.slab()) s->comm->allgather(mine, all);
  // The serial scan over the ranks' candidates in rank order (= index order).
  const double* best = all.data();
  for (std::size_t r = 1; 6 * r < all.size(); ++r) {
    const double* c = all.data() + 6 * r;
    if (best[0] == 0.0 && (c[0] != 0.0 || c[2] > best[2])) best = c;
  }
  return {best[1], best[3], best[4], best[5]};
}

}  // namespace

RunResult simulate(const config::Case& c, const Packing& packing, const SampleHook& hook,
                   std::shared_ptr<SlabComm> comm, const ProgressHook& progress) {
  const Derived d = derive(c);
  std::optional<SlabPlan> plan;
  if (comm && comm->ranks() > 1) {
    if (hook) throw InputError(c.path + ": output.vtk_every: VTK snapshots are not written by a run split over MPI ranks");
    plan = plan_slab(packing, list_skin(packing), comm, c.path);
  }
  Dynamics dyn(packing, case_model(c.contact, c.crystal->density), d.dt, plan ? &*plan : nullptr);
  RunResult res;
  Traces& tr = res.traces;
  tr.nlayers = static_cast<std::size_t>(packing.layers);
  // Positions along z: the mean z of each layer's particles in the (relaxed) packing, from that
  // of the innermost driven layer. A relaxed polydisperse packing is not at the lattice's
  // (L - F + 1) l0 (crystal_poly2: 1.3e-5 m short at the top, a 2e-5 error in front speeds).
  {
    std::vector<double> z_sum(packing.layers, 0.0);
    std::vector<int> count(packing.layers, 0);
    for (std::size_t p = 0; p < packing.size(); ++p) {
      z_sum[packing.layer[p]] += packing.z[p];
      ++count[packing.layer[p]];
    }
    const int driven = packing.fixed_layers - 1;
    const double z_driven = z_sum[driven] / count[driven];
    for (int L = 0; L < packing.layers; ++L) tr.layer_z.push_back(z_sum[L] / count[L] - z_driven);
  }

  // Excitation at t = 0 (secs. 2.2 B, 3.1): a displacement step moves all bottom fixed layers
  // together; the velocity drive ("an initial velocity as a perturbation of the layer, without
  // controlling its displacement further on", sec. 3.1) frees the innermost one only, the layers
  // below it staying fixed as the wall that holds the prestress.
  // (By global index; `held`: the local indices of those this rank holds, owned or halo: every
  // rank moves its copies the same way.)
  const int first_source_layer =
      c.excitation.drive == config::Excitation::Drive::velocity ? packing.fixed_layers - 1 : 0;
  std::vector<std::size_t> source, held;
  for (std::size_t p = 0; p < packing.size(); ++p)
    if (packing.fixed[p] && packing.layer[p] < packing.fixed_layers && packing.layer[p] >= first_source_layer) {
      source.push_back(p);
      if (p >= dyn.offset() && p - dyn.offset() < dyn.size()) held.push_back(p - dyn.offset());
    }
  const bool p_mode = c.excitation.mode == config::Excitation::Mode::P;
  const double e_start = dyn.potential_energy();
  if (c.excitation.drive == config::Excitation::Drive::displacement) {
    const double step = c.excitation.amplitude * packing.d;  // a step of amplitude * d, held
    dyn.displace(held, p_mode ? 0.0 : step, 0.0, p_mode ? step : 0.0);
  } else {
    // Initial source velocity, no displacement control afterwards: the source is integrated.
    dyn.set_mobile(held, true);
    for (std::size_t p : held) (p_mode ? dyn.vz[p] : dyn.vx[p]) = c.excitation.amplitude;
    for (std::size_t p : source)  // the packing's masses: the same sum on every rank
      dyn.work_in += 0.5 * packing.mass[p] * c.excitation.amplitude * c.excitation.amplitude;
    // F(0) of the state (x(0), v(0)): the dashpots see the source's initial velocity, as in
    // LIGGGHTS' setup and the YADE driver's first step (before: F(0) of the source at rest).
    dyn.compute_forces_of_state();
  }
  const double budget = e_start + std::abs(dyn.work_in);

  {  // the series' final lengths (no copies as they grow)
    const std::size_t samples = static_cast<std::size_t>(d.steps / d.sample_every) + 1;
    if (!plan || plan->rank == 0)  // the rank that keeps the rows
      for (auto* f : {&tr.stress_zz, &tr.stress_zx, &tr.displacement_z, &tr.displacement_x, &tr.velocity_z,
                      &tr.velocity_x})
        f->reserve(samples * tr.nlayers);
    for (auto* f : {&tr.time, &tr.coordination, &tr.kinetic, &tr.potential, &tr.dissipated, &tr.work_in,
                    &tr.verlet_correction})
      f->reserve(samples);
  }
  sample(dyn, tr);
  if (hook) hook(dyn, 0);
  const double cpu0 = process_cpu_seconds();
  const double msg0 = comm ? comm->message_seconds : 0.0, msg_cpu0 = comm ? comm->message_cpu_seconds : 0.0;
  const auto t0 = std::chrono::steady_clock::now();
  PhaseClock clock(res.phases, t0);
  for (long s = 0; s < d.steps;) {
    const long k = std::min(d.sample_every - s % d.sample_every, d.steps - s);  // steps to the next sample
    s += k;
    const bool sampled = s % d.sample_every == 0;
    dyn.advance(k, sampled, &clock);  // only a sample reads the contact forces (layer stress)
    if (!sampled) continue;
    sample(dyn, tr);
    clock.lap(PhaseTimes::sample);
    if (progress) progress(s, d.steps);
    const double e = tr.kinetic.back() + tr.potential.back();
    // Energy can only leave (dashpots, friction); growth beyond the budget is an instability.
    if (!std::isfinite(e) || e > 1.5 * budget + 1e-30) {
      const auto [index, ux, uy, uz] = culprit(dyn);
      const auto p = static_cast<std::size_t>(index);
      std::ostringstream msg;
      msg << "crystal run unstable at step " << s << " (t = " << dyn.time << " s): E_kin + E_pot = " << e
          << " J against " << budget << " J available; particle " << p << " (layer " << packing.layer[p]
          << ") has velocity (" << ux << ", " << uy << ", " << uz << ") m/s";
      res.failed = true;
      res.error = msg.str();
      break;
    }
    clock.lap(PhaseTimes::other);
    if (hook) {
      hook(dyn, tr.samples() - 1);
      clock.lap(PhaseTimes::sample);
    }
  }
  res.seconds = std::chrono::duration<double>(clock.lap(PhaseTimes::other) - t0).count();
  res.steps = dyn.steps;
  res.rebuilds = dyn.rebuilds;
  {  // how the work split: every rank's times, to rank 0 (serial: the one process's)
    const std::vector<double> mine{res.seconds, plan ? comm->message_seconds - msg0 : 0.0, process_cpu_seconds() - cpu0,
                                   plan ? comm->message_cpu_seconds - msg_cpu0 : 0.0};
    std::vector<double> all = mine;
    if (plan) plan->comm->gather(mine, all);
    for (std::size_t r = 0; 4 * r < all.size(); ++r) {
      res.rank_seconds.push_back(all[4 * r]);
      res.rank_message_seconds.push_back(all[4 * r + 1]);
      res.rank_cpu_seconds.push_back(all[4 * r + 2]);
      res.rank_message_cpu_seconds.push_back(all[4 * r + 3]);
    }
  }
  return res;
}

analysis::CrystalTrace analysis_trace(const config::Case& c, const Packing& packing, const Traces& tr) {
  analysis::CrystalTrace t;
  t.time = tr.time;
  t.layer_z = tr.layer_z;
  t.nt = tr.samples();
  t.nlayers = tr.nlayers;
  t.l0 = packing.l0;
  t.fixed_layers = packing.fixed_layers;
  t.mode = c.excitation.mode == config::Excitation::Mode::S ? 'S' : 'P';
  t.mode_source = "case_toml";
  t.stress_zz = tr.stress_zz;
  t.stress_zx = tr.stress_zx;
  t.displacement_z = tr.displacement_z;
  t.displacement_x = tr.displacement_x;
  t.velocity_z = tr.velocity_z;
  t.velocity_x = tr.velocity_x;
  t.coordination = tr.coordination;
  return t;
}

namespace {
bool wants(const config::Case& c, const std::string& field) {
  if (c.output.fields.empty()) return true;
  for (const auto& f : c.output.fields)
    if (f == field) return true;
  return false;
}

// A dataset of the trace: its path and series, [nt, nlayers] or one-dimensional.
struct TraceField {
  std::string path;
  std::vector<double> Traces::*series;
  bool per_layer;
};

// The datasets of the case's trace but /system, in the file's order.
std::vector<TraceField> trace_fields(const config::Case& c) {
  std::vector<TraceField> out = {{"/time", &Traces::time, false}, {"/crystal/layer_z", &Traces::layer_z, false}};
  const std::pair<const char*, std::vector<double> Traces::*> fields[] = {
      {"layer_stress_zz", &Traces::stress_zz},         {"layer_stress_zx", &Traces::stress_zx},
      {"layer_displacement_z", &Traces::displacement_z}, {"layer_displacement_x", &Traces::displacement_x},
      {"layer_velocity_z", &Traces::velocity_z},       {"layer_velocity_x", &Traces::velocity_x}};
  for (const auto& [name, series] : fields)
    if (wants(c, name)) out.push_back({std::string("/crystal/") + name, series, true});
  if (wants(c, "coordination")) out.push_back({"/crystal/coordination", &Traces::coordination, false});
  if (wants(c, "energy"))
    for (const auto& [name, series] : {std::pair{"kinetic", &Traces::kinetic}, {"potential", &Traces::potential},
                                       {"dissipated", &Traces::dissipated}, {"work_in", &Traces::work_in},
                                       {"verlet_correction", &Traces::verlet_correction}})
      out.push_back({std::string("/energy/") + name, series, false});
  return out;
}

std::vector<std::size_t> shape_of(const TraceField& f, const Traces& t) {
  return f.per_layer ? std::vector<std::size_t>{t.samples(), t.nlayers} : std::vector<std::size_t>{(t.*f.series).size()};
}
}  // namespace

void write_trace(const config::Case& c, const Packing& p, const RunResult& r, io::H5Writer& w) {
  io::write_provenance(w);
  w.attr("/", "case_name", c.name);
  w.attr("/", "case_toml", c.toml_text);
  w.attr("/", "time_convention", std::string("synchronous"));
  // The contact-law conventions the crosscheck compares (data/SCHEMA.md §3).
  w.attr("/", "lever_arm", std::string(contact::lever_arm_name(c.contact.friction().lever_arm)));
  w.attr("/", "normal_tension", std::string(c.contact.friction().clip() ? "clip" : "allow"));
  w.attr("/", "coulomb_normal",
         std::string(c.contact.friction().magnitude() ? "magnitude" : "compressive"));
  w.attr("/", "contact_law", contact_law_name(c.contact));
  w.attr("/", "tangential_history", tangential_history_name(c.contact));
  w.attr("/", "rolling_lever", std::string(contact::rolling_lever_name(c.contact.rolling().rolling_lever)));
  w.attr("/", "rolling_history", std::string(contact::rolling_history_name(c.contact.rolling().rolling_history)));
  w.attr("/", "status", r.failed ? "failed: " + r.error : std::string("complete"));
  write_system(w, p, c.name, "/system");
  for (const auto& f : trace_fields(c)) w.write(f.path, r.traces.*f.series, shape_of(f, r.traces));
}

TraceSeries take_series(const config::Case& c, Traces&& t) {
  TraceSeries out;
  const auto fields = trace_fields(c);
  for (const auto& f : fields) out.datasets.push_back({f.path, shape_of(f, t), {}, {}});  // before /time moves
  for (std::size_t k = 0; k < fields.size(); ++k) out.datasets[k].values = std::move(t.*fields[k].series);
  return out;
}

}  // namespace granwave::crystal
