// Seed 002 secs. 3.4 and 3.5 on granwave's crystal, measured with the one ruler (src/analysis):
//
// 1. The wavelength table of sec. 3.4: lambda = V T with T "the duration of the first oscillation
//    of a signal (based on first-arrival time, one per cent peak level)", lambda/l0 = 8, 9, 10, 16, 19
//    (+- 1) at z/l0 = 10, 15, 20, 80, 150 (a published number). T = the full first oscillation (1 %
//    arrival to the third 1 % crossing, measures.hpp) gives it; the leading pulse alone (the next
//    crossing) gives 6.0 .. 14.5. The full oscillation is also the wavelength in space: the length
//    of the first oscillation in a snapshot of the crystal when the first peak passes z.
//    The second table of sec. 3.4, lambda = 2 pi/k with k = (2/l0) arccos(V/V(k->0)), 8.3, 9.2, 10.1
//    l0 at z/l0 = 10, 15, 20: V is the local speed of the layer displacement's first peaks.
// 2. The kt trend of sec. 3.5 ("the first peak amplitude decreases as kt is increasing") for the P
//    wave, against its closed form. The displacement step moves the normal springs only (f_t = 0
//    at t = 0, data/SCHEMA.md [excitation]), so the held source pushes the first free layer with a
//    force F0 = 2 (k - f0/d') Delta per particle whatever kt is, while the chain of layers has the
//    stiffness K = 2 (k + kt - f0/d') (docs/design.md §3, the u_z block of the lattice dynamics):
//    m u_n'' = K (u_{n+1} - 2 u_n + u_{n-1}) + F0 delta_n1, so u_n(t) = (F0/K) w_n(t sqrt(K/m)) with
//    w the same for every kt. First peaks: u ~ 1/K, v ~ 1/sqrt(K) = V(0)/V(kt) (the lattice long-wave
//    speeds of the same packing), interface forces ~ F0, independent of kt. The layer stress
//    -sum (a - delta/2) u_z f_z (crystal::layer_stress) also turns and shortens the arm with the
//    step: per contact, to first order in the layer gap change D, d sigma ~ D (k + kt - 3 f0/d')
//    (the prestress f0 adds + f0/d' twice: the arm's delta/2 and the branch's direction), so its
//    first peak goes as (k + kt - 3 f0/d')/(k + kt - f0/d'): +0.07, +0.10, +0.13 % at kt/k = 0.5,
//    1, 2 against kt = 0 (delta/d' = 1e-3) - a rise, not the seed's fall.
#include <catch2/catch.hpp>

#include <array>
#include <cmath>
#include <cstdio>
#include <span>
#include <string>
#include <vector>

#include "analysis/measures.hpp"
#include "analysis/trace_analysis.hpp"
#include "config/case.hpp"
#include "crystal/packing.hpp"
#include "crystal/simulation.hpp"
#include "theory/crystal_theory.hpp"
#include "theory/lattice_dynamics.hpp"

using namespace granwave;

namespace {

config::Case seed_case(const char* name) {
  return config::load_case(std::string(GRANWAVE_SOURCE_DIR) + "/data/cases/" + name);
}

analysis::CrystalTrace to_trace(const crystal::RunResult& r, const crystal::Packing& pk, char mode) {
  analysis::CrystalTrace t;
  t.time = r.traces.time;
  t.layer_z = r.traces.layer_z;
  t.nt = r.traces.samples();
  t.nlayers = r.traces.nlayers;
  t.l0 = pk.l0;
  t.fixed_layers = pk.fixed_layers;
  t.mode = mode;
  t.mode_source = "case_toml";
  t.stress_zz = r.traces["layer_stress_zz"];
  t.stress_zx = r.traces["layer_stress_zx"];
  t.displacement_z = r.traces["layer_displacement_z"];
  t.displacement_x = r.traces["layer_displacement_x"];
  t.velocity_z = r.traces["layer_velocity_z"];
  t.velocity_x = r.traces["layer_velocity_x"];
  return t;
}

// Long-wave speed along z of the lattice dynamics with rotations and prestress of this packing.
double lattice_speed(const config::Case& c, const crystal::Packing& pk, bool shear) {
  const theory::ContactNetwork net = crystal::contact_network(c, pk);
  const auto cell = theory::lattice_cell(net, {pk.fixed_layers, pk.layers - 1 - pk.fixed_layers}, {});
  REQUIRE(cell);
  return theory::lattice_long_wave(*cell, theory::Vec3::UnitZ())
      .speed_along(shear ? theory::Vec3::UnitX() : theory::Vec3::UnitZ());
}

// First peak (measures.hpp) of field f minus its t = 0 value at the layer nearest z/l0 = zq,
// turned positive by its largest excursion.
double first_peak_at(const crystal::Traces& tr, const std::vector<double>& f, double l0, int zq) {
  std::size_t L = 0;
  while (L < tr.nlayers && std::lround(tr.layer_z[L] / l0) != zq) ++L;
  REQUIRE(L < tr.nlayers);
  std::vector<double> y(tr.samples());
  double big = 0.0;
  for (std::size_t i = 0; i < y.size(); ++i) {
    y[i] = f[i * tr.nlayers + L] - f[L];
    if (std::abs(y[i]) > std::abs(big)) big = y[i];
  }
  for (auto& v : y) v = big < 0.0 ? -v : v;
  const analysis::Peak p = analysis::first_peak(tr.time, y);
  REQUIRE(p.found);
  REQUIRE(p.index + 1 < y.size());  // a peak, not a signal still rising at the end
  return p.value;
}

}  // namespace

TEST_CASE("seed 002 sec. 3.4: lambda = V T over the full first oscillation gives the seed's 8, 9, 10, 16, 19 l0",
          "[crystal][wavelength][physics]") {
  // The 3200-particle P run of Figs. 2-4 (crystal_p: 4 x 4 x 200, 1.2 ms, 1 us output), about 1 s.
  const config::Case c = seed_case("crystal_p.toml");
  const crystal::Packing pk = crystal::make_packing(c);
  const crystal::RunResult r = crystal::simulate(c, pk);
  REQUIRE_FALSE(r.failed);
  const analysis::CrystalAnalysis a = analysis::analyze_crystal(to_trace(r, pk, 'P'));
  REQUIRE(a.period_reading == analysis::PeriodReading::oscillation);  // the default
  const int z[] = {10, 15, 20, 80, 150};
  const double seed[] = {8, 9, 10, 16, 19};
  for (int q = 0; q < 5; ++q) {
    const analysis::LayerMeasures* L = nullptr;
    for (const auto& x : a.layers)
      if (std::lround(x.z_over_l0) == z[q]) L = &x;
    REQUIRE(L);
    REQUIRE(L->arrived);
    const double lam = L->lambda_vt.value / a.l0, pulse = L->local_speed.value * L->duration.value / a.l0;
    const double space = L->oscillation_length.value / a.l0;
    std::printf("z/l0 = %3d: lambda/l0 = V T %.2f +- %.2f (leading pulse alone %.2f), first oscillation in the "
                "snapshot %.2f; seed %g +- 1\n",
                z[q], lam, L->lambda_vt.error / a.l0, pulse, space, seed[q]);
    INFO("z/l0 = " << z[q] << ": V T = " << lam << " l0, pulse reading " << pulse << ", snapshot " << space);
    // The seed's error margin, +- 1 (measured: 8.18, 9.28, 10.15, 15.78, 19.36).
    CHECK(std::abs(lam - seed[q]) <= 1.0);
    // The leading pulse alone is about 3/4 of it (measured 5.97 .. 14.54): outside the margin at
    // every position but the last.
    if (q < 4) CHECK(pulse < seed[q] - 1.0);
    // In space: far from the source, where the wavelength changes little over one wavelength, the
    // snapshot's first oscillation is V T to 2 % (measured 0.7 % and 0.6 %). Near the source it grows
    // by ~0.2 l0 per layer, and the two readings, centred half a wavelength apart, differ by ~5 %.
    if (z[q] >= 80) CHECK(std::abs(space / lam - 1.0) < 0.02);
    else CHECK(std::abs(space / lam - 1.0) < 0.08);
  }
  // The other reading on request (analyze --period pulse, [analysis] period = "pulse").
  analysis::CrystalAnalysisOptions o;
  o.period = analysis::PeriodReading::pulse;
  const analysis::CrystalAnalysis b = analysis::analyze_crystal(to_trace(r, pk, 'P'), o);
  CHECK(b.period_source == "option");
  for (std::size_t i = 0; i < b.layers.size(); ++i)
    if (std::isfinite(b.layers[i].lambda_vt.value))
      CHECK(b.layers[i].lambda_vt.value == a.layers[i].local_speed.value * a.layers[i].duration.value);
}

TEST_CASE("seed 002 sec. 3.4: 2 pi/k(V) from the displacement's first peaks gives the seed's 8.3, 9.2, 10.1 l0",
          "[crystal][wavelength][physics]") {
  // The seed's second table: k = (2/l0) arccos(V/V(k->0)), the group speed V(k->0) cos(k l0/2) of
  // omega_0 sin(k l0/2) set equal to "the local wave-speed", lambda = 2 pi/k = 8.3, 9.2, 10.1, 13.9,
  // 17.0 l0 at z/l0 = 10, 15, 20, 80, 150, with V ~ 208 m/s at z/l0 ~ 20. (The phase speed
  // omega/k = V(k->0) sin(x)/x, x = k l0/2, would put 208 m/s at lambda = 5.8 l0: not the seed's
  // pairing.) V = the five-layer local speed of the first peaks of the layer displacement u_z, the
  // default reading, gives them; that of the stress's first peaks (Fig. 4's V, lambda = V T's) runs
  // ~5 m/s faster near the source and gives 10.7, 12.5, 13.9.
  const config::Case c = seed_case("crystal_p.toml");
  const crystal::Packing pk = crystal::make_packing(c);
  const crystal::RunResult r = crystal::simulate(c, pk);
  REQUIRE_FALSE(r.failed);
  const analysis::CrystalAnalysis a = analysis::analyze_crystal(to_trace(r, pk, 'P'));
  REQUIRE(a.wavenumber_speed == analysis::WavenumberSpeed::displacement_peak);  // the default
  REQUIRE(a.wavenumber_speed_field == "layer_displacement_z");
  const double two_pi = 2.0 * std::acos(-1.0), vk0 = a.dispersion.v_k0;
  const int z[] = {10, 15, 20, 80, 150};
  const double seed[] = {8.3, 9.2, 10.1, 13.9, 17.0};
  for (int q = 0; q < 5; ++q) {
    const analysis::LayerMeasures* L = nullptr;
    for (const auto& x : a.layers)
      if (std::lround(x.z_over_l0) == z[q]) L = &x;
    REQUIRE(L);
    REQUIRE(std::isfinite(L->k_from_speed.value));
    const double k = L->k_from_speed.value, lam = two_pi / k / a.l0, err = two_pi * L->k_from_speed.error / (k * k) / a.l0;
    const double lam_stress = two_pi / analysis::wavenumber_from_speed(L->local_speed.value, vk0, a.l0) / a.l0;
    std::printf("z/l0 = %3d: lambda/l0 = 2 pi/k %.2f +- %.2f (V = %.2f m/s); from the stress's first peak %.2f "
                "(V = %.2f); seed %g\n",
                z[q], lam, err, L->k_speed.value, lam_stress, L->local_speed.value, seed[q]);
    INFO("z/l0 = " << z[q] << ": 2 pi/k = " << lam << " +- " << err << " l0, stress reading " << lam_stress);
    if (q >= 3) continue;  // far rows: reported (15.7, 19.2 against 13.9, 17.0), not asserted
    // The seed prints one decimal (+- 0.05) of a V read off its Fig. 4; ours carries a standard error
    // of 0.12-0.16 l0 (the scatter of the four delays, mostly the acceleration itself): 0.15 is
    // about their sum in quadrature. Measured 8.21, 9.27, 10.10.
    CHECK(std::abs(lam - seed[q]) <= 0.15);
    CHECK(err < 0.2);
    // The other reading is far outside it (measured +2.4 .. +3.8 l0).
    CHECK(lam_stress - seed[q] > 2.0);
  }
  // The seed's "~ 208 m/s at z/l0 ~ 20" (three digits): measured 207.70.
  for (const auto& L : a.layers)
    if (std::lround(L.z_over_l0) == 20) CHECK(std::abs(L.k_speed.value - 208.0) <= 0.5);
  // The stress's first peaks on request (analyze --wavenumber-speed first_peak, [analysis]
  // wavenumber_speed = "first_peak"): k's V is then the local speed of lambda = V T.
  analysis::CrystalAnalysisOptions o;
  o.wavenumber_speed = analysis::WavenumberSpeed::first_peak;
  const analysis::CrystalAnalysis b = analysis::analyze_crystal(to_trace(r, pk, 'P'), o);
  CHECK(b.wavenumber_speed_source == "option");
  int n = 0;
  for (const auto& L : b.layers)
    if (std::isfinite(L.local_speed.value)) {
      ++n;
      CHECK(L.k_speed.value == L.local_speed.value);
    }
  CHECK(n > 150);
}

TEST_CASE("seed 002 sec. 3.5 kt trend, P wave: the first peaks of stress, v and u follow the closed forms",
          "[crystal][wavelength][physics]") {
  // 3 x 3 x 40 crystal, dt = 1e-7 s stored every other step (0.2 us); z/l0 = 5, 10, 20, all before
  // the reflection from the far end returns.
  struct Peaks {
    double v_lattice;
    double geometric;         // f0/d' (N/m) of a contact between free particles
    std::array<double, 9> p;  // (sigma, v, u) at z/l0 = 5, 10, 20
  };
  const int zs[] = {5, 10, 20};
  auto run = [&](double kt_over_k) {
    config::Case c = seed_case("crystal_p.toml");
    c.contact.get<contact::LinearLudingParams>().kt = kt_over_k * c.contact.get<contact::LinearLudingParams>().kn;
    c.crystal->cells = {3, 3, 40};
    c.integrator.t_end = 1.6e-4;
    c.integrator.dt = 1e-7;
    c.output.interval = 2e-7;
    const crystal::Packing pk = crystal::make_packing(c);
    const crystal::RunResult r = crystal::simulate(c, pk);
    REQUIRE_FALSE(r.failed);
    Peaks out{lattice_speed(c, pk, false), 0.0, {}};
    for (const auto& q : crystal::list_contacts(pk, false))
      if (!pk.fixed[q.i] && !pk.fixed[q.j]) {
        out.geometric = c.contact.get<contact::LinearLudingParams>().kn * q.overlap / std::sqrt(q.bx * q.bx + q.by * q.by + q.bz * q.bz);
        break;
      }
    REQUIRE(out.geometric > 0.0);
    for (int q = 0; q < 3; ++q) {
      out.p[3 * q + 0] = first_peak_at(r.traces, r.traces["layer_stress_zz"], pk.l0, zs[q]);
      out.p[3 * q + 1] = first_peak_at(r.traces, r.traces["layer_velocity_z"], pk.l0, zs[q]);
      out.p[3 * q + 2] = first_peak_at(r.traces, r.traces["layer_displacement_z"], pk.l0, zs[q]);
    }
    return out;
  };
  const Peaks p0 = run(0.0);
  const double k = 1e5;  // crystal_p's kn
  for (double kt : {0.5, 1.0, 2.0}) {
    const Peaks p = run(kt);
    const double v_ratio = p0.v_lattice / p.v_lattice;  // sqrt((k - f0/d')/(k + kt - f0/d'))
    const double g = p.geometric;
    const double s_ratio = ((k + kt * k - 3 * g) / (k + kt * k - g)) / ((k - 3 * g) / (k - g));
    for (int q = 0; q < 3; ++q) {
      const double s = p.p[3 * q] / p0.p[3 * q], v = p.p[3 * q + 1] / p0.p[3 * q + 1], u = p.p[3 * q + 2] / p0.p[3 * q + 2];
      std::printf("P, kt/k = %g, z/l0 = %2d: first peak / kt = 0: sigma_zz %.5f (closed form %.5f), v_z %.5f (%.5f), "
                  "u_z %.5f (%.5f)\n",
                  kt, zs[q], s, s_ratio, v, v_ratio, u, v_ratio * v_ratio);
      INFO("kt/k = " << kt << ", z/l0 = " << zs[q]);
      // The closed forms to 3e-4 (measured within 1.4e-4 at dt = 1e-7 s, 4.3e-4 at 2e-7: the Verlet
      // phase error, growing with z and kt; the trend itself is 18 % .. 67 % for v and u, and the
      // stress's +0.07 .. +0.13 % is resolved: 1 would be off by up to 4 times the tolerance).
      CHECK(std::abs(v / v_ratio - 1.0) < 3e-4);
      CHECK(std::abs(u / (v_ratio * v_ratio) - 1.0) < 3e-4);
      CHECK(std::abs(s / s_ratio - 1.0) < 3e-4);
    }
  }
}

TEST_CASE("seed 002 sec. 3.5 kt trend, S wave: the first peaks of stress and velocity fall with kt",
          "[crystal][wavelength][physics]") {
  // The S wave turns the particles (the (u_x, theta_y) block): no single factor, but the seed's
  // statement holds for every quantity. Measured at z/l0 = 10, kt = k: sigma_zx x0.85, v_x x0.58.
  auto peaks = [](double kt_over_k) {
    config::Case c = seed_case("crystal_p.toml");
    c.contact.get<contact::LinearLudingParams>().kt = kt_over_k * c.contact.get<contact::LinearLudingParams>().kn;
    c.excitation.mode = config::Excitation::Mode::S;
    c.crystal->cells = {3, 3, 40};
    c.integrator.t_end = 1.6e-4;
    c.output.interval = 2e-7;
    const crystal::Packing pk = crystal::make_packing(c);
    const crystal::RunResult r = crystal::simulate(c, pk);
    REQUIRE_FALSE(r.failed);
    return std::array<double, 2>{first_peak_at(r.traces, r.traces["layer_stress_zx"], pk.l0, 10),
                                 first_peak_at(r.traces, r.traces["layer_velocity_x"], pk.l0, 10)};
  };
  const auto p0 = peaks(0.0), p1 = peaks(1.0);
  std::printf("S, kt/k = 1, z/l0 = 10: first peak / kt = 0: sigma_zx %.4f, v_x %.4f\n", p1[0] / p0[0], p1[1] / p0[1]);
  CHECK(p1[0] / p0[0] < 0.95);
  CHECK(p1[1] / p0[1] < 0.75);
}
