// Lattice dynamics with rotations (src/theory/lattice_dynamics.hpp) on the FCC of seed 002, against
// closed forms derived by hand (docs/design.md §3) and against eq. (10) / the lattice omega_0 of
// crystal_theory (theory against theory).
//
// FCC of square layers, wave vector along z, q = k l0, contact distance d', l0 = d'/sqrt(2),
// f0 = k delta the static normal force, arm the lever arm, I = 2/5 m a^2. Of the 12 contacts, 4 lie
// in the layer (b.z = 0) and 8 in the two neighbouring layers (n_z^2 = 1/2, n_x^2 = n_y^2 = 1/4).
// The 6x6 problem splits into u_z (P), theta_z (torsion) and two 2x2 blocks (u_x, theta_y),
// (u_y, theta_x) (S):
//   P:       m omega^2 = 4 (k + kt - f0/d') (1 - cos q)
//   torsion: I omega^2 = kt arm^2 (12 + 4 cos q)
//   S:       [ A    iB ] [u_x    ]            A = (2k + 6 (kt - f0/d')) (1 - cos q)
//            [ -iB  C  ] [theta_y] = omega^2 M,  B = 4 sqrt(2) kt arm sin q,  C = kt arm^2 (10 + 6 cos q)
// Long waves: V_p^2 = 2 l0^2 (k + kt - f0/d')/m; V_s^2 = l0^2 (k + 3 kt - 3 f0/d' - 2 kt)/m: the
// rotations (theta_y = -i B/C u_x) take back 2 kt of eq. (10)'s 3 kt, so V_s = V_s(0) sqrt(1 + kt/k)
// (prestress aside), not eq. (10)'s sqrt(1 + 3 kt/k) and not the frictionless V_s(0).
// Rotations at k = 0: omega^2 = 16 kt arm^2 / I (three-fold) = 40 kt/m for arm = a.
// Rolling and torsion springs kr, ko (N m/rad) on the relative turn add to the rotational diagonal
// only through the 8 bonds out of the layer (n_z^2 = 1/2, n_x^2 = n_y^2 = 1/4), times (1 - cos q):
//   torsion: I omega^2 = kt arm^2 (12 + 4 cos q) + 4 (kr + ko) (1 - cos q)
//   S:       C = kt arm^2 (10 + 6 cos q) + (6 kr + 2 ko) (1 - cos q)
// so at k = 0 nothing changes (long-wave speeds, rotational frequencies); the zone edge moves most.
#include <catch2/catch.hpp>

#include <cmath>
#include <numbers>

#include "theory/crystal_theory.hpp"
#include "theory/lattice_dynamics.hpp"

using namespace granwave::theory;
using Catch::Matchers::WithinAbs;
using Catch::Matchers::WithinRel;

namespace {
constexpr double a = 1e-3, rho0 = 2000.0, k = 1e5, overlap = 1e-3;
const double d = 2 * a, dp = d * (1 - overlap), delta = d - dp;
const double m = rho0 * 4.0 / 3.0 * std::numbers::pi * a * a * a;
const double l0 = dp / std::sqrt(2.0);
const Vec3 ez(0, 0, 1);

struct Params {
  double kt = 0.0;
  double f0 = 0.0;
  double arm_shift = 0.0;
  double kr = 0.0;  // rolling resistance, N m/rad
  double ko = 0.0;  // torsion resistance, N m/rad
};

LatticeCell fcc_cell(const Params& p) {
  const auto net = fcc_network(4, 4, 8, dp, m, k, p.kt, p.f0);
  LatticeCellOptions opt;
  opt.arm_shift = p.arm_shift;
  opt.k_roll = p.kr;
  opt.k_twist = p.ko;
  std::string why;
  const auto cell = lattice_cell(net, {}, opt, &why);
  INFO(why);
  REQUIRE(cell);
  return *cell;
}

// fcc_network's radius r = (d' + f0/k)/2, inertia 2/5 m r^2; the lever arm r - shift * delta.
double radius_of(const Params& p) { return 0.5 * (dp + p.f0 / k); }
double inertia_of(const Params& p) { return 0.4 * m * radius_of(p) * radius_of(p); }
double arm_of(const Params& p) { return radius_of(p) - p.arm_shift * p.f0 / k; }

struct Closed {
  double P, torsion, S_low, S_high;  // omega^2
};
Closed closed_forms(const Params& p, double q) {
  const double arm = arm_of(p), I = inertia_of(p), kt = p.kt, g = p.f0 / dp, c = std::cos(q), s = std::sin(q);
  Closed r;
  r.P = 4 * (k + kt - g) * (1 - c) / m;
  r.torsion = (kt * arm * arm * (12 + 4 * c) + 4 * (p.kr + p.ko) * (1 - c)) / I;
  const double A = (2 * k + 6 * (kt - g)) * (1 - c) / m;
  const double C = (kt * arm * arm * (10 + 6 * c) + (6 * p.kr + 2 * p.ko) * (1 - c)) / I;
  const double B2 = 32 * kt * kt * arm * arm * s * s / (m * I);
  const double mean = 0.5 * (A + C), half = std::sqrt(0.25 * (A - C) * (A - C) + B2);
  r.S_low = mean - half;
  r.S_high = mean + half;
  return r;
}

const std::vector<Params> kCases = {
    {0.0, 0.0, 0.0},        {0.0, k * delta, 0.0},   {0.2 * k, 0.0, 0.0},     {1.0 * k, 0.0, 0.0},
    {1.0 * k, k * delta, 0.5}, {2.0 * k, k * delta, 0.0}, {2.0 * k, 0.0, 0.5}, {0.5 * k, k * delta, 0.5}};

// kt a^2 = 0.1 N m for kt = k: the angular scale of the tangential spring.
const double kta2 = k * a * a;
// Rolling and torsion springs (N m/rad) on top of the tangential spring, and alone.
const std::vector<Params> kRollingCases = {
    {1.0 * k, 0.0, 0.0, 0.05 * kta2, 0.0},         {1.0 * k, 0.0, 0.0, 0.0, 0.5 * kta2},
    {1.0 * k, k * delta, 0.5, 2.0 * kta2, 1.0 * kta2}, {0.2 * k, k * delta, 0.0, 0.5 * kta2, 0.2 * kta2},
    {0.0, 0.0, 0.0, 1.0 * kta2, 0.3 * kta2}};

// Without and with rolling and torsion springs.
std::vector<Params> all_cases() {
  std::vector<Params> all = kCases;
  all.insert(all.end(), kRollingCases.begin(), kRollingCases.end());
  return all;
}

// Each mode's Hellmann-Feynman group velocity against the slope of the closed form it equals.
void check_group_velocities(const Params& p, const LatticeCell& cell) {
  for (double q : {0.3, 1.0, 2.0, 2.9}) {
    const double h = 1e-6;
    const Closed c = closed_forms(p, q), cp = closed_forms(p, q + h), cm = closed_forms(p, q - h);
    auto slope = [&](double Closed::*f) { return (std::sqrt(cp.*f) - std::sqrt(cm.*f)) / (2 * h) * l0; };
    for (const auto& md : lattice_modes(cell, ez, q / l0)) {
      double expect = 0.0;
      if (std::abs(md.omega2 - c.P) < 1e-9 * c.P) expect = slope(&Closed::P);
      else if (std::abs(md.omega2 - c.torsion) < 1e-9 * c.torsion) expect = slope(&Closed::torsion);
      else if (std::abs(md.omega2 - c.S_low) < 1e-9 * c.S_low) expect = slope(&Closed::S_low);
      else if (std::abs(md.omega2 - c.S_high) < 1e-9 * c.S_high) expect = slope(&Closed::S_high);
      else FAIL("mode omega^2 = " << md.omega2 << " matches no closed form");
      CHECK_THAT(md.group_velocity, WithinAbs(expect, 1e-5 * 300.0));
    }
  }
}

}  // namespace

TEST_CASE("dynamical matrix: Hermitian and positive semi-definite at every k of the zone", "[theory][lattice]") {
  for (const auto& p : all_cases()) {
    const LatticeCell cell = fcc_cell(p);
    for (int i = -50; i <= 50; ++i) {
      const double kz = std::numbers::pi / l0 * i / 50.0;
      const Matrix6cd D = dynamical_matrix(cell, kz * ez);
      INFO("kt/k = " << p.kt / k << ", f0 = " << p.f0 << ", k l0 = " << kz * l0);
      CHECK(hermitian_defect(D) < 1e-14);
      // Also off the z axis: any k of the Bravais lattice.
      CHECK(hermitian_defect(dynamical_matrix(cell, Vec3(0.3 * kz, -0.7 * kz, 0.5 * kz))) < 1e-14);
      Eigen::SelfAdjointEigenSolver<Matrix6cd> es(0.5 * (D + D.adjoint()));
      CHECK(es.eigenvalues().minCoeff() >= -1e-12 * es.eigenvalues().cwiseAbs().maxCoeff());
    }
  }
}

TEST_CASE("FCC along z: all six branches equal the closed forms", "[theory][lattice]") {
  for (const auto& p : all_cases()) {
    const LatticeCell cell = fcc_cell(p);
    REQUIRE(cell.bonds.size() == 12);
    for (int i = 0; i <= 40; ++i) {
      const double q = std::numbers::pi * i / 40.0;
      const auto modes = lattice_modes(cell, ez, q / l0);
      const Closed c = closed_forms(p, q);
      // The analytic list, two S polarisations each.
      std::vector<double> expect = {c.P, c.torsion, c.S_low, c.S_low, c.S_high, c.S_high};
      std::sort(expect.begin(), expect.end());
      const double scale = std::max({c.P, c.torsion, c.S_high});
      INFO("kt/k = " << p.kt / k << ", f0 = " << p.f0 << ", arm shift " << p.arm_shift << ", kr = " << p.kr
                     << ", ko = " << p.ko << ", q = " << q);
      for (int b = 0; b < 6; ++b) CHECK_THAT(modes[b].omega2, WithinAbs(expect[b], 1e-12 * scale));
      // Polarisation: P has no rotation at all; a mode is either in (u_z), (theta_z), (u_x, theta_y)
      // or (u_y, theta_x).
      for (const auto& md : modes) {
        const auto& e = md.content;
        const double fam[3] = {e[0] + e[4], e[1] + e[3], e[2] + e[5]};
        CHECK(std::max({fam[0], fam[1], fam[2]}) > 1 - 1e-12);
        if (e[2] > 0.5) CHECK(md.rotation() < 1e-12);
      }
    }
  }
}

TEST_CASE("frictionless without prestress: the P and S branches are eq. (10)'s sine, omega_0 = 309019 1/s", "[theory][lattice]") {
  const auto net = fcc_network(4, 4, 8, dp, m, k, 0.0, 0.0);
  const auto eq10 = crystal_prediction(net);
  const LatticeCell cell = fcc_cell({});
  const auto d = lattice_dispersion(cell, ez, layer_period(cell, ez), 41);
  CHECK_THAT(layer_period(cell, ez), WithinRel(l0, 1e-12));
  // Zone edge of the u_z branch = omega_0 of eq. (10)'s lattice (309019, docs/design.md §3), and
  // the sine shape at every k.
  int P = -1, Sx = -1;
  for (int b = 0; b < 6; ++b) {
    if (d.dominant[b] == 2) P = b;
    if (d.dominant[b] == 0) Sx = b;
  }
  REQUIRE(P >= 0);
  REQUIRE(Sx >= 0);
  CHECK(d.acoustic[P]);
  CHECK(d.acoustic[Sx]);
  CHECK_THAT(d.branches[P].back().omega, WithinRel(eq10.omega0_p, 1e-6));
  CHECK_THAT(d.branches[P].back().omega, WithinRel(309019.0, 1e-5));
  CHECK_THAT(d.branches[Sx].back().omega, WithinRel(eq10.omega0_s, 1e-6));
  for (std::size_t i = 0; i < d.k.size(); ++i) {
    CHECK_THAT(d.branches[P][i].omega, WithinAbs(lattice_omega(eq10.omega0_p, std::abs(d.k[i]), l0), 1e-9 * eq10.omega0_p));
    CHECK_THAT(d.branches[Sx][i].omega, WithinAbs(lattice_omega(eq10.omega0_s, std::abs(d.k[i]), l0), 1e-9 * eq10.omega0_p));
  }
  // Long waves: eq. (10)'s speeds with the actual distance d' (218.29, 154.36 m/s).
  const auto lw = lattice_long_wave(cell, ez);
  CHECK_THAT(lw.speed_along(ez), WithinRel(eq10.V_pz, 1e-6));
  CHECK_THAT(lw.speed_along(Vec3::UnitX()), WithinRel(eq10.V_sz, 1e-6));
  CHECK_THAT(lw.speed_along(Vec3::UnitX()), WithinRel(154.36, 1e-4));
  // No tangential spring: the rotations are free (three zero branches, zero group velocity).
  int zero = 0;
  for (int b = 0; b < 6; ++b)
    if (d.branches[b][d.k.size() - 1].omega2 == 0.0) {
      ++zero;
      CHECK(d.branches[b][5].group_velocity == 0.0);
    }
  CHECK(zero == 3);
}

TEST_CASE("prestress: the zone-edge P frequency is the prestressed omega_0 (308865 1/s)", "[theory][lattice]") {
  const double f0 = k * delta;
  const auto net = fcc_network(4, 4, 8, dp, m, k, 0.0, f0);
  const auto eq10 = crystal_prediction(net);
  const LatticeCell cell = fcc_cell({0.0, f0, 0.0});
  const auto modes = lattice_modes(cell, ez, std::numbers::pi / l0);
  double wP = 0.0, wS = 0.0;
  for (const auto& md : modes) {
    if (md.dominant() == 2) wP = md.omega;
    if (md.dominant() == 0) wS = md.omega;
  }
  CHECK_THAT(wP, WithinRel(eq10.omega0_p_prestressed, 1e-6));
  CHECK_THAT(wP, WithinRel(308865.0, 2e-6));
  CHECK_THAT(wS, WithinRel(eq10.omega0_s_prestressed, 1e-6));
  // With friction P is unchanged by rotations: the zone edge is sqrt(8 (k + kt - f0/d')/m).
  const LatticeCell cf = fcc_cell({k, f0, 0.0});
  for (const auto& md : lattice_modes(cf, ez, std::numbers::pi / l0))
    if (md.dominant() == 2) CHECK_THAT(md.omega, WithinRel(std::sqrt(8 * (2 * k - f0 / dp) / m), 1e-12));
}

TEST_CASE("long waves: closed forms of V_p, V_s with rotations, and the rotational frequencies at k = 0", "[theory][lattice]") {
  for (const auto& p : kCases) {
    const LatticeCell cell = fcc_cell(p);
    const auto lw = lattice_long_wave(cell, ez);
    const double g = p.f0 / dp, arm = arm_of(p), I = inertia_of(p);
    INFO("kt/k = " << p.kt / k << ", f0 = " << p.f0 << ", arm shift " << p.arm_shift);
    CHECK_THAT(lw.speed_along(ez), WithinRel(l0 * std::sqrt(2 * (k + p.kt - g) / m), 1e-12));
    // Rotations take 2 kt back from eq. (10)'s k + 3 kt; independent of the lever arm.
    CHECK_THAT(lw.speed_along(Vec3::UnitX()), WithinRel(l0 * std::sqrt((k + p.kt - 3 * g) / m), 1e-12));
    CHECK_THAT(lw.speed_along(Vec3::UnitY()), WithinRel(l0 * std::sqrt((k + p.kt - 3 * g) / m), 1e-12));
    CHECK_THAT(lw.speed_along(Vec3::UnitX(), false), WithinRel(l0 * std::sqrt((k + 3 * p.kt - 3 * g) / m), 1e-12));
    for (double w : lw.omega_rotation_k0)
      CHECK_THAT(w, WithinAbs(std::sqrt(16 * p.kt * arm * arm / I), 1e-9 * std::sqrt(k / m)));
    if (p.arm_shift == 0.0 && p.f0 == 0.0) CHECK_THAT(lw.omega_rotation_k0[0], WithinAbs(std::sqrt(40 * p.kt / m), 1e-6));
    // The numerical dispersion's slope at small k: omega(k)/k -> V (error O(q^2)).
    const double q = 1e-4;
    for (const auto& md : lattice_modes(cell, ez, q / l0)) {
      if (md.translation() < 0.5 || md.omega2 > 1e-3 * k / m) continue;  // acoustic modes only
      const Vec3 pol = md.dominant() == 2 ? ez : md.dominant() == 0 ? Vec3::UnitX() : Vec3::UnitY();
      CHECK_THAT(md.omega / (q / l0), WithinRel(lw.speed_along(pol), 1e-7));
      CHECK_THAT(md.group_velocity, WithinRel(lw.speed_along(pol), 1e-7));
    }
  }
  // Seed 002's crystal at kt = k: S with rotations 218.30 m/s (no prestress) against eq. (10)'s 308.7.
  const auto lw = lattice_long_wave(fcc_cell({k, 0.0, 0.0}), ez);
  CHECK_THAT(lw.speed_along(Vec3::UnitX()), WithinRel(154.36 * std::sqrt(2.0), 1e-4));
  CHECK_THAT(lw.speed_along(Vec3::UnitX(), false), WithinRel(154.36 * 2.0, 1e-4));
}

TEST_CASE("group velocities (Hellmann-Feynman) equal the slope of the closed forms", "[theory][lattice]") {
  const Params p{2.0 * k, k * delta, 0.5};
  const LatticeCell cell = fcc_cell(p);
  check_group_velocities(p, cell);
  // kt/k = 2: the upper S branch falls from sqrt(16 kt a^2/I) to the zone edge: a backward wave
  // (negative group velocity at k > 0).
  const auto d = lattice_dispersion(cell, ez, l0, 41);
  int opt = -1;
  for (int b = 0; b < 6; ++b)
    if (d.dominant[b] == 4) opt = b;  // theta_y: the optical partner of the x-polarised S wave
  REQUIRE(opt >= 0);
  CHECK_FALSE(d.acoustic[opt]);
  for (std::size_t i = 21; i < 40; ++i) CHECK(d.branches[opt][i].group_velocity < 0.0);
  for (std::size_t i = 1; i < 20; ++i) CHECK(d.branches[opt][i].group_velocity > 0.0);
}

TEST_CASE("lattice_dispersion: grid, symmetry omega(-k) = omega(k), branches followed through crossings", "[theory][lattice]") {
  const LatticeCell cell = fcc_cell({0.2 * k, k * delta, 0.0});
  const auto d = lattice_dispersion(cell, ez, l0, 61);
  REQUIRE(d.k.size() == 61);
  CHECK(d.k[30] == 0.0);
  CHECK_THAT(d.k.back(), WithinRel(std::numbers::pi / l0, 1e-15));
  CHECK(d.max_hermitian_defect < 1e-14);
  CHECK(d.min_omega2 >= -1e-3);
  for (int b = 0; b < 6; ++b)
    for (int i = 0; i < 61; ++i) {
      CHECK_THAT(d.branches[b][i].omega, WithinAbs(d.branches[b][60 - i].omega, 1e-9 * 1e6));
      // A followed branch keeps its family (its dominant pair of degrees of freedom).
      const auto& e = d.branches[b][i].content;
      const auto& e0 = d.branches[b][31].content;
      const double fam[3] = {e[0] + e[4], e[1] + e[3], e[2] + e[5]}, fam0[3] = {e0[0] + e0[4], e0[1] + e0[3], e0[2] + e0[5]};
      for (int f = 0; f < 3; ++f) CHECK_THAT(fam[f], WithinAbs(fam0[f], 1e-9));
    }
  // kt/k = 0.2: torsion (sqrt(16 kt a^2/I) at k = 0) crosses the P branch; followed, not sorted.
  int P = -1, T = -1;
  for (int b = 0; b < 6; ++b) {
    if (d.dominant[b] == 2) P = b;
    if (d.dominant[b] == 5) T = b;
  }
  REQUIRE(P >= 0);
  REQUIRE(T >= 0);
  CHECK(d.branches[P][60].omega > d.branches[T][60].omega);
  CHECK(d.branches[P][31].omega < d.branches[T][31].omega);
}

TEST_CASE("lattice_cell refuses a packing that is not a Bravais lattice", "[theory][lattice]") {
  auto net = fcc_network(4, 4, 8, dp, m, k, k, k * delta);
  std::string why;
  CHECK(lattice_cell(net, {}, {}, &why));
  net.particles[40].radius *= 1 + 1e-6;  // a polydisperse particle in the slab
  CHECK_FALSE(lattice_cell(net, {}, {}, &why));
  CHECK(why.find("particle 40") != std::string::npos);
  auto bare = fcc_network(4, 4, 8, dp, m, k, k, 0.0);
  for (auto& p : bare.particles) p.radius = 0.0;
  CHECK_FALSE(lattice_cell(bare, {}, {}, &why));
  CHECK(why.find("radius") != std::string::npos);
  CHECK_THROWS(lattice_dispersion(fcc_cell({}), ez, l0, 4));
  CHECK_THROWS(lattice_dispersion(fcc_cell({}), ez, 0.0, 5));
}

TEST_CASE("lattice_dispersion: coupled branches never cross (avoided crossings), whatever the grid", "[theory][lattice]") {
  // kt = k: the x-polarised S block ends with the rotation below the translation at the zone edge
  // (10 kt/m < (4k + 12 kt)/m); the acoustic branch stays the lower one and ends rotational.
  const Params p{k, k * delta, 0.5};
  const LatticeCell cell = fcc_cell(p);
  for (int nk : {5, 9, 65}) {
    const auto d = lattice_dispersion(cell, ez, l0, nk);
    int ac = -1, op = -1;
    for (int b = 0; b < 6; ++b) {
      if (d.dominant[b] == 0) ac = b;
      if (d.dominant[b] == 4) op = b;
    }
    REQUIRE(ac >= 0);
    REQUIRE(op >= 0);
    const Closed edge = closed_forms(p, std::numbers::pi);
    INFO("nk = " << nk);
    CHECK_THAT(d.branches[ac].back().omega2, WithinRel(edge.S_low, 1e-12));
    CHECK_THAT(d.branches[op].back().omega2, WithinRel(edge.S_high, 1e-12));
    CHECK(d.branches[ac].back().content[4] > 1 - 1e-12);  // theta_y at the edge
    for (std::size_t i = 0; i < d.k.size(); ++i) CHECK(d.branches[ac][i].omega < d.branches[op][i].omega);
  }
}

TEST_CASE("compare_ridge: finds a synthetic ridge on the branch, ignores lines outside the band", "[theory][lattice]") {
  const LatticeCell cell = fcc_cell({2.0 * k, k * delta, 0.5});
  const auto d = lattice_dispersion(cell, ez, l0, 201);
  int opt = -1;
  for (int b = 0; b < 6; ++b)
    if (d.dominant[b] == 4) opt = b;
  REQUIRE(opt >= 0);
  // A spectrum like granwave's: omega >= 0 by rows, signed k by columns.
  const double dw = 5000.0, dk = std::numbers::pi / l0 / 50;
  std::vector<double> w_axis, k_axis;
  for (int j = 0; j < 240; ++j) w_axis.push_back(j * dw);
  for (int s = -49; s <= 50; ++s) k_axis.push_back(s * dk);
  std::vector<double> F(w_axis.size() * k_axis.size(), 1e-6);
  for (std::size_t c = 0; c < k_axis.size(); ++c) {
    const double kc = k_axis[c];
    // The optical branch at |k| (closed form, lower sign flipped: the upper root), 0.4 bins high.
    const double w0 = std::sqrt(closed_forms({2.0 * k, k * delta, 0.5}, std::abs(kc) * l0).S_high) + 0.4 * dw;
    for (std::size_t j = 0; j < w_axis.size(); ++j) {
      double& a = F[j * k_axis.size() + c];
      if (kc < 0) a += std::exp(-0.5 * std::pow((w_axis[j] - w0) / (0.7 * dw), 2));
      a += 5.0 * std::exp(-0.5 * std::pow((w_axis[j] - 552000.0) / dw, 2));  // a flat line in the gap
    }
  }
  const auto r = compare_ridge(F, k_axis, w_axis, d, opt, -1);
  CHECK(r.columns > 20);
  CHECK(r.with_ridge == r.columns);
  CHECK(r.within_one_bin == r.columns);
  CHECK(r.max_offset_bins < 0.95);
  CHECK(r.median_offset_bins == Approx(0.4).margin(0.5));
  // On the k > 0 side there is no ridge inside the band (the gap line lies below it).
  const auto rp = compare_ridge(F, k_axis, w_axis, d, opt, +1);
  CHECK(rp.columns > 20);
  CHECK(rp.within_one_bin == 0);
  CHECK_THROWS(compare_ridge(std::vector<double>(3), k_axis, w_axis, d, opt, -1));
}

// ---- rolling and torsion resistance (Luding's full contact model), as angular springs ----

TEST_CASE("rolling and torsion: long waves unchanged, the zone edge moved by the closed form", "[theory][lattice]") {
  for (const auto& p : kRollingCases) {
    if (p.kt == 0.0) continue;
    Params bare = p;
    bare.kr = bare.ko = 0.0;
    const LatticeCell cell = fcc_cell(p), cell0 = fcc_cell(bare);
    const auto lw0 = lattice_long_wave(cell0, ez), lw = lattice_long_wave(cell, ez);
    for (int s = 0; s < 3; ++s) CHECK_THAT(lw.speed[s], WithinRel(lw0.speed[s], 1e-12));  // no turn at k = 0
    // The S branch at small k: the springs stiffen its rotations by O(q^2), which changes omega^2
    // by O(q^4): the relative change grows as q^2 (x4 for twice the q) and vanishes at k = 0, so
    // the long-wave speeds are those without them. The P branch has no rotation and no change.
    auto relative_change = [&](double q, int dof) {
      const auto with = lattice_modes(cell, ez, q / l0), without = lattice_modes(cell0, ez, q / l0);
      for (int b = 0; b < 6; ++b)
        if (with[b].dominant() == dof) {
          for (int c = 0; c < 6; ++c)
            if (without[c].dominant() == dof) return (with[b].omega2 - without[c].omega2) / without[c].omega2;
        }
      FAIL("no mode dominated by " << kLatticeDof[dof]);
      return 0.0;
    };
    const double r1 = relative_change(0.01, 0), r2 = relative_change(0.02, 0);
    INFO("relative change of the S branch's omega^2: " << r1 << " at q = 0.01, " << r2 << " at q = 0.02");
    CHECK(r1 > 0.0);
    CHECK(r1 < 1e-4);
    CHECK_THAT(r2 / r1, WithinRel(4.0, 1e-2));
    CHECK(std::abs(relative_change(0.01, 2)) < 1e-12);  // eigensolver round-off only
    // k = 0: the rotational frequencies are the tangential spring's alone.
    const auto m0 = lattice_modes(cell, ez, 0.0), b0 = lattice_modes(cell0, ez, 0.0);
    for (int b = 0; b < 6; ++b) CHECK_THAT(m0[b].omega2, WithinAbs(b0[b].omega2, 1e-12 * b0[5].omega2));
    // Zone edge (q = pi): the torsion branch rises by 8 (kr + ko)/I, the S optical diagonal by
    // (12 kr + 4 ko)/I.
    const double I = inertia_of(p), arm = arm_of(p);
    const auto edge = lattice_modes(cell, ez, std::numbers::pi / l0);
    const double torsion = (8 * p.kt * arm * arm + 8 * (p.kr + p.ko)) / I;
    bool found = false;
    for (const auto& md : edge) found = found || (md.content[5] > 0.99 && std::abs(md.omega2 - torsion) < 1e-12 * torsion);
    CHECK(found);
  }
}

TEST_CASE("rolling and torsion: group velocities (Hellmann-Feynman) equal the slope of the closed forms", "[theory][lattice]") {
  const Params p{1.0 * k, k * delta, 0.5, 2.0 * kta2, 1.0 * kta2};
  const LatticeCell cell = fcc_cell(p);
  check_group_velocities(p, cell);
}

TEST_CASE("rolling and torsion without a tangential spring: rotational acoustic branches", "[theory][lattice]") {
  // kt = 0: the turns are held by the rolling and torsion springs alone, which resist a relative turn:
  // I omega^2 = (6 kr + 2 ko)(1 - cos q) for theta_x, theta_y and 4 (kr + ko)(1 - cos q) for theta_z,
  // so omega -> 0 at k = 0 with a finite slope.
  const Params p{0.0, 0.0, 0.0, 1.0 * kta2, 0.3 * kta2};
  const auto d = lattice_dispersion(fcc_cell(p), ez, l0, 41);
  const double I = inertia_of(p);
  int rotational = 0;
  for (int b = 0; b < 6; ++b) {
    CHECK_FALSE(d.zero[b]);
    if (!d.rotational_acoustic[b]) continue;
    ++rotational;
    CHECK(std::string(d.kind(b)) == "rotational acoustic");
    const double w = d.dominant[b] == 5 ? 4 * (p.kr + p.ko) : 6 * p.kr + 2 * p.ko;
    for (std::size_t i = 0; i < d.k.size(); ++i)
      CHECK_THAT(d.branches[b][i].omega2, WithinAbs(w * (1 - std::cos(d.k[i] * l0)) / I, 1e-12 * 8 * w / I));
  }
  CHECK(rotational == 3);
  // Without them, the same lattice has three free rotations.
  const auto d0 = lattice_dispersion(fcc_cell({}), ez, l0, 41);
  int free_rotations = 0;
  for (int b = 0; b < 6; ++b) free_rotations += d0.zero[b] ? 1 : 0;
  CHECK(free_rotations == 3);
}
