// The lattice rows' contact pass (crystal/lattice.hpp) against the list's pass: regression tests of one
// route against the other (the physics of both is validated by the crystal's physics tests, which run
// the lattice route on the seed's crystals). Per contact the two take the same operations on the same
// values, so every overlap, loss and force is the list's bit for bit where the list's pair has the
// lattice's orientation (the seams' others to rounding); each particle's sum adds the same terms in
// another order (to rounding). Threads give the one-thread bits; what is no such crystal, or has a
// pair outside the lattice, takes the list's pass.
#include <catch2/catch.hpp>
#include <algorithm>
#include <array>
#include <bit>
#include <cmath>
#include <cstdint>
#include <stdexcept>
#include <string>
#include <vector>
#ifdef _OPENMP
#include <omp.h>
#endif

#include "config/case.hpp"
#include "crystal/derive.hpp"
#include "crystal/dynamics.hpp"
#include "crystal/observers.hpp"
#include "crystal/packing.hpp"
#include "../case_text.hpp"

using namespace granwave;

namespace {

// data/cases/crystal_small.toml's frictionless crystal with `cells`, and a dashpot (seed 002's
// crystal_damped) when `gamma_n` > 0.
config::Case lattice_case(int nx, int ny, int layers, double gamma_n) {
  config::Case c = config::parse_case(
      test_support::case_text("data/cases/crystal_small.toml",
                              {{"gamma_n = 0.0\nkt", "gamma_n = " + std::to_string(gamma_n) + "\nkt"}}),
      "lattice.toml");
  c.crystal->cells = {nx, ny, layers};
  return c;
}

// The crystal of `c`, its source displaced (x and y too: every component of every force) and stepped,
// so that forces and velocities differ between contacts; `lattice`: which pass.
crystal::Dynamics stepped(const config::Case& c, bool lattice, int steps = 40) {
  const crystal::Packing p = crystal::make_packing(c);
  crystal::Dynamics d(p, crystal::case_model(c.contact, c.crystal->density), crystal::derive(c).dt);
  d.lattice_pass = lattice;
  std::vector<std::size_t> source;
  for (std::size_t q = 0; q < p.size(); ++q)
    if (p.layer[q] < p.fixed_layers) source.push_back(q);
  d.displace(source, 1e-5 * p.d, -2e-5 * p.d, 1e-4 * p.d);
  for (int s = 0; s < steps; ++s) d.step();
  return d;
}

bool same(double a, double b) { return std::bit_cast<std::uint64_t>(a) == std::bit_cast<std::uint64_t>(b); }

}  // namespace

TEST_CASE("lattice pass against the list's: overlaps, losses and forces bit for bit, sums to rounding",
          "[crystal][lattice]") {
  // 4 x 4 sites (the seed's), 8 x 2 (two vectors a row; the +y pairs twice, through two images), 4 x 3;
  // with and without a dashpot.
  struct Crystal {
    int nx, ny, layers;
    double gamma_n;
  };
  for (const Crystal k : {Crystal{4, 4, 16, 0.0}, Crystal{8, 2, 9, 0.1}, Crystal{4, 3, 7, 0.1}}) {
    CAPTURE(k.nx, k.ny, k.layers, k.gamma_n);
    const config::Case c = lattice_case(k.nx, k.ny, k.layers, k.gamma_n);
    crystal::Dynamics lat = stepped(c, true), list = stepped(c, true);
    list.lattice_pass = false;  // the same state, the other pass
    REQUIRE(lat.lattice_rows() != nullptr);
    REQUIRE(list.lattice_rows() == nullptr);
    const crystal::ContactPassPlan plan{lat.dt(), true, false, true};
    const crystal::ContactSums a = lat.model().contact_pass(lat, plan);
    const crystal::ContactSums b = list.model().contact_pass(list, plan);
    REQUIRE(a.rows == 1);
    REQUIRE(b.rows == 1);
    // The sample's forces and end arms stay by slot place: the layer stress reads them there, the same
    // ends in the same order as from the list (forces_to_list), and as from the arms it makes itself.
    REQUIRE(lat.sampled_lattice_forces() != nullptr);
    REQUIRE(!lat.end_arms_stored);
    std::vector<double> zz[3], zx[3];
    crystal::layer_stress(lat, zz[0], zx[0]);
    lat.forces_to_list();
    REQUIRE(lat.sampled_lattice_forces() == nullptr);
    REQUIRE(lat.end_arms_stored);
    crystal::layer_stress(lat, zz[1], zx[1]);
    lat.end_arms_stored = false;
    crystal::layer_stress(lat, zz[2], zx[2]);
    lat.end_arms_stored = true;
    CHECK(std::any_of(zz[0].begin(), zz[0].end(), [](double s) { return s != 0.0; }));
    CHECK((zz[0] == zz[1] && zz[0] == zz[2]));
    CHECK((zx[0] == zx[1] && zx[0] == zx[2]));
    const crystal::ContactList &A = lat.contacts, &B = list.contacts;
    REQUIRE(A.size() == B.size());
    const crystal::LatticeRows& L = *lat.lattice_rows();
    std::vector<std::uint8_t> reversed(B.size(), 0);
    for (std::size_t slot = 0; slot < L.listed.size(); ++slot)
      if (L.listed[slot] >= 0) reversed[L.listed[slot]] = L.reversed[slot] != 0.0;
    double f_max = 0.0;
    for (std::size_t q = 0; q < B.size(); ++q) f_max = std::max({f_max, std::fabs(B.f_x[q]), std::fabs(B.f_z[q])});
    REQUIRE(f_max > 0.0);
    long oriented = 0, seams = 0;
    double worst = 0.0;
    for (std::size_t q = 0; q < B.size(); ++q) {
      if (reversed[q]) {
        // The seams: x_j - box - x_i against -(x_i + box - x_j): b to rounding.
        ++seams;
        for (auto f : {&crystal::ContactList::f_x, &crystal::ContactList::f_y, &crystal::ContactList::f_z})
          worst = std::max(worst, std::fabs((A.*f)[q] - (B.*f)[q]) / f_max);
        CHECK(std::fabs(A.delta[q] - B.delta[q]) < 1e-12 * lat.packing().delta);
      } else {
        ++oriented;
        CHECK(same(A.delta[q], B.delta[q]));
        CHECK(same(A.dissipated[q], B.dissipated[q]));
        CHECK((same(A.f_x[q], B.f_x[q]) && same(A.f_y[q], B.f_y[q]) && same(A.f_z[q], B.f_z[q])));
        CHECK((same(lat.end_arms[2 * q], list.end_arms[2 * q]) && same(lat.end_arms[2 * q + 1], list.end_arms[2 * q + 1])));
      }
    }
    CHECK(oriented > 0);
    CHECK(seams > 0);
    CHECK(worst < 1e-12);  // one ulp of the distance (2 mm) over the overlap (2 um)
    double sum_worst = 0.0;
    for (std::size_t p = 0; p < lat.size(); ++p)
      for (int r = 0; r < 3; ++r)
        sum_worst = std::max(sum_worst, std::fabs(lat.contact_sums[4 * p + r] - list.contact_sums[4 * p + r]) / f_max);
    CHECK(sum_worst < 1e-12);
    if (k.gamma_n > 0.0) CHECK(lat.dissipated_energy() > 0.0);
  }
}

TEST_CASE("lattice pass: a run follows the list's to rounding, and threads give its bits", "[crystal][lattice]") {
  const config::Case c = lattice_case(4, 4, 24, 0.1);
  crystal::Dynamics lat = stepped(c, true, 300), list = stepped(c, false, 300);
  REQUIRE(lat.lattice_rows() != nullptr);
  double z_scale = 0.0, worst = 0.0;
  for (std::size_t p = 0; p < lat.size(); ++p) {
    z_scale = std::max(z_scale, std::fabs(list.vz[p]));
    worst = std::max(worst, std::fabs(lat.vz[p] - list.vz[p]));
  }
  REQUIRE(z_scale > 0.0);
  CHECK(worst / z_scale < 1e-9);  // the net forces are small differences of the prestress's
  CHECK(lat.dissipated_energy() > 0.0);
  CHECK(std::fabs(lat.dissipated_energy() - list.dissipated_energy()) <= 1e-9 * list.dissipated_energy());

#ifdef _OPENMP
  const int threads_before = omp_get_max_threads();
  omp_set_num_threads(2);
#endif
  crystal::Dynamics one = stepped(c, true, 0), two = stepped(c, true, 0);
  one.parallel_min_particles = ~std::size_t{0};
  two.parallel_min_particles = 0;
  for (auto* d : {&one, &two}) {
    d->advance(150);  // the finish fused with the next drift
    d->advance(1);    // and not
  }
#ifdef _OPENMP
  CHECK(two.threaded());
  omp_set_num_threads(threads_before);
#endif
  CHECK(one.z == two.z);
  CHECK(one.vz == two.vz);
  CHECK(one.fz == two.fz);
  CHECK(one.contacts.delta == two.contacts.delta);
  CHECK(same(one.dissipated_energy(), two.dissipated_energy()));
}

// A regression test of one route against the other: a run that keeps no contact forces (the samples read
// the layer stress only) writes a sampled step's places into a ring of layers and sums the layer stress
// from there; every sample is the bits of the run that keeps them, and a reader of the forces is refused.
TEST_CASE("lattice pass: without the contact forces kept, the samples' bits and a refused reader",
          "[crystal][lattice]") {
  const config::Case c = lattice_case(4, 4, 24, 0.1);  // a dashpot: losses booked as well
  const crystal::Packing p = crystal::make_packing(c);
  auto made = [&](bool keep) {
    crystal::Dynamics d(p, crystal::case_model(c.contact, c.crystal->density), crystal::derive(c).dt, nullptr, keep);
    d.parallel_min_particles = ~std::size_t{0};  // one thread: the pass sums the layer stress
    std::vector<std::size_t> source;
    for (std::size_t q = 0; q < p.size(); ++q)
      if (p.layer[q] < p.fixed_layers) source.push_back(q);
    d.displace(source, 1e-5 * p.d, -2e-5 * p.d, 1e-4 * p.d);
    return d;
  };
  crystal::Dynamics kept = made(true), ring = made(false);
  REQUIRE(kept.lattice_rows() != nullptr);
  REQUIRE(ring.lattice_rows() != nullptr);
  CHECK(kept.lattice_rows()->place_layers == 24);
  CHECK(ring.lattice_rows()->place_layers == crystal::LatticeRows::kRingLayers);
  std::vector<double> zz_k, zx_k, zz_r, zx_r;
  int compared = 0;
  for (int sample = 0; sample < 12; ++sample) {
    kept.advance(5, true);
    ring.advance(5, true);
    crystal::layer_stress(kept, zz_k, zx_k);
    crystal::layer_stress(ring, zz_r, zx_r);
    bool all = zz_k.size() == zz_r.size() && zx_k.size() == zx_r.size();
    for (std::size_t L = 0; all && L < zz_k.size(); ++L) all = same(zz_k[L], zz_r[L]) && same(zx_k[L], zx_r[L]);
    CHECK(all);
    const crystal::Dynamics::Energies ek = kept.energies(), er = ring.energies();
    CHECK(same(ek.potential, er.potential));
    CHECK(same(ek.dissipated, er.dissipated));
    CHECK(same(crystal::coordination(kept), crystal::coordination(ring)));
    compared += all;
  }
  CHECK(compared == 12);
  double peak = 0.0;
  for (double v : zz_k) peak = std::max(peak, std::fabs(v));
  CHECK(peak > 0.0);  // a stress to compare
  CHECK(ring.z == kept.z);
  CHECK(ring.vz == kept.vz);
  // The forces of a sampled step went with the ring: a reader of the list's is told so, not given old ones.
  CHECK_THROWS_AS(ring.forces_to_list(), std::logic_error);
  std::vector<double> per_particle;
  CHECK_THROWS_AS(crystal::layer_stress(ring, zz_r, zx_r, &per_particle), std::logic_error);
  CHECK_NOTHROW(kept.forces_to_list());
  // Once the list's own pass takes over, the list's forces are its: no refusal, the same stress.
  kept.lattice_pass = ring.lattice_pass = false;
  kept.advance(5, true);
  ring.advance(5, true);
  CHECK_NOTHROW(ring.forces_to_list());
  crystal::layer_stress(kept, zz_k, zx_k);
  crystal::layer_stress(ring, zz_r, zx_r);
  CHECK(zz_k == zz_r);
  CHECK(zx_k == zx_r);
}

TEST_CASE("lattice pass: what is no lattice crystal, or has a pair outside it, takes the list's pass",
          "[crystal][lattice]") {
  const config::Case c = lattice_case(4, 4, 8, 0.0);
  crystal::Packing p = crystal::make_packing(c);
  const auto model = crystal::case_model(c.contact, c.crystal->density);
  {
    crystal::Dynamics d(p, model, 1e-7);
    CHECK(d.lattice_rows() != nullptr);
  }
  {
    crystal::Dynamics d(crystal::make_packing(lattice_case(6, 4, 8, 0.0)), model, 1e-7);  // rows of six
    CHECK(d.lattice_rows() == nullptr);
  }
  {
    crystal::Packing file = p;
    file.generator = "file";
    crystal::Dynamics d(file, model, 1e-7);
    CHECK(d.lattice_rows() == nullptr);
  }
  {
    crystal::Dynamics d(p, model, 1e-7);
    crystal::ImageMotion sheared;
    sheared.shift_x = 1e-3 * p.d;
    d.set_box(p.box_x, p.box_y, sheared);
    CHECK(d.lattice_rows() == nullptr);
  }
  // A particle moved by one site in x comes within reach of its +x neighbour's neighbour: the list's pass.
  const std::size_t q = 3 * static_cast<std::size_t>(c.crystal->cells[0] * c.crystal->cells[1]);
  p.x[q] += p.d_prime;
  crystal::Dynamics d(p, model, 1e-7);
  CHECK(d.lattice_rows() == nullptr);
}
