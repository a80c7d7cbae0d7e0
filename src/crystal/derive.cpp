// The numbers derived from a crystal case (crystal/derive.hpp): the law linearised at the static
// overlap, the time step and its stability limit, the prestress and eq. (10)'s FCC speeds; the
// contact network and lattice options of the theory.
#include "crystal/derive.hpp"

#include <algorithm>
#include <atomic>
#include <cmath>
#include <numbers>
#include <numeric>
#include <string>

#include "config/contact_laws.hpp"
#include "contact/linear_spring_dashpot.hpp"
#include "contact/tangential_spring.hpp"
#include "core/error.hpp"
#include "theory/stiffness.hpp"

namespace granwave::crystal {

ContactAt contact_at(const config::Case& c, double delta) {
  return contact_between(c, c.crystal->radius, c.crystal->radius, delta);
}

double linearisation_overlap(const config::Case& c, const Packing& pk) {
  return pk.from_file() ? 2.0 * c.crystal->radius * c.crystal->overlap : pk.delta;
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
  const ContactAt k0 = contact_at(c, linearisation_overlap(c, pk));
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

namespace {
std::atomic<long> g_derivations{0};

// lattice = "file": what derive() takes from the FCC's closed forms, from the imported packing's
// contact network instead (the state before the relaxation, z cut open, every contact the case's
// law at its own overlap): the stability bound with the largest per-particle coordination and the
// stiffest contact at its overlap plus the source's; sigma_0 = the Love-Weber sigma_zz,
// (1/V) sum f_n b_z^2/|b|; V_p and V_s from eq. (10) over the network (theory/stiffness.hpp),
// affine, V_s without kt as for the FCC.
void network_numbers(const config::Case& c, Derived& d) {
  const Packing pk = imported_packing(c);
  const auto contacts = list_contacts(pk, true);
  if (contacts.empty()) throw InputError(c.path + ": packing.file: the packing has no contacts (it is not jammed)");
  std::vector<int> coordination(pk.size(), 0);
  const double extra = d.delta_max - 2.0 * c.crystal->radius * c.crystal->overlap;  // the source's
  double kn = 0.0, kt = 0.0, gn = 0.0, gt = 0.0, szz = 0.0;
  std::vector<theory::ContactGeometry> geometry, frictionless;
  for (const PackingContact& q : contacts) {
    ++coordination[q.i];
    ++coordination[q.j];
    const ContactAt top = contact_between(c, pk.radius[q.i], pk.radius[q.j], q.overlap + extra);
    kn = std::max(kn, top.kn);
    kt = std::max(kt, top.kt);
    gn = std::max(gn, top.gamma_n);
    gt = std::max(gt, top.gamma_t);
    const ContactAt now = contact_between(c, pk.radius[q.i], pk.radius[q.j], q.overlap);
    const theory::Vec3 b(q.bx, q.by, q.bz);
    szz += now.f_n * q.bz * q.bz / b.norm();
    geometry.push_back({b, now.kn, now.kt, 1.0});
    frictionless.push_back({b, now.kn, 0.0, 1.0});
  }
  const double z = *std::max_element(coordination.begin(), coordination.end());
  const double m_min = *std::min_element(pk.mass.begin(), pk.mass.end());
  const double omega_max = std::sqrt(2.0 * z * (kn + 3.5 * kt) / m_min);
  const double zeta = z * (gn + gt) / (2.0 * m_min) / omega_max;
  d.dt_stable = 2.0 / omega_max * (std::sqrt(1.0 + zeta * zeta) - zeta);
  const double height = c.crystal->imported->box.length(2);
  const double volume = pk.box_x * pk.box_y * height;
  d.sigma_0 = szz / volume;
  const double rho = std::accumulate(pk.mass.begin(), pk.mass.end(), 0.0) / volume;
  d.v_p = std::sqrt(theory::stiffness_tensor(geometry, volume, true)(2, 2, 2, 2) / rho);
  d.v_s = std::sqrt(theory::stiffness_tensor(frictionless, volume, false)(2, 0, 2, 0) / rho);
  d.max_coordination = static_cast<int>(z);
}
}

long derivations() { return g_derivations.load(); }

Derived derive(const config::Case& c) {
  ++g_derivations;
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
  if (k.from_file()) {  // no lattice: the packing's own network
    network_numbers(c, d);
    d.steps = std::llround(c.integrator.t_end / d.dt);
    d.sample_every = c.output.interval > 0.0 ? std::max(1LL, std::llround(c.output.interval / d.dt)) : 1;
    return d;
  }
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

}  // namespace granwave::crystal
