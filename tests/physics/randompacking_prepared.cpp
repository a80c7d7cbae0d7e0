// A random packing prepared at a pressure (crystal.lattice = "random", data/cases/random_small.toml:
// 300 monodisperse spheres, frictionless, a linear law, 1 kPa): the prepared periodic packing holds
// the target pressure and is static by both criteria, recomputed here from its centres; its solid
// fraction and coordination are those of random close packing; cut open and relaxed it stands still.
#include <catch2/catch.hpp>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <string>
#include <vector>

#include "config/contact_laws.hpp"
#include "config/case.hpp"
#include "crystal/derive.hpp"
#include "crystal/dynamics.hpp"
#include "crystal/packing.hpp"
#include "io/h5.hpp"
#include "packing/contacts.hpp"

using namespace granwave;
using namespace granwave::crystal;

namespace {
const config::Case& random_case() {
  static const config::Case c = config::load_case(std::string(GRANWAVE_SOURCE_DIR) + "/data/cases/random_small.toml");
  return c;
}
const Packing& relaxed() {
  static const Packing p = make_packing(random_case());
  return p;
}
}  // namespace

TEST_CASE("random packing: the prepared packing holds the target pressure and is static", "[physics][random]") {
  const config::Case& c = random_case();
  const packing::Packing& pk = *c.crystal->imported;
  const packing::RandomSpec& spec = *c.crystal->random;
  const config::ContactLawInfo& law = config::law_of(c.contact);
  // Love-Weber from the stored centres, under the case's law: p = (1/3V) sum f |b|; the net force
  // on every particle from the same contacts (the static check, independent of the compression's).
  std::vector<double> net(3 * pk.particles.size(), 0.0);
  double virial = 0.0, f_sum = 0.0;
  const auto touching = packing::touching_pairs(pk);
  REQUIRE(!touching.empty());
  for (const packing::Touch& t : touching) {
    const auto& pi = pk.particles[t.i];
    const auto& pj = pk.particles[t.j];
    double b[3] = {pj.centre.x() - pi.centre.x(), pj.centre.y() - pi.centre.y(), pj.centre.z() - pi.centre.z()};
    for (int d = 0; d < 3; ++d) b[d] -= pk.box.length(d) * std::round(b[d] / pk.box.length(d));
    const double r = std::sqrt(b[0] * b[0] + b[1] * b[1] + b[2] * b[2]);
    const double f = law.at(c.contact, c.crystal->density, pi.radius, pj.radius, t.overlap).f_n;
    for (int d = 0; d < 3; ++d) net[3 * t.i + d] -= f * b[d] / r, net[3 * t.j + d] += f * b[d] / r;
    virial += f * r;
    f_sum += f;
  }
  const double p = virial / (3.0 * pk.box.volume());
  double worst = 0.0;
  for (std::size_t q = 0; q < pk.particles.size(); ++q) worst = std::max(worst, std::hypot(net[3 * q], net[3 * q + 1], net[3 * q + 2]));
  const double unbalanced = worst / (f_sum / touching.size());
  const packing::Preparation& prep = *c.crystal->preparation;
  INFO("p = " << p << " Pa (recorded " << prep.pressure << "), unbalanced " << unbalanced << " (recorded "
              << prep.unbalanced_force << "), E_kin/E_pot " << prep.kinetic_ratio << ", " << prep.steps << " steps");
  CHECK(std::abs(p / spec.pressure - 1.0) <= spec.pressure_tolerance);
  CHECK(unbalanced <= spec.unbalanced_force);
  CHECK(prep.kinetic_ratio <= spec.kinetic_ratio);  // velocities are not stored: the compression's own number
  CHECK(prep.pressure == Approx(p).epsilon(1e-9));
}

TEST_CASE("random packing: frictionless monodisperse, the solid fraction and coordination of random close packing",
          "[physics][random]") {
  const packing::Preparation& prep = *random_case().crystal->preparation;
  const std::size_t n = random_case().crystal->imported->particles.size();
  INFO("Phi " << prep.solid_fraction << ", Z " << prep.coordination << ", z* " << prep.coordination_backbone << ", rattlers "
              << prep.rattlers);
  // Frictionless spheres compressed fast jam at random close packing: Phi = 0.639 for N >= 4000
  // (Agnolin & Roux, PRE 76, 061302 (2007)); O'Hern et al., PRE 68, 011306 (2003) find the jamming
  // fraction's spread over samples ~ 0.2 N^-0.55 (about 0.01 at N = 300): a window of +- 0.02.
  CHECK(prep.solid_fraction > 0.619);
  CHECK(prep.solid_fraction < 0.659);
  // Isostatic: a rigid frictionless backbone has z* >= 2 d = 6 (less 6/N for the box's modes), and
  // at this overlap (~ 8e-4 d) O'Hern's z - 6 ~ 3.6 (Phi - Phi_J)^(1/2) stays well below 1.
  CHECK(prep.coordination_backbone >= 6.0 - 6.0 / static_cast<double>(n));
  CHECK(prep.coordination_backbone < 7.0);
  CHECK(prep.rattlers < static_cast<long>(0.05 * n));  // Agnolin & Roux: ~1.3 % rattlers, frictionless
}

TEST_CASE("random packing: cut open and relaxed, a quiescent run stays still", "[physics][random]") {
  const config::Case& c = random_case();
  const Packing& p = relaxed();
  REQUIRE(p.generator == "random");
  REQUIRE(p.relaxed);
  CHECK(p.relax_ratio < c.crystal->relax_tolerance);
  const Derived d = derive(c);
  Dynamics dyn(p, case_model(c.contact, c.crystal->density), d.dt);
  // The bound of the file packing's test (filepacking_wave.cpp): 1e-3 of a step's velocity scale.
  const double bound = 1e-3 * c.excitation.amplitude * p.d * d.omega;
  double v_max = 0.0;
  for (int block = 0; block < 10; ++block) {
    dyn.advance(100, false);
    for (std::size_t q = 0; q < dyn.size(); ++q)
      v_max = std::max(v_max, std::sqrt(dyn.vx[q] * dyn.vx[q] + dyn.vy[q] * dyn.vy[q] + dyn.vz[q] * dyn.vz[q]));
  }
  INFO("largest speed over 1000 steps: " << v_max << " m/s; bound " << bound << " m/s");
  CHECK(v_max < bound);
}

TEST_CASE("random packing: the system file carries the generator and the preparation's residuals", "[physics][random]") {
  const Packing& p = relaxed();
  const std::string path = (std::filesystem::temp_directory_path() / "granwave_random_system.h5").string();
  {
    io::H5Writer w(path);
    write_system(w, p, "random_small");
    w.commit();
  }
  const Packing back = read_system(path);
  std::filesystem::remove(path);
  CHECK(back.generator == "random");
  CHECK(back.seed == random_case().crystal->random->seed);
  CHECK(back.size() == p.size());
  CHECK(back.z == p.z);
  const packing::Preparation& a = p.preparation;
  const packing::Preparation& b = back.preparation;
  CHECK(b.steps == a.steps);
  CHECK(b.pressure == a.pressure);
  CHECK(b.kinetic_ratio == a.kinetic_ratio);
  CHECK(b.unbalanced_force == a.unbalanced_force);
  CHECK(b.solid_fraction == a.solid_fraction);
  CHECK(b.coordination_backbone == a.coordination_backbone);
  CHECK(b.rattlers == a.rattlers);
  CHECK(a.steps > 0);
}
