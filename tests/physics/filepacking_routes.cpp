// Routes through a disordered packing (data/cases/packing_lammps.toml): the one-thread contact pass
// leaves out the listed pairs that are apart (crystal/kernel_apart.hpp); the threaded route
// evaluates every listed pair. Both must give the same bits while contacts open and close.
#include <catch2/catch.hpp>

#include <cmath>
#include <string>
#include <vector>

#include "../test_support.hpp"
#include "config/case.hpp"
#include "contact/hertz_mindlin_params.hpp"
#include "core/rng.hpp"
#include "crystal/derive.hpp"
#include "crystal/dynamics.hpp"
#include "crystal/packing.hpp"
#include "crystal/simulation.hpp"

using namespace granwave;

TEST_CASE("packing from LAMMPS: leaving out the pairs apart changes no bit (one thread against threads)",
          "[physics][packing][route]") {
  test_support::require_openmp_threads(2, "the threaded route");
  config::Case c = config::load_case(std::string(GRANWAVE_SOURCE_DIR) + "/data/cases/packing_lammps.toml");
  const crystal::Packing p = crystal::make_packing(c);
  const double dt = crystal::derive(c).dt, kn = c.contact.get<contact::LinearLudingParams>().kn;
  // Friction with the contact-point arm and rolling and torsion springs (couples, three rows of sums).
  contact::LawParams luding = c.contact;
  auto& lp = luding.get<contact::LinearLudingParams>();
  lp.kt = kn, lp.gamma_n = 0.05;
  luding.friction().mu_static = 0.3, luding.friction().mu_dynamic = 0.2;
  luding.friction().lever_arm = config::LeverArm::contact_point;
  contact::RollingTorsionKeys& rk = *luding.rolling_keys();
  rk.kr = rk.ko = 0.5 * kn, rk.mu_r = rk.mu_o = 0.05, rk.gamma_r = rk.gamma_o = 0.01;
  // Hertz-Mindlin with sliding, as stiff at the packing's mean overlap as the linear law
  // (k_n = 2 E* sqrt(R* delta) = kn), so that the case's time step stays stable.
  const double r_mean = c.crystal->radius, overlap = c.crystal->overlap * 2.0 * r_mean;
  contact::HertzMindlinCaseParams hertz;
  hertz.poisson_ratio = 0.23;
  hertz.youngs_modulus = kn / (2.0 * std::sqrt(0.5 * r_mean * overlap)) * 2.0 * (1.0 - 0.23 * 0.23);
  hertz.damping_ratio = 0.1;
  hertz.friction.mu_static = 0.3, hertz.friction.mu_dynamic = 0.2;
  // Random velocities that move a particle by its mean overlap in 10 steps: contacts open and close,
  // and particles leave the skin (the list is built again).
  const double speed = overlap / (10.0 * dt);
  for (const contact::LawParams& cp : {luding, contact::LawParams(hertz)}) {
    const auto model = crystal::case_model(cp, c.crystal->density);
    crystal::Dynamics one(p, model, dt), two(p, model, dt);
    one.parallel_min_particles = ~std::size_t{0};  // one thread: the pairs apart left out
    two.parallel_min_particles = 0;                // threads: every listed pair evaluated
    for (auto* d : {&one, &two}) {
      for (std::size_t q = 0; q < p.size(); ++q) {
        CounterRng rng(7, q);
        d->vx[q] = speed * (2 * rng.uniform() - 1), d->vy[q] = speed * (2 * rng.uniform() - 1);
        d->vz[q] = speed * (2 * rng.uniform() - 1), d->wx[q] = speed / r_mean * (2 * rng.uniform() - 1);
      }
      d->advance(299, false);
      d->advance(1);  // forces stored
    }
    CHECK(!one.threaded());
    CHECK(two.threaded());
    CHECK(one.contacts.apart_lanes);  // the route under test was taken
    std::size_t apart = 0, touching = 0;
    for (double delta : one.contacts.delta) (delta > 0.0 ? touching : apart) += 1;
    INFO("listed pairs: " << touching << " touching, " << apart << " apart; rebuilds " << one.rebuilds);
    CHECK(16 * apart >= one.contacts.size());
    CHECK(one.rebuilds == two.rebuilds);
    CHECK(one.rebuilds > 1);  // the particles left the skin: the list was built again
    for (auto f : {&crystal::Dynamics::x, &crystal::Dynamics::z, &crystal::Dynamics::vx, &crystal::Dynamics::vz,
                   &crystal::Dynamics::wx, &crystal::Dynamics::wy, &crystal::Dynamics::fx, &crystal::Dynamics::fz,
                   &crystal::Dynamics::ty})
      CHECK(one.*f == two.*f);
    CHECK(one.contacts.f_x == two.contacts.f_x);
    CHECK(one.contacts.delta == two.contacts.delta);
    CHECK(one.contacts.history == two.contacts.history);
    CHECK(one.dissipated_energy() == two.dissipated_energy());
    CHECK(one.dissipated_energy() > 0.0);
  }
}
