// The Verlet step skips the beads ahead of the front (exactly at rest in an unloaded Hertz
// chain). That must change nothing: compare, bit for bit, with a plain full-chain velocity
// Verlet loop written out here from eq. (13).
#include <catch2/catch.hpp>

#include <algorithm>
#include <cmath>
#include <string>
#include <vector>

#include "chain/chain.hpp"
#include "config/case.hpp"

using namespace granwave;

namespace {
// oriented20 with a random dimer stretch in front, so the front meets reversed cells.
config::Case front_case() {
  return config::load_case(std::string(GRANWAVE_SOURCE_DIR) + "/data/cases/oriented20.toml");
}

struct Plain {
  std::vector<double> u, v, a, F, A, g, inv_m;
  std::size_t n;
  explicit Plain(const chain::ChainSystem& s) : n(s.nbeads()) {
    u.assign(n + 1, 0.0);
    v.assign(s.velocity.begin(), s.velocity.end());
    a.assign(n, 0.0);
    F.assign(n + 1, 0.0);
    A.assign(n, 0.0);
    g.assign(n, 0.0);
    for (std::size_t j = 0; j < s.ncontacts(); ++j) {
      A[j] = s.hertz_constant[j];
      g[j] = s.initial_overlap[j];
    }
    for (std::size_t i = 0; i < n; ++i) inv_m.push_back(1.0 / s.mass[i]);
    forces();
  }
  void forces() {
    for (std::size_t j = 0; j < n; ++j) {
      const double d = std::max(g[j] + u[j] - u[j + 1], 0.0);
      F[j + 1] = A[j] * d * std::sqrt(d);
    }
    for (std::size_t i = 0; i < n; ++i) a[i] = (F[i] - F[i + 1]) * inv_m[i];
  }
  void step(double dt) {
    for (std::size_t i = 0; i < n; ++i) {
      v[i] += 0.5 * dt * a[i];
      u[i] += dt * v[i];
    }
    forces();
    for (std::size_t i = 0; i < n; ++i) v[i] += 0.5 * dt * a[i];
  }
};
}  // namespace

TEST_CASE("skipping the beads ahead of the front changes no bit of the Verlet trajectory", "[chain]") {
  config::Case c = front_case();
  chain::ChainSystem sys = chain::build_chain(c);
  chain::apply_spins(sys, std::string(sys.nflippable(), '1'));
  const double dt = 2e-8;
  chain::Stepper st(sys, config::Scheme::verlet, dt);
  Plain plain(sys);
  // Long enough for the front to cross the chain and reflect from the wall (about 0.6 ms).
  for (int k = 0; k < 40000; ++k) {
    st.step();
    plain.step(dt);
    if (k % 1000 == 999) {
      for (std::size_t i = 0; i < sys.nbeads(); ++i) {
        INFO("step " << k + 1 << ", bead " << i);
        REQUIRE(st.displacement()[i] == plain.u[i]);
        REQUIRE(st.velocity()[i] == plain.v[i]);
      }
    }
  }
  // The wall has been reached: the whole chain moves by now.
  CHECK(std::count_if(plain.v.begin(), plain.v.end(), [](double x) { return x != 0.0; }) == static_cast<long>(sys.nbeads()));
}
