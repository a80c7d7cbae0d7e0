// The one-component spring of contact/tangential_spring.hpp (the torsion's) against the Vec3 routines
// on (x, 0, 0), which the torsion ran on before: the same bits for the test force, the stick-slip
// decision, the Coulomb cap, the spring kept, the slip and the dashpot's losses, over random inputs
// (zero, subnormal and huge values, zero stiffness or dashpot, sliding and sticking, either Coulomb normal).
#include <catch2/catch.hpp>
#include <bit>
#include <cmath>
#include <cstdint>
#include <limits>
#include <random>

#include "contact/tangential_spring.hpp"

using namespace granwave;
using contact::Vec3;

namespace {
// The same bits; of a NaN, only that it is one: IEEE 754 leaves open which NaN an operation on two
// NaNs returns, and x86 returns its first operand's, whose place the compiler picks (an input NaN
// times an overflow's inf * 0 came out +NaN in one form, -NaN in the other).
bool same(double a, double b) {
  return std::bit_cast<std::uint64_t>(a) == std::bit_cast<std::uint64_t>(b) || (std::isnan(a) && std::isnan(b));
}

// A value of random sign over many decades, sometimes a special one (+-0, a subnormal, huge, inf, NaN).
double any_value(std::mt19937_64& g, bool specials) {
  std::uniform_int_distribution<int> pick(0, 19);
  std::uniform_real_distribution<double> decade(-12.0, 12.0);
  const double sign = (g() & 1) ? -1.0 : 1.0;
  switch (specials ? pick(g) : 19) {
    case 0: return 0.0;
    case 1: return -0.0;
    case 2: return sign * 3e-320;  // subnormal
    case 3: return sign * 1e-170;  // its square underflows
    case 4: return sign * 1e170;   // its square overflows
    case 5: return sign * std::numeric_limits<double>::infinity();
    case 6: return std::numeric_limits<double>::quiet_NaN();
    default: return sign * std::pow(10.0, decade(g));
  }
}
// A stiffness, a dashpot or a friction coefficient: 0 a quarter of the time, else positive.
double coefficient(std::mt19937_64& g, double lo, double hi) {
  if (g() % 4 == 0) return 0.0;
  std::uniform_real_distribution<double> decade(std::log10(lo), std::log10(hi));
  return std::pow(10.0, decade(g));
}

struct Tally {
  int slid = 0, stuck = 0, zero_k = 0;
};

template <bool Dashpot>
void compare(std::mt19937_64& g, Tally& tally) {
  contact::TangentialSpringParams p;
  p.kt = coefficient(g, 1e-3, 1e9);
  p.gamma_t = Dashpot ? coefficient(g, 1e-6, 1e3) : 0.0;
  p.mu_dynamic = g() % 8 == 0 ? HUGE_VAL : coefficient(g, 1e-3, 2.0);
  p.mu_static = g() % 2 ? p.mu_dynamic : p.mu_dynamic * 1.5;
  p.coulomb_on_magnitude = g() & 1;
  const bool specials = g() % 4 == 0;
  const double xi = any_value(g, specials), v = any_value(g, specials), dt = 2e-7;
  // A normal force near the test force's limit half the time (the cap then binds or nearly), else any.
  double f_n = any_value(g, specials);
  if (g() & 1) {
    std::uniform_real_distribution<double> ratio(0.3, 3.0);
    const double test = std::abs(p.kt * xi + p.gamma_t * v);
    f_n = ((g() % 8 == 0) ? -1.0 : 1.0) * ratio(g) * test / (p.mu_dynamic > 0.0 ? p.mu_dynamic : 1.0);
  }
  const bool was_sliding = g() & 1;
  const Vec3 xi3(xi, 0.0, 0.0), v3(v, 0.0, 0.0);

  const contact::TangentialTest t3 = contact::tangential_test<Dashpot>(p, xi3, v3, f_n, was_sliding);
  const contact::ScalarTest t1 = contact::tangential_test<Dashpot>(p, xi, v, f_n, was_sliding);
  REQUIRE(same(t1.force, t3.force.x()));
  REQUIRE(same(t1.magnitude2, t3.magnitude2));
  REQUIRE(same(t1.f_dynamic, t3.f_dynamic));
  REQUIRE(t1.sliding == t3.sliding);
  // The vectorised evaluation's loss of a sticking contact.
  REQUIRE(same(contact::spring_dashpot_loss<Dashpot>(p, t1.force, v, dt, 0.0),
               contact::spring_dashpot_loss<Dashpot>(p, t3.force, v3, dt, 0.0)));

  const contact::TangentialResult r3 = contact::tangential_force<Dashpot>(p, xi3, v3, f_n, was_sliding);
  const contact::ScalarResult r1 = contact::tangential_force<Dashpot>(p, xi, v, f_n, was_sliding);
  REQUIRE(same(r1.force, r3.force.x()));
  REQUIRE(same(r1.spring, r3.spring.x()));
  REQUIRE(r1.sliding == r3.sliding);
  REQUIRE(same(r1.slip_loss, r3.slip_loss));
  REQUIRE(same(contact::spring_dashpot_loss<Dashpot>(p, r1.force, v, dt, r1.slip_loss),
               contact::spring_dashpot_loss<Dashpot>(p, r3.force, v3, dt, r3.slip_loss)));
  // The stored energy (1/2) k xi^2 of the spring kept, as the law books it for each form.
  REQUIRE(same(0.5 * p.kt * (r1.spring * r1.spring), 0.5 * p.kt * r3.spring.squaredNorm()));
  tally.slid += r1.sliding;
  tally.stuck += !r1.sliding;
  tally.zero_k += p.kt == 0.0;
}
}  // namespace

TEST_CASE("tangential spring of one component (torsion): the bits of the Vec3 spring on (x, 0, 0)", "[contact]") {
  std::mt19937_64 g(20261130);
  Tally with, without;
  for (int k = 0; k < 200000; ++k) {
    compare<true>(g, with);
    compare<false>(g, without);
  }
  // Every branch was taken often: sliding (the cap), sticking, and no spring.
  for (const Tally& t : {with, without}) {
    CHECK(t.slid > 20000);
    CHECK(t.stuck > 20000);
    CHECK(t.zero_k > 20000);
  }
}

TEST_CASE("tangential spring of one component (torsion): capped at f_C^d, reset by eq. (7)", "[contact]") {
  const contact::TangentialSpringParams p{1e5, 0.5, 0.4, 0.3, false};
  const double xi = 2e-6, v = -0.01, f_n = 0.2;  // |f_o| = 0.195 > 0.4 f_n = 0.08
  const contact::ScalarResult r = contact::tangential_force<true>(p, xi, v, f_n, false);
  REQUIRE(r.sliding);
  CHECK(r.force == -0.3 * f_n);                       // f_C^d against the test force's sign
  CHECK(r.spring == -(r.force + p.gamma_t * v) / p.kt);  // eq. (7)
  CHECK(r.slip_loss > 0.0);
}
