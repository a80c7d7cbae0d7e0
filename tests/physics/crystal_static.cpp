// The prestressed crystal of seed 002 sec. 2.2: isotropic prestress, static equilibrium,
// coordination 12, invariance under periodic shifts and storage order; the energy audit.
#include <catch2/catch.hpp>
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <numeric>
#include <vector>

#include "../test_support.hpp"
#include "config/case.hpp"
#include "contact/hertz_mindlin_params.hpp"
#include "core/rng.hpp"
#include "crystal/dynamics.hpp"
#include "crystal/observers.hpp"
#include "crystal/packing.hpp"
#include "crystal/simulation.hpp"

using namespace granwave;

namespace {
config::Case load(const std::string& name) {
  return config::load_case(std::string(GRANWAVE_SOURCE_DIR) + "/data/cases/" + name + ".toml");
}
}  // namespace

TEST_CASE("prestress is isotropic: sigma_0 = 2 sqrt(2) k delta / d'^2 = 1.417e5 Pa", "[crystal][static]") {
  const config::Case c = load("crystal_p");
  const crystal::Packing p = crystal::make_packing(c);
  crystal::Dynamics dyn(p, c.contact, *c.integrator.dt);
  const double sigma_0 = 2 * std::sqrt(2.0) * 1e5 * p.delta / (p.d_prime * p.d_prime);
  CHECK(sigma_0 == Approx(1.417e5).epsilon(3e-4));
  std::vector<double> zz, zx, ps;
  crystal::layer_stress(dyn, zz, zx, &ps);
  for (int L = 2; L < 198; ++L) {  // free layers (fixed-fixed contacts are excluded in the end layers)
    CHECK(zz[L] == Approx(sigma_0).epsilon(1e-9));
    CHECK(std::abs(zx[L]) < 1e-9 * sigma_0);
  }
  for (std::size_t q = 0; q < p.size(); q += 97) {
    if (p.fixed[q]) continue;
    CHECK(ps[9 * q + 0] == Approx(sigma_0).epsilon(1e-9));  // xx
    CHECK(ps[9 * q + 4] == Approx(sigma_0).epsilon(1e-9));  // yy
    CHECK(ps[9 * q + 8] == Approx(sigma_0).epsilon(1e-9));  // zz
    CHECK(std::abs(ps[9 * q + 1]) < 1e-9 * sigma_0);
  }
  CHECK(crystal::coordination(dyn) == 12.0);
  // Unexcited, it stays static.
  const double e_pot = dyn.potential_energy();
  for (int s = 0; s < 1000; ++s) dyn.step();
  std::printf("static crystal after 1000 steps: E_kin/E_pot = %.3g\n", dyn.kinetic_energy() / e_pot);
  CHECK(dyn.kinetic_energy() / e_pot < 1e-12);
}

namespace {
// A disturbed copy of a packing (deterministic, 1e-8 m), with velocities and spins, so that
// normal, dashpot and tangential forces are all non-zero.
struct Disturbed {
  crystal::Packing p;
  std::vector<double> v, w;
};
Disturbed disturb(crystal::Packing p) {
  Disturbed d;
  const std::size_t n = p.size();
  d.v.resize(3 * n);
  d.w.resize(3 * n);
  for (std::size_t q = 0; q < n; ++q) {
    CounterRng rng(42, q);
    p.x[q] += 1e-8 * (2 * rng.uniform() - 1);
    p.y[q] += 1e-8 * (2 * rng.uniform() - 1);
    p.z[q] += 1e-8 * (2 * rng.uniform() - 1);
    for (int k = 0; k < 3; ++k) d.v[3 * q + k] = 1e-3 * (2 * rng.uniform() - 1);
    for (int k = 0; k < 3; ++k) d.w[3 * q + k] = 1.0 * (2 * rng.uniform() - 1);
  }
  d.p = std::move(p);
  return d;
}
crystal::Dynamics forces_of(const Disturbed& d, const contact::LawParams& cp) {
  crystal::Dynamics dyn(d.p, cp, 2e-7);
  for (std::size_t q = 0; q < d.p.size(); ++q) {
    dyn.vx[q] = d.v[3 * q], dyn.vy[q] = d.v[3 * q + 1], dyn.vz[q] = d.v[3 * q + 2];
    dyn.wx[q] = d.w[3 * q], dyn.wy[q] = d.w[3 * q + 1], dyn.wz[q] = d.w[3 * q + 2];
  }
  dyn.compute_forces();
  return dyn;
}
// crystal_small with sliding friction (kt = k, mu^s = 0.3 > mu^d = 0.2, a normal dashpot), and
// the laws that route the particle sums differently: the linear law with the radius arm and
// with the contact-point arm, and a damped Hertz-Mindlin law with stick-slip; `rolling`: the
// same three with rolling and torsion resistance (a row of couples more), rolling and twisting
// slips included, the linear radius arm without their dashpots, the others with.
struct RouteLaws {
  config::Case c;
  contact::LawParams radius, contact_point, hertz;
  std::vector<contact::LawParams> rolling;
};
RouteLaws route_laws() {
  RouteLaws r;
  r.c = load("crystal_small");
  r.c.contact.get<contact::LinearLudingParams>().kt = 1e5;
  r.c.contact.get<contact::LinearLudingParams>().gamma_n = 0.1;
  r.c.contact.friction().mu_static = 0.3;
  r.c.contact.friction().mu_dynamic = 0.2;
  r.radius = r.c.contact;
  r.radius.friction().lever_arm = config::LeverArm::radius;
  r.contact_point = r.c.contact;
  r.contact_point.friction().lever_arm = config::LeverArm::contact_point;
  contact::HertzMindlinCaseParams hertz;
  hertz.youngs_modulus = 63e9;
  hertz.poisson_ratio = 0.23;
  hertz.damping_ratio = 0.1;
  hertz.friction.mu_static = 0.3;
  hertz.friction.mu_dynamic = 0.2;
  hertz.tangential_history = contact::TangentialHistory::displacement_rescale;
  r.hertz = hertz;
  for (contact::LawParams cp : {r.radius, r.contact_point, r.hertz}) {
    contact::RollingTorsionKeys& k = *cp.rolling_keys();
    k.kr = k.ko = 5e4;
    k.mu_r = k.mu_o = 0.05;
    if (cp.find<contact::HertzMindlinCaseParams>() || cp.friction().lever_arm == config::LeverArm::contact_point)
      k.gamma_r = k.gamma_o = 0.01;
    r.rolling.push_back(cp);
  }
  return r;
}
// Every law of route_laws: the three, then the three with rolling and torsion.
std::vector<contact::LawParams> all_laws(const RouteLaws& r) {
  std::vector<contact::LawParams> laws{r.radius, r.contact_point, r.hertz};
  laws.insert(laws.end(), r.rolling.begin(), r.rolling.end());
  return laws;
}
// The packing without its last three (top-layer, fixed) particles: a count not a multiple of four
// when `whole`'s is.
crystal::Packing three_fewer(const crystal::Packing& whole) {
  crystal::Packing p = whole;
  for (auto* v : {&p.x, &p.y, &p.z, &p.radius, &p.mass, &p.inertia}) v->resize(v->size() - 3);
  p.layer.resize(p.layer.size() - 3);
  p.fixed.resize(p.fixed.size() - 3);
  return p;
}
// The disturbed velocities, and spins so fast that the surfaces slide past each other at ~0.3 m/s
// (contacts slip).
void set_sliding_motion(crystal::Dynamics& d, const Disturbed& base) {
  for (std::size_t q = 0; q < base.p.size(); ++q) {
    d.vx[q] = base.v[3 * q], d.vy[q] = base.v[3 * q + 1], d.vz[q] = base.v[3 * q + 2];
    d.wx[q] = 300 * base.w[3 * q], d.wy[q] = 300 * base.w[3 * q + 1], d.wz[q] = 300 * base.w[3 * q + 2];
  }
}
}  // namespace

TEST_CASE("same forces after a shift across the periodic faces and after reordering", "[crystal][static]") {
  config::Case c = load("crystal_small");
  c.crystal->cells = {4, 4, 20};
  c.contact.get<contact::LinearLudingParams>().kt = 1e5;
  c.contact.get<contact::LinearLudingParams>().gamma_n = 0.1;
  c.contact.get<contact::LinearLudingParams>().gamma_t = 0.05;
  const Disturbed base = disturb(crystal::make_packing(c));
  const crystal::Dynamics ref = forces_of(base, c.contact);
  const double f_scale = 1e5 * 2e-6;

  // Shift by 0.37 box in x and 0.81 box in y, wrapping particles back into the box.
  Disturbed shifted = base;
  for (std::size_t q = 0; q < base.p.size(); ++q) {
    shifted.p.x[q] = std::fmod(base.p.x[q] + 0.37 * base.p.box_x, base.p.box_x);
    shifted.p.y[q] = std::fmod(base.p.y[q] + 0.81 * base.p.box_y, base.p.box_y);
  }
  const crystal::Dynamics s = forces_of(shifted, c.contact);
  // Reverse the storage order.
  Disturbed reordered = base;
  const std::size_t n = base.p.size();
  auto rev = [n](auto& v, int k) {
    auto copy = v;
    for (std::size_t q = 0; q < n; ++q)
      for (int m = 0; m < k; ++m) v[k * q + m] = copy[k * (n - 1 - q) + m];
  };
  for (auto* v : {&reordered.p.x, &reordered.p.y, &reordered.p.z, &reordered.p.radius, &reordered.p.mass,
                  &reordered.p.inertia})
    rev(*v, 1);
  rev(reordered.p.layer, 1);
  rev(reordered.p.fixed, 1);
  rev(reordered.v, 3);
  rev(reordered.w, 3);
  const crystal::Dynamics r = forces_of(reordered, c.contact);
  double max_shift = 0.0, max_order = 0.0, max_f = 0.0, max_torque_diff = 0.0;
  for (std::size_t q = 0; q < n; ++q) {
    const std::size_t k = n - 1 - q;
    max_f = std::max({max_f, std::abs(ref.fx[q]), std::abs(ref.fz[q])});
    max_shift = std::max({max_shift, std::abs(s.fx[q] - ref.fx[q]), std::abs(s.fy[q] - ref.fy[q]),
                          std::abs(s.fz[q] - ref.fz[q])});
    max_order = std::max({max_order, std::abs(r.fx[k] - ref.fx[q]), std::abs(r.fy[k] - ref.fy[q]),
                          std::abs(r.fz[k] - ref.fz[q])});
    max_torque_diff = std::max({max_torque_diff, std::abs(s.tx[q] - ref.tx[q]), std::abs(r.tz[k] - ref.tz[q])});
  }
  std::printf("max |F| %.3g N; differences: shifted %.3g N, reordered %.3g N, torques %.3g N m\n", max_f, max_shift,
              max_order, max_torque_diff);
  CHECK(max_f > 1e-3 * f_scale);
  // Round-off of positions ~1e-3 m (ulp 2e-19) against overlaps of 2e-6 m: relative 1e-10.
  CHECK(max_shift < 1e-9 * f_scale);
  CHECK(max_order < 1e-9 * f_scale);
  CHECK(max_torque_diff < 1e-9 * f_scale * 1e-3);
}

TEST_CASE("results do not depend on the number of threads", "[crystal][static][route]") {
  // The threaded run must really use threads.
  test_support::require_openmp_threads(2, "thread invariance");
  config::Case c = load("crystal_small");
  c.contact.get<contact::LinearLudingParams>().kt = 1e5;
  c.contact.get<contact::LinearLudingParams>().gamma_n = 0.1;
  const Disturbed base = disturb(crystal::make_packing(c));
  // The linear law of the case, and a damped Hertz-Mindlin law with stick-slip (issue #14).
  contact::HertzMindlinCaseParams hertz_params;
  hertz_params.youngs_modulus = 63e9;
  hertz_params.poisson_ratio = 0.23;
  hertz_params.damping_ratio = 0.1;
  hertz_params.friction.mu_static = 0.5;
  hertz_params.friction.mu_dynamic = 0.4;
  hertz_params.tangential_history = contact::TangentialHistory::displacement_rescale;
  const contact::LawParams hertz = hertz_params;
  for (const contact::LawParams& cp : {c.contact, hertz}) {
    const auto model = crystal::case_model(cp, c.crystal->density);
    crystal::Dynamics serial(base.p, model, 2e-7), threaded(base.p, model, 2e-7);
    serial.parallel_min_particles = ~std::size_t{0};  // never threaded
    threaded.parallel_min_particles = 0;               // always (as many threads as OpenMP gives)
    for (auto* d : {&serial, &threaded}) {
      d->vz.assign(base.p.size(), 0.0);
      for (std::size_t q = 0; q < base.p.size(); ++q) d->vz[q] = base.v[3 * q + 2];
      for (int s = 0; s < 200; ++s) d->step();
    }
    CHECK(serial.x == threaded.x);
    CHECK(serial.z == threaded.z);
    CHECK(serial.wy == threaded.wy);
    CHECK(serial.dissipated_energy() == threaded.dissipated_energy());
    CHECK(serial.dissipated_energy() > 0.0);
  }
}

TEST_CASE("threaded contact sums of a law without torques equal one thread's bit for bit", "[crystal][static][route]") {
  // A law without torques scatters its forces into the particles' sums on threads too: each part
  // of the list into the particles it alone touches, the particles two parts share summed from the
  // stored forces after the parts join (ContactList::ThreadParts), and the finish joined to the
  // next drift runs on the threads. The order of every sum stays the one-thread order: positions,
  // velocities and forces agree to the last bit, for the linear law and frictionless Hertz.
  test_support::require_openmp_threads(2, "the threaded scatter");
  config::Case c = load("crystal_small");
  c.crystal->cells = {4, 4, 40};  // 640 particles, about 3 500 contacts: more than two blocks of the pass
  c.contact.get<contact::LinearLudingParams>().gamma_n = 0.1;
  contact::HertzMindlinCaseParams hertz;
  hertz.youngs_modulus = 63e9;
  hertz.poisson_ratio = 0.23;
  hertz.damping_ratio = 0.1;
  hertz.mindlin = false;
  const Disturbed base = disturb(crystal::make_packing(c));
  for (const contact::LawParams& cp : {c.contact, contact::LawParams(hertz)}) {
    const auto model = crystal::case_model(cp, c.crystal->density);
    crystal::Dynamics one(base.p, model, 2e-7), two(base.p, model, 2e-7);
    one.parallel_min_particles = ~std::size_t{0};  // one thread
    two.parallel_min_particles = 0;                // as many threads as OpenMP gives
    for (auto* d : {&one, &two}) {
      for (std::size_t q = 0; q < base.p.size(); ++q)
        d->vx[q] = base.v[3 * q], d->vy[q] = base.v[3 * q + 1], d->vz[q] = base.v[3 * q + 2];
      d->advance(150);  // the finish fused with the next drift
      d->advance(1);    // and not
    }
    CHECK(!one.threaded());
    CHECK(two.threaded());
    // The list is cut into parts that share some particles (else the test shows nothing).
    const auto& split = two.contacts.thread_parts(two.size(), crystal::Dynamics::threads_available(), 1024);
    CHECK(split.parts >= 2);
    CHECK(!split.shared_particles.empty());
    CHECK(one.rebuilds == two.rebuilds);
    for (auto f : {&crystal::Dynamics::fx, &crystal::Dynamics::fy, &crystal::Dynamics::fz, &crystal::Dynamics::x,
                   &crystal::Dynamics::y, &crystal::Dynamics::z, &crystal::Dynamics::vx, &crystal::Dynamics::vz})
      CHECK(one.*f == two.*f);
    CHECK(one.contacts.f_z == two.contacts.f_z);
    CHECK(one.dissipated_energy() == two.dissipated_energy());
    CHECK(one.dissipated_energy() > 0.0);
  }
}

TEST_CASE("threaded contact sums of a law with torques equal one thread's bit for bit", "[crystal][static][route]") {
  // A law with torques adds each contact's force and n x f^t (and its couple) straight into
  // per-particle rows (crystal/kernel.hpp's scatter); threaded, each part of the list into the
  // particles it alone touches, the particles two parts share summed from the stored values after
  // the parts join. Both add in the same order: every force, torque and position agrees to the
  // last bit, for both lever arms, a sliding law (deferred contacts), Hertz-Mindlin and the rolling
  // and torsion springs; and then a sample's observers. Needs OpenMP with two threads.
  test_support::require_openmp_threads(2, "the threaded scatter");
  const RouteLaws r = route_laws();
  config::Case c = r.c;
  c.crystal->cells = {4, 4, 40};  // about 3 500 contacts: parts that share particles
  const Disturbed base = disturb(crystal::make_packing(c));
  for (const contact::LawParams& cp : all_laws(r)) {
    const auto model = crystal::case_model(cp, c.crystal->density);
    crystal::Dynamics one(base.p, model, 2e-7), two(base.p, model, 2e-7);
    one.parallel_min_particles = ~std::size_t{0};  // one thread: the scatter
    two.parallel_min_particles = 0;                // threaded: the parts and the shared sums
    for (auto* d : {&one, &two}) {
      set_sliding_motion(*d, base);
      // the scatter does not need the contact forces; the last step stores them
      for (int s = 0; s < 100; ++s) d->step(s == 99);
    }
    CHECK(!one.threaded());  // the routes really differ
    CHECK(two.threaded());
    CHECK(!two.contacts.thread_parts(two.size(), crystal::Dynamics::threads_available(), 1024).shared_particles.empty());
    for (auto f : {&crystal::Dynamics::fx, &crystal::Dynamics::fy, &crystal::Dynamics::fz, &crystal::Dynamics::tx,
                   &crystal::Dynamics::ty, &crystal::Dynamics::tz, &crystal::Dynamics::x, &crystal::Dynamics::z,
                   &crystal::Dynamics::vy, &crystal::Dynamics::wx, &crystal::Dynamics::wz})
      CHECK(one.*f == two.*f);
    CHECK(one.contacts.f_x == two.contacts.f_x);
    CHECK(one.contacts.f_z == two.contacts.f_z);
    CHECK(one.dissipated_energy() == two.dissipated_energy());
    CHECK(one.dissipated_energy() > 0.0);
    // A sample's observers: threaded, each layer's sums on one thread (over_layer_runs), the same
    // bits; the layer stress from the end arms the pass stored and from those it makes itself.
    for (bool stored : {true, false}) {
      std::vector<double> zz1, zx1, zz2, zx2;
      one.end_arms_stored = two.end_arms_stored = stored && one.end_arms_stored && two.end_arms_stored;
      crystal::layer_stress(one, zz1, zx1);
      crystal::layer_stress(two, zz2, zx2);
      CHECK(zz1 == zz2);
      CHECK(zx1 == zx2);
      CHECK(std::count(zz1.begin(), zz1.end(), 0.0) < static_cast<std::ptrdiff_t>(zz1.size()));
    }
    const std::size_t nl = static_cast<std::size_t>(base.p.layers);
    std::vector<double> motion1(4 * nl), motion2(4 * nl);
    double* out1[4] = {&motion1[0], &motion1[nl], &motion1[2 * nl], &motion1[3 * nl]};
    double* out2[4] = {&motion2[0], &motion2[nl], &motion2[2 * nl], &motion2[3 * nl]};
    crystal::sample_layer_motion(one, out1);
    crystal::sample_layer_motion(two, out2);
    CHECK(motion1 == motion2);
    const crystal::Dynamics::Energies e1 = one.energies(), e2 = two.energies();
    CHECK(e1.kinetic == e2.kinetic);
    CHECK(e1.potential == e2.potential);
    CHECK(e1.dissipated == e2.dissipated);
    CHECK(e1.verlet_correction == e2.verlet_correction);
    CHECK(e1.potential > 0.0);
    // Some contacts slide (deferred to the exact sweep): column 3 of both laws' history is the
    // stick/slip flag (after the spring's three components).
    const double* flag = one.contacts.history_column(3);
    CHECK(std::count(flag, flag + one.contacts.size(), 1.0) > 0);
    if (cp.rolling().kr > 0.0) {  // the rolling springs (the four columns after the base law's) are stretched
      const double* xi_r = one.contacts.history_column(one.contacts.history_columns - 4);
      CHECK(std::count(xi_r, xi_r + one.contacts.size(), 0.0) < static_cast<std::ptrdiff_t>(one.contacts.size()));
    }
  }
}

TEST_CASE("advance(k) equals k steps bit for bit (second half kick fused with the next drift)", "[crystal][static][route]") {
  // On one thread Dynamics::advance finishes each step's forces and kicks in the same pass as the
  // next step's first half kick and drift, four particles at a time (the last few through the
  // two passes as they are). Every state and force must equal k calls of step() to the last bit:
  // all five row layouts of the sums (no torques; radius arm; contact-point arm; either with the
  // couples' row), a sliding law, Hertz-Mindlin, and a crystal whose particle count is not a
  // multiple of four.
  const RouteLaws r = route_laws();
  const config::Case& c = r.c;
  contact::LawParams frictionless = c.contact;
  frictionless.set_number("kt", 0.0);
  const crystal::Packing whole = crystal::make_packing(c);
  const crystal::Packing short_of_three = three_fewer(whole);  // n % 4 = 1
  REQUIRE(whole.size() % 4 == 0);
  REQUIRE(short_of_three.size() % 4 == 1);
  REQUIRE(short_of_three.fixed.back() == 1);
  for (const crystal::Packing* packing : {&whole, static_cast<const crystal::Packing*>(&short_of_three)}) {
    const Disturbed base = disturb(*packing);
    std::vector<contact::LawParams> laws{frictionless};
    for (const contact::LawParams& cp : all_laws(r)) laws.push_back(cp);
    for (const contact::LawParams& cp : laws) {
      const auto model = crystal::case_model(cp, c.crystal->density);
      crystal::Dynamics stepped(base.p, model, 2e-7), advanced(base.p, model, 2e-7);
      for (auto* d : {&stepped, &advanced}) {
        d->parallel_min_particles = ~std::size_t{0};  // one thread: the fused route
        set_sliding_motion(*d, base);
      }
      for (int s = 0; s < 60; ++s) stepped.step();
      advanced.advance(1);
      advanced.advance(59);
      for (auto f : {&crystal::Dynamics::fx, &crystal::Dynamics::fy, &crystal::Dynamics::fz, &crystal::Dynamics::tx,
                     &crystal::Dynamics::ty, &crystal::Dynamics::tz, &crystal::Dynamics::x, &crystal::Dynamics::y,
                     &crystal::Dynamics::z, &crystal::Dynamics::vx, &crystal::Dynamics::vz, &crystal::Dynamics::wx,
                     &crystal::Dynamics::wy})
        CHECK(stepped.*f == advanced.*f);
      CHECK(stepped.contacts.f_x == advanced.contacts.f_x);
      CHECK(stepped.contacts.delta == advanced.contacts.delta);
      CHECK(stepped.steps == advanced.steps);
      CHECK(stepped.time == advanced.time);
      CHECK(stepped.dissipated_energy() == advanced.dissipated_energy());
      CHECK(stepped.kinetic_energy() > 0.0);
    }
  }
}

TEST_CASE("the gather rows as the state within an advance and the drift behind the contact pass give the bits of the arrays",
          "[crystal][static][route]") {
  // Regression (route against route). From Dynamics::state_in_rows_min_particles on, the fused
  // particle pass of an advance reads x, v and w from the gather rows and writes only the rows; the
  // arrays are made again before the list's upkeep and the advance's last step. With the rows the
  // state, the next step's finish, kick and drift run behind the one-thread contact pass
  // (Dynamics::behind_batch particles at a time, once their sums are whole). Lowered to 0 and to
  // batches of 4 particles on a small crystal (and on one whose count is not a multiple of four, its
  // tail in the arrays), with the particles fast enough to relist and rebuild within an advance:
  // every state, force, layer stress and energy agrees with the arrays' route to the last bit, for
  // every law whose contact pass reads the rows.
  const RouteLaws r = route_laws();
  const crystal::Packing whole = crystal::make_packing(r.c);
  const crystal::Packing short_of_three = three_fewer(whole);  // n % 4 = 1
  for (const crystal::Packing* packing : {&whole, static_cast<const crystal::Packing*>(&short_of_three)}) {
    const Disturbed base = disturb(*packing);
    for (const contact::LawParams& cp : all_laws(r)) {
      const auto model = crystal::case_model(cp, r.c.crystal->density);
      crystal::Dynamics arrays(base.p, model, 2e-7), in_rows(base.p, model, 2e-7), behind(base.p, model, 2e-7);
      crystal::Dynamics* routes[] = {&arrays, &in_rows, &behind};
      arrays.state_in_rows_min_particles = ~std::size_t{0};
      in_rows.state_in_rows_min_particles = behind.state_in_rows_min_particles = 0;
      in_rows.behind_batch = 0;  // the drift after the pass
      behind.behind_batch = 4;   // a group of four at a time
      std::vector<double> zz[3], zx[3];
      for (int route = 0; route < 3; ++route) {
        crystal::Dynamics& d = *routes[route];
        d.parallel_min_particles = ~std::size_t{0};  // one thread: the fused route
        set_sliding_motion(d, base);
        for (std::size_t q = 0; q < base.p.size(); ++q) d.vz[q] *= 1e4;  // ~10 m/s along z: the lists move
        for (int k = 0; k < 4; ++k) d.advance(25);  // fused steps, each 25th stores the forces (a sample)
        crystal::layer_stress(d, zz[route], zx[route]);
      }
      CHECK(!arrays.state_in_rows());  // the routes really differ
      CHECK((in_rows.state_in_rows() && !in_rows.finishes_behind()));
      CHECK(behind.finishes_behind());
      // the linear laws' soft springs let the particles travel: relists and rebuilds within advances
      if (!cp.find<contact::HertzMindlinCaseParams>()) CHECK(in_rows.relists + in_rows.rebuilds > 10);
      using D = crystal::Dynamics;
      for (const D* d : {&in_rows, &behind}) {
        CHECK(d->relists == arrays.relists);
        CHECK(d->rebuilds == arrays.rebuilds);
        for (auto f : {&D::fx, &D::fy, &D::fz, &D::tx, &D::ty, &D::tz, &D::x, &D::y, &D::z, &D::vx, &D::vy, &D::vz,
                       &D::wx, &D::wy, &D::wz})
          CHECK(arrays.*f == d->*f);
        CHECK(arrays.contacts.f_x == d->contacts.f_x);
        CHECK(arrays.contacts.f_z == d->contacts.f_z);
        CHECK(arrays.contacts.delta == d->contacts.delta);
        CHECK(arrays.potential_energy() == d->potential_energy());
        CHECK(arrays.dissipated_energy() == d->dissipated_energy());
      }
      CHECK((zz[0] == zz[1] && zx[0] == zx[1] && zz[0] == zz[2] && zx[0] == zx[2]));
      CHECK(arrays.dissipated_energy() > 0.0);
    }
  }
}

TEST_CASE("stores past the caches (a crystal beyond the L3) give the same bits as plain stores",
          "[crystal][static][route]") {
  // From Dynamics::stream_min_particles on, the kick and drift write the gather rows, and a
  // sampled step's contact pass the forces and end arms, with non-temporal stores. The same values
  // land in the same places: here the switch is lowered to 0 on a small crystal and every state,
  // force, layer stress and energy agrees with plain stores to the last bit, for both lever arms,
  // Hertz-Mindlin and rolling with torsion (the laws whose contact pass reads the rows).
  const RouteLaws r = route_laws();
  const Disturbed base = disturb(crystal::make_packing(r.c));
  for (const contact::LawParams& cp : all_laws(r)) {
    const auto model = crystal::case_model(cp, r.c.crystal->density);
    crystal::Dynamics plain(base.p, model, 2e-7), streamed(base.p, model, 2e-7);
    plain.stream_min_particles = ~std::size_t{0};
    streamed.stream_min_particles = 0;
    std::vector<double> zz[2], zx[2];
    for (auto* d : {&plain, &streamed}) {
      d->parallel_min_particles = ~std::size_t{0};  // one thread: the route that writes the rows
      set_sliding_motion(*d, base);
      for (int k = 0; k < 4; ++k) d->advance(25);  // fused steps, each 25th stores the forces (a sample)
      const int route = d == &plain ? 0 : 1;
      crystal::layer_stress(*d, zz[route], zx[route]);  // from the end arms the last pass stored
    }
    CHECK(!plain.streams());  // the routes really differ
    CHECK(streamed.streams());
    CHECK(streamed.end_arms_stored);
    for (auto f : {&crystal::Dynamics::fx, &crystal::Dynamics::fz, &crystal::Dynamics::tx, &crystal::Dynamics::ty,
                   &crystal::Dynamics::x, &crystal::Dynamics::y, &crystal::Dynamics::z, &crystal::Dynamics::vx,
                   &crystal::Dynamics::vz, &crystal::Dynamics::wx, &crystal::Dynamics::wy, &crystal::Dynamics::wz})
      CHECK(plain.*f == streamed.*f);
    CHECK(plain.gather_rows == streamed.gather_rows);
    CHECK(plain.contacts.f_x == streamed.contacts.f_x);
    CHECK(plain.contacts.f_y == streamed.contacts.f_y);
    CHECK(plain.contacts.f_z == streamed.contacts.f_z);
    CHECK(plain.end_arms == streamed.end_arms);
    CHECK(zz[0] == zz[1]);
    CHECK(zx[0] == zx[1]);
    CHECK(plain.potential_energy() == streamed.potential_energy());
    CHECK(plain.dissipated_energy() == streamed.dissipated_energy());
    CHECK(plain.dissipated_energy() > 0.0);
  }
}
