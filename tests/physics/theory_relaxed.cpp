// Issue 39 items 1-2 on the synthetic FCC network (theory::fcc_network): the relaxed tensor of the
// triply periodic crystal against the lattice dynamics' long-wave limit with rotations
// (S + G R^+ G, an independent derivation: Bloch waves, not a static solve), the affine tensor
// without the initial stress against eq. (10), and the counting of rattlers and zero modes.
#include <catch2/catch.hpp>
#include <cmath>
#include <cstdio>

#include "theory/crystal_theory.hpp"
#include "theory/lattice_dynamics.hpp"
#include "theory/relaxed_moduli.hpp"
#include "theory/stiffness.hpp"

using namespace granwave::theory;

namespace {

constexpr int kNx = 4, kNy = 4, kLayers = 8;  // even: the ABAB stack closes across z
constexpr double kL = 2e-3 * (1 - 1e-3), kMass = 8.4e-6, kK = 1e5;

struct Fcc {
  ContactNetwork net;       // as built (open in z)
  ContactNetwork periodic;  // closed across z
  double box_z = 0.0;
};

// The centres fcc_network's particles have (layer n at z = n l0, odd layers shifted by (l/2, l/2)).
Fcc fcc(double kt, double f0) {
  Fcc f;
  f.net = fcc_network(kNx, kNy, kLayers, kL, kMass, kK, kt, f0);
  const double l0 = kL / std::sqrt(2.0);
  std::vector<Vec3> centres;
  for (int n = 0; n < kLayers; ++n)
    for (int j = 0; j < kNy; ++j)
      for (int i = 0; i < kNx; ++i) {
        const double s = (n % 2) ? 0.5 * kL : 0.0;
        centres.emplace_back(i * kL + s, j * kL + s, n * l0);
      }
  f.box_z = kLayers * l0;
  f.periodic = periodic_in_z(f.net, centres, f.box_z, [&](int, int, const Vec3&, double) {
    NetworkContact c;
    c.normal_force = f0;
    return c;
  });
  return f;
}

double rel_diff(const Eigen::Matrix3d& a, const Eigen::Matrix3d& b) {
  return (a - b).cwiseAbs().maxCoeff() / b.cwiseAbs().maxCoeff();
}

double tensor_diff(const Tensor4& a, const Tensor4& b) {
  double m = 0.0, s = 0.0;
  for (int i = 0; i < 81; ++i) m = std::max(m, std::abs(a.data()[i] - b.data()[i])), s = std::max(s, std::abs(b.data()[i]));
  return m / s;
}

const Vec3 kDirections[] = {Vec3::UnitZ(), Vec3::UnitX(), Vec3(1, 2, 3).normalized(), Vec3(1, 1, 0).normalized()};

}  // namespace

TEST_CASE("FCC, triply periodic: relaxed Christoffel tensor = lattice long waves with rotations", "[theory][relaxed]") {
  struct Variant {
    double kt, f0, arm_shift, kr;
    const char* name;
  };
  const Variant variants[] = {{0.0, 0.0, 0.0, 0.0, "frictionless"},
                              {0.5 * kK, 0.0, 0.0, 0.0, "kt = k/2"},
                              {0.5 * kK, 2e-3 * kK * 1e-6, 0.0, 0.0, "kt = k/2, prestressed"},
                              {kK, 0.2, 0.5, 0.0, "kt = k, contact-point arm, f0 = 0.2 N"},
                              {0.2 * kK, 0.1, 0.0, 0.3 * kK, "kt = k/5, rolling springs"}};
  for (const auto& v : variants) {
    INFO(v.name);
    const Fcc f = fcc(v.kt, v.f0);
    REQUIRE(f.periodic.contacts.size() == f.net.contacts.size() + kNx * kNy * 4);
    RelaxedOptions o;
    o.boundary = RelaxedBoundary::bulk;
    o.box_z = f.box_z;
    o.contact.arm_shift = v.arm_shift;
    o.contact.kr = v.kr;
    const RelaxedModuli r = relaxed_moduli(f.periodic, o);
    LatticeCellOptions lo = o.contact;
    const auto cell = lattice_cell(f.net, {}, lo);
    REQUIRE(cell);
    CHECK(r.rattlers == 0);
    CHECK(r.translation_modes == 3);
    CHECK(r.mechanisms == 0);
    CHECK(r.unstable_modes == 0);
    CHECK(r.free_rotation_modes == (v.kt == 0.0 && v.kr == 0.0 ? 3 * kNx * kNy * kLayers : 0));
    CHECK(r.coordination == Approx(12.0).epsilon(1e-15));
    CHECK(r.residual < 1e-12);
    for (const Vec3& h : kDirections) {
      const LatticeLongWave lw = lattice_long_wave(*cell, h);
      const Eigen::Matrix3d relaxed = r.relaxed.christoffel(h) / r.rho;
      const Eigen::Matrix3d affine = r.affine.christoffel(h) / r.rho;
      std::printf("%-40s h = (%.3f %.3f %.3f): relaxed vs lattice %.2e, affine vs lattice S/m %.2e\n", v.name, h.x(),
                  h.y(), h.z(), rel_diff(relaxed, lw.with_rotations), rel_diff(affine, lw.affine));
      CHECK(rel_diff(relaxed, lw.with_rotations) < 1e-6);
      CHECK(rel_diff(affine, lw.affine) < 1e-6);
      CHECK(r.relaxed.christoffel(h)(0, 0) <= r.affine.christoffel(h)(0, 0) * (1 + 1e-12));
    }
    // The speeds along z, as `granwave theory` prints them.
    const LatticeLongWave lz = lattice_long_wave(*cell, Vec3::UnitZ());
    CHECK(r.V_pz == Approx(lz.speed_along(Vec3::UnitZ())).epsilon(1e-6));
    CHECK(r.V_sz == Approx(lz.speed_along(Vec3::UnitX())).epsilon(1e-6));
    CHECK(r.V_sy == Approx(lz.speed_along(Vec3::UnitY())).epsilon(1e-6));
  }
}

TEST_CASE("FCC: the affine tensor without the initial stress is eq. (10), bulk and slab", "[theory][relaxed]") {
  const Fcc f = fcc(0.3 * kK, 0.5);
  const CrystalPrediction p = crystal_prediction(f.net);  // eq. (10) over the inner layers
  RelaxedOptions bulk;
  bulk.boundary = RelaxedBoundary::bulk;
  bulk.box_z = f.box_z;
  const RelaxedModuli b = relaxed_moduli(f.periodic, bulk);
  CHECK(tensor_diff(b.affine_unstressed, p.C) < 1e-13);
  CHECK(b.rho == Approx(p.rho_bulk).epsilon(1e-14));
  RelaxedOptions slab;
  slab.affine_layers = 2;
  const RelaxedModuli s = relaxed_moduli(f.net, slab);
  CHECK(tensor_diff(s.affine_unstressed, p.C) < 1e-13);
  CHECK(s.rho == Approx(p.rho_bulk).epsilon(1e-14));
  CHECK(s.translation_modes == 0);
  CHECK(s.mechanisms == 0);
  CHECK(s.free_particles == kNx * kNy * (kLayers - 4));
  // The initial-stress term: A_affine - A_affine,unstressed = -(1/V) sum f0 l n_a n_g P_bf, whose
  // trace over (b = f) with a = g summed is -2 (1/V) sum f0 l = -6 p. (A difference of tensors
  // 1/(f0/(k l)) = 400 times larger than it: round-off 1e-16 * 400 per term.)
  double tr = 0.0;
  for (int a = 0; a < 3; ++a)
    for (int bb = 0; bb < 3; ++bb) tr += b.affine(a, bb, a, bb) - b.affine_unstressed(a, bb, a, bb);
  CHECK(tr == Approx(-6.0 * b.pressure).epsilon(1e-11));
  CHECK(b.pressure == Approx(2.0 * std::sqrt(2.0) * 0.5 / (kL * kL)).epsilon(1e-12));  // 6 f0 l / (3 l^3/sqrt 2)
  // The slab relaxes less than the bulk (its end layers hold their rotations) but still softens S.
  std::printf("FCC kt = 0.3 k, f0 = 0.5 N: V_sz bulk %.6f, slab %.6f, affine %.6f m/s\n", b.V_sz, s.V_sz, s.V_sz_affine);
  CHECK(s.V_sz < s.V_sz_affine);
  CHECK(s.V_sz >= b.V_sz * (1 - 1e-12));
}

TEST_CASE("Rattlers and zero modes are found and counted, never divided by", "[theory][relaxed]") {
  // A particle hanging on three contacts joins the periodic FCC: a rattler; the tensor is unchanged.
  Fcc f = fcc(0.5 * kK, 0.2);
  RelaxedOptions o;
  o.boundary = RelaxedBoundary::bulk;
  o.box_z = f.box_z;
  const RelaxedModuli ref = relaxed_moduli(f.periodic, o);
  ContactNetwork with = f.periodic;
  const int extra = static_cast<int>(with.particles.size());
  with.particles.push_back({kMass, 3, 0.0, 0.5 * kL, 0.4 * kMass * 0.25 * kL * kL});
  for (int t = 0; t < 3; ++t) {
    NetworkContact c;
    c.i = t, c.j = extra, c.branch = Vec3(t == 0, t == 1, t == 2) * kL, c.normal_force = 0.2;
    with.contacts.push_back(c);
  }
  const RelaxedModuli r = relaxed_moduli(with, o);
  CHECK(r.rattlers == 1);
  CHECK(r.contacts_used == ref.contacts_used);
  CHECK(r.mechanisms == 0);
  CHECK(tensor_diff(r.relaxed * (r.volume / ref.volume), ref.relaxed) < 1e-12);

  // Rolling springs without tangential springs: rotations are coupled only to each other, so the
  // uniform turn of the bulk is 3 zero modes the inertia count finds; the strain does not drive them.
  const Fcc g = fcc(0.0, 0.1);
  RelaxedOptions q = o;
  q.box_z = g.box_z;
  q.contact.k_roll = 1e-3;
  const RelaxedModuli m = relaxed_moduli(g.periodic, q);
  CHECK(m.free_rotation_modes == 0);
  CHECK(m.mechanisms == 3);
  CHECK(m.forcing_on_zero_modes < 1e-12);
  CHECK(tensor_diff(m.relaxed, m.affine) < 1e-12);  // frictionless FCC: nothing relaxes
}
