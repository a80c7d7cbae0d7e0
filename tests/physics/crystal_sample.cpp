// The observers of a crystal sample (crystal/simulation.cpp's layer stress and coordination,
// Dynamics' energies) walk per-layer lists (Dynamics::layer_order, layer_chains: several layers'
// sums side by side). They must give the bits of the plain sums in the order of docs/design.md
// §2.8, computed here the straightforward way, with open contacts, friction and a storage order
// that is not layer by layer.
#include <catch2/catch.hpp>
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <tuple>

#include "config/case.hpp"
#include "core/rng.hpp"
#include "crystal/dynamics.hpp"
#include "crystal/packing.hpp"
#include "crystal/simulation.hpp"

using namespace granwave;

namespace {

// Sum per layer (s[L] += term in call order), then over the layers in layer order.
struct PerLayer {
  std::vector<double> s;
  explicit PerLayer(int layers) : s(static_cast<std::size_t>(layers), 0.0) {}
  double total() const {
    double t = 0.0;
    for (double v : s) t += v;
    return t;
  }
};

void check_observers(const crystal::Dynamics& dyn) {
  const crystal::Packing& pk = dyn.packing();
  const crystal::ContactList& C = dyn.contacts;
  REQUIRE(dyn.rebuilds == 1);  // nothing folded into the dissipation at rebuilds

  // Coordination: every free particle's touching contacts (its own walk over its contacts).
  long touching = 0, free = 0;
  for (std::size_t p = 0; p < dyn.size(); ++p)
    if (!pk.fixed[p]) {
      ++free;
      touching += dyn.touching_contacts_of(p);
    }
  CHECK(crystal::coordination(dyn) == static_cast<double>(touching) / static_cast<double>(free));

  // Layer stress: the fast path (per-layer lists of contact ends) against the contact walk that
  // also fills the per-particle stresses.
  std::vector<double> zz, zx, zz_walk, zx_walk, per_particle;
  crystal::layer_stress(dyn, zz, zx);
  crystal::layer_stress(dyn, zz_walk, zx_walk, &per_particle);
  CHECK(zz == zz_walk);
  CHECK(zx == zx_walk);

  // Energies.
  PerLayer kinetic(pk.layers), verlet(pk.layers), stored(pk.layers), lost(pk.layers);
  for (std::size_t p = 0; p < dyn.size(); ++p) {
    if (!dyn.mobile[p]) continue;
    const int L = pk.layer[p];
    kinetic.s[L] += 0.5 * dyn.mass[p] * (dyn.vx[p] * dyn.vx[p] + dyn.vy[p] * dyn.vy[p] + dyn.vz[p] * dyn.vz[p]) +
                    0.5 * dyn.inertia[p] * (dyn.wx[p] * dyn.wx[p] + dyn.wy[p] * dyn.wy[p] + dyn.wz[p] * dyn.wz[p]);
    verlet.s[L] += (dyn.fx[p] * dyn.fx[p] + dyn.fy[p] * dyn.fy[p] + dyn.fz[p] * dyn.fz[p]) * dyn.inv_mass[p] +
                   (dyn.tx[p] * dyn.tx[p] + dyn.ty[p] * dyn.ty[p] + dyn.tz[p] * dyn.tz[p]) * dyn.inv_inertia[p];
  }
  // The law's stored energy, one contact after the other (ContactModel's walk over the list).
  dyn.model().add_stored_energy(stored.s.data(), C, C.own_first, pk.layer.data(), dyn.radius.data());
  for (std::size_t c = C.own_first; c < C.size(); ++c) lost.s[pk.layer[C.i[c]]] += C.dissipated[c];
  const crystal::Dynamics::Energies e = dyn.energies();
  CHECK(e.kinetic == kinetic.total());
  CHECK(e.potential == stored.total());
  CHECK(e.dissipated == lost.total());
  CHECK(e.verlet_correction == dyn.dt() * dyn.dt() / 8.0 * verlet.total());
  CHECK(dyn.kinetic_energy() == e.kinetic);
  CHECK(dyn.potential_energy() == e.potential);
  CHECK(dyn.dissipated_energy() == e.dissipated);
  CHECK(dyn.verlet_correction() == e.verlet_correction);
  CHECK(e.kinetic > 0.0);
  CHECK(e.potential > 0.0);
  CHECK(e.dissipated > 0.0);
}

}  // namespace

TEST_CASE("the sample's per-layer sums equal the plain sums bit for bit", "[crystal][sample][route]") {
  config::Case c = config::load_case(std::string(GRANWAVE_SOURCE_DIR) + "/data/cases/crystal_small.toml");
  c.contact.get<contact::LinearLudingParams>().kt = 1e5;
  c.contact.get<contact::LinearLudingParams>().gamma_n = 0.1;
  c.contact.friction().mu_static = 0.3;
  c.contact.friction().mu_dynamic = 0.2;
  crystal::Packing p = crystal::make_packing(c);
  const double delta = 2.0 * c.crystal->radius * c.crystal->overlap;
  // The upper half lifted by 4 overlaps: the contacts across the cut are open (still in the
  // list, within the skin); small random offsets and velocities, fast spins (slip: dissipation).
  const int cut = p.layers / 2;
  std::vector<double> v(3 * p.size()), w(3 * p.size());
  for (std::size_t q = 0; q < p.size(); ++q) {
    CounterRng rng(7, q);
    if (p.layer[q] >= cut) p.z[q] += 4.0 * delta;
    p.x[q] += 1e-8 * (2 * rng.uniform() - 1);
    p.z[q] += 1e-8 * (2 * rng.uniform() - 1);
    for (int k = 0; k < 3; ++k) v[3 * q + k] = 1e-3 * (2 * rng.uniform() - 1);
    for (int k = 0; k < 3; ++k) w[3 * q + k] = 300.0 * (2 * rng.uniform() - 1);
  }
  // The same crystal stored top layer first (layers are then not in index order).
  crystal::Packing reversed = p;
  std::vector<double> v_rev(v.size()), w_rev(w.size());
  const std::size_t n = p.size();
  auto rev = [n](auto& dst, const auto& src, int k) {
    for (std::size_t q = 0; q < n; ++q)
      for (int m = 0; m < k; ++m) dst[k * q + m] = src[k * (n - 1 - q) + m];
  };
  rev(reversed.x, p.x, 1), rev(reversed.y, p.y, 1), rev(reversed.z, p.z, 1);
  rev(reversed.radius, p.radius, 1), rev(reversed.mass, p.mass, 1), rev(reversed.inertia, p.inertia, 1);
  rev(reversed.layer, p.layer, 1), rev(reversed.fixed, p.fixed, 1);
  rev(v_rev, v, 3), rev(w_rev, w, 3);
  for (const auto& [packing, vel, spin] : {std::tuple{&p, &v, &w}, std::tuple{&reversed, &v_rev, &w_rev}}) {
    crystal::Dynamics dyn(*packing, crystal::case_model(c.contact, c.crystal->density), 2e-7);
    for (std::size_t q = 0; q < n; ++q) {
      dyn.vx[q] = (*vel)[3 * q], dyn.vy[q] = (*vel)[3 * q + 1], dyn.vz[q] = (*vel)[3 * q + 2];
      dyn.wx[q] = (*spin)[3 * q], dyn.wy[q] = (*spin)[3 * q + 1], dyn.wz[q] = (*spin)[3 * q + 2];
    }
    for (int s = 0; s < 20; ++s) dyn.step();
    const long open = std::count_if(dyn.contacts.delta.begin(), dyn.contacts.delta.end(), [](double d) { return d <= 0.0; });
    std::printf("%zu contacts, %ld open\n", dyn.contacts.size(), open);
    const long per_layer = std::count(p.layer.begin(), p.layer.end(), cut);
    CHECK(open >= 4 * per_layer);  // the cut: each particle below it has 4 neighbours above
    // One thread: the contact pass stored the layer stress's end arms with the forces; the layer
    // stress's own arms (its route on threads) give the same bits.
    REQUIRE(dyn.end_arms_stored);
    std::vector<double> zz, zx, zz_own, zx_own;
    crystal::layer_stress(dyn, zz, zx);
    dyn.end_arms_stored = false;
    crystal::layer_stress(dyn, zz_own, zx_own);
    dyn.end_arms_stored = true;
    CHECK(zz == zz_own);
    CHECK(zx == zx_own);
    check_observers(dyn);
  }
}

TEST_CASE("a list no contact has lost energy in is skipped by the dissipation sums, bit for bit",
          "[crystal][sample][route]") {
  // Friction without dashpots: the vectorised sweep dissipates nothing (contact::LosslessSweep), so
  // until a contact slides or opens with a stretched spring every entry stays +0.0 and the sums
  // skip the list (ContactList::losses_booked). Slow spins: nothing slides; fast spins: slip.
  config::Case c = config::load_case(std::string(GRANWAVE_SOURCE_DIR) + "/data/cases/crystal_small.toml");
  c.contact.get<contact::LinearLudingParams>().kt = 1e5;
  c.contact.get<contact::LinearLudingParams>().gamma_n = c.contact.get<contact::LinearLudingParams>().gamma_t = 0.0;
  c.contact.friction().mu_static = c.contact.friction().mu_dynamic = 0.5;
  const crystal::Packing p = crystal::make_packing(c);
  for (const double spin : {1e-3, 300.0}) {
    crystal::Dynamics dyn(p, crystal::case_model(c.contact, c.crystal->density), 2e-7);
    for (std::size_t q = 0; q < dyn.size(); ++q) {
      CounterRng rng(11, q);
      dyn.wx[q] = spin * (2 * rng.uniform() - 1), dyn.wy[q] = spin * (2 * rng.uniform() - 1);
    }
    for (int s = 0; s < 20; ++s) dyn.step();
    const crystal::ContactList& C = dyn.contacts;
    double plain = 0.0;  // the plain per-layer sums (docs/design.md 2.8), then over the layers
    {
      std::vector<double> s(static_cast<std::size_t>(p.layers), 0.0);
      for (std::size_t k = C.own_first; k < C.size(); ++k) s[p.layer[C.i[k]]] += C.dissipated[k];
      for (double v : s) plain += v;
    }
    INFO("spin " << spin << " rad/s, dissipated " << plain << " J");
    if (spin < 1.0) {
      CHECK_FALSE(C.losses_booked);
      CHECK(std::all_of(C.dissipated.begin(), C.dissipated.end(), [](double d) { return d == 0.0 && !std::signbit(d); }));
    } else {
      CHECK(C.losses_booked);
      CHECK(plain > 0.0);
    }
    CHECK(dyn.energies().dissipated == plain);
    CHECK(dyn.dissipated_energy() == plain);
  }
}
