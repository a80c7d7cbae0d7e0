// granwave theory CASE [--json] [--layers LO:HI] [--nk N]: eq. (10) of seed 002 from the case's
// actual contact network (regular or polydisperse, relaxed as `granwave build` would), the derived
// sound speeds, anisotropy ratios, lattice omega_0 and the two-body t_c and restitution; for a
// monodisperse (Bravais) packing also the lattice dynamics with rotations along z
// (theory/lattice_dynamics.hpp): long-wave speeds and all six branches over the zone.
// src/theory/ stays pure (no crystal dependency); the packing is built here (cli links all).
#include <cmath>
#include <cstdio>
#include <iostream>
#include <numbers>
#include <string>

#include "cli/theory_json.hpp"
#include "cli/theory_relaxed.hpp"
#include "cli/verbs.hpp"
#include "config/case.hpp"
#include "config/contact_laws.hpp"
#include "core/error.hpp"
#include "core/format.hpp"
#include "core/json.hpp"
#include "core/resources.hpp"
#include "crystal/packing.hpp"
#include "crystal/simulation.hpp"
#include "impact/impact.hpp"
#include "theory/hertz.hpp"
#include "theory/crystal_theory.hpp"
#include "theory/lattice_dynamics.hpp"

namespace granwave::cli {
namespace {

constexpr const char* kTheoryHelp = R"(usage: granwave theory CASE.toml [--json] [--layers LO:HI] [--nk N]

Continuum and lattice predictions for a crystal case (seed 002 secs. 2.1, 3.3, 3.4), from the
packing's actual contact network (polydisperse packings are relaxed first, as in `build`):
  C        the stiffness tensor of eq. (10), full 3x3x3x3, with the affine kt term (major but not
           minor symmetry), C_frictionless without it, and the Voigt 6x6 of its symmetrised part
  V_pz, V_sz, V_sy   sqrt(C_zzzz/rho), sqrt(C_zxzx/rho), sqrt(C_zyzy/rho), rho = bulk density of
           the representative slab (particle mass / slab volume)
  ratios   C_xxxx/C_zzzz, C_zxzx/C_yxyx, C_zzzz/C_zxzx (frictionless FCC: 1.25, 2, 2)
  omega_0  of omega = omega_0 sin(k l0/2) from the nearest-layer dynamical matrix (P and S),
           v_k0 = omega_0 l0/2; also with the geometric stiffness of the static contact forces
  t_c, restitution   two-body linear spring-dashpot collision of two mean particles (sec. 2.1)
  lattice  Bloch waves along z of the packing as built, one particle with 3 translations and
           3 rotations (I = 2/5 m a^2): normal springs, tangential springs with the case's lever
           arm ([contact] lever_arm), the static contact forces' geometric stiffness; the
           long-wave speeds V_pz_lattice, V_sz_lattice (x-polarised), V_sy_lattice, and the six
           branches omega_b(k) for k in [-pi/l0, pi/l0] with their polarisations. Needs a
           Bravais lattice: omitted, with a note, for a polydisperse packing.
  relaxed  the non-affine tensor A_relaxed (theory/relaxed_moduli.hpp): every free particle's
           translation and rotation relaxed under a homogeneous strain, with the prestress's
           geometric term; rho V^2 = eigenvalues of A_abgf m_a m_g. Slab: the fixed layers (a
           file's packing: its source and top slabs) moved affinely; bulk: the packing closed across
           z (a file's: its triply periodic packing relaxed by FIRE). V_pz, V_sz, V_sy, rattlers, zero modes
           (free rotations, translations, mechanisms), sliding contacts (all treated as sticking)
  effective medium   the affine estimate at the packing's non-rattler Z, solid fraction and mean
           stress: Walton's K, G for Hertz-Mindlin, the isotropic linear-spring K, G otherwise
Index convention: C[a][b][g][f] with a, g branch (gradient) directions and b, f displacement
(force) directions; sigma_ab = C_abgf du_f/dx_g.

  --layers LO:HI   representative slab (layer indices, inclusive); default: the free layers
  --nk N           points of the lattice k grid over the zone (odd, 3..10001; default 65)
  --json           one JSON object; every number as {"value": v, "unit": u}; top-level keys
                   V_pz, V_sz, V_sy, t_c, restitution, omega_0 (= omega_0 of P), omega_0_s, v_k0,
                   v_k0_s, rho_bulk, l0, ratios, C, C_frictionless, C_voigt_sym, V_pz_lattice,
                   V_sz_lattice, V_sy_lattice, lattice (details, or the note why it is omitted),
                   dispersion (k grid; per branch omega, group velocity, translation/rotation
                   fractions and the fraction in each of u_x u_y u_z theta_x theta_y theta_z),
                   relaxed {slab, bulk}, effective_medium (data/SCHEMA.md), ...
)";

// Eq. (10)'s index convention (the help's "Index convention").
constexpr const char* kCIndexOrder = "C[a][b][g][f]: a,g branch, b,f displacement";

int parse_nk(const std::string& s) {
  std::size_t used = 0;
  const double v = leading_number(s, &used);
  const int n = v >= 3 && v <= 10001 ? static_cast<int>(v) : 0;
  if (used != s.size() || s.empty() || n != v || n % 2 == 0)
    throw InputError("--nk " + s + ": must be an odd integer in [3, 10001] (points of the k grid over the zone)");
  return n;
}

// The lattice-dynamics part: with the packing's prestress (the top-level numbers) and without it.
struct LatticePart {
  bool available = false;
  std::string note;
  theory::LatticeCell cell;
  theory::LatticeLongWave lw, lw_unstressed;
  theory::LatticeDispersion disp;
  double l0 = 0.0, arm = 0.0, f0 = 0.0;
};

LatticePart lattice_part(const config::Case& c, const theory::ContactNetwork& net, theory::SlabSelection slab, int nk) {
  LatticePart L;
  if (c.crystal->polydispersity > 0.0) {
    L.note = "omitted: a polydisperse packing (polydispersity = " + fmt("%.10g", c.crystal->polydispersity) +
             " delta) is not a Bravais lattice; Bloch waves of one particle do not describe it";
    return L;
  }
  // Contact forces come from overlaps of positions far larger than them: at delta_0 = 1e-5 d and
  // z = 0.28 m the overlap's rounding (1e-16 z) is 1.5e-9 of it, a Hertz force's 2.3e-9. The cell's
  // bonds are the reference particle's either way; the tolerance only decides whether all agree.
  const theory::LatticeCellOptions opt = crystal::lattice_options(c, 1e-6);
  std::string why;
  const auto cell = theory::lattice_cell(net, slab, opt, &why);
  if (!cell) {
    L.note = "omitted: " + why;
    return L;
  }
  L.available = true;
  L.cell = *cell;
  const theory::Vec3 ez = theory::Vec3::UnitZ();
  L.l0 = theory::layer_period(L.cell, ez);
  if (!(L.l0 > 0.0)) throw RunError("theory: the packing has no contacts between layers");
  L.lw = theory::lattice_long_wave(L.cell, ez);
  theory::LatticeCell bare = L.cell;
  for (auto& b : bare.bonds) b.f0 = 0.0;
  L.lw_unstressed = theory::lattice_long_wave(bare, ez);
  L.disp = theory::lattice_dispersion(L.cell, ez, L.l0, nk);
  L.arm = L.cell.bonds.front().arm;
  L.f0 = L.cell.bonds.front().f0;
  return L;
}

Json dispersion_json(const LatticePart& L) {
  const auto& d = L.disp;
  std::vector<double> kl0;
  for (double k : d.k) kl0.push_back(k * L.l0);
  Json branches = Json::array();
  for (int b = 0; b < 6; ++b) {
    std::vector<double> w, vg, tr, rot;
    std::array<std::vector<double>, 6> frac;
    for (const auto& m : d.branches[b]) {
      w.push_back(m.omega);
      vg.push_back(m.group_velocity);
      tr.push_back(m.translation());
      rot.push_back(m.rotation());
      for (int i = 0; i < 6; ++i) frac[i].push_back(m.content[i]);
    }
    Json br = {{"dominant", theory::kLatticeDof[d.dominant[b]]},
               {"kind", d.kind(b)},
               {"omega", values(w, "1/s")},
               {"group_velocity", values(vg, "m/s")},
               {"translation", tr},
               {"rotation", rot}};
    for (int i = 0; i < 6; ++i) br[theory::kLatticeDof[i]] = frac[i];
    branches.push_back(br);
  }
  return {{"direction", {0, 0, 1}},
          {"zone", "k in [-pi/l0, pi/l0]"},
          {"l0", quantity(L.l0, "m")},
          {"k", values(d.k, "1/m")},
          {"k_l0", values(kl0, "1")},
          {"dof", theory::kLatticeDof},
          {"note", "branches followed through crossings from k = 0; fractions are |e_i|^2 of the mass-weighted "
                   "eigenvector; omega(-k) = omega(k); group velocity d omega/dk"},
          {"max_hermitian_defect", d.max_hermitian_defect},
          {"min_omega2", quantity(d.min_omega2, "1/s^2")},
          {"branches", branches}};
}

}  // namespace

int cmd_theory(const Args& args) { return cmd_theory(args, std::cout); }

int cmd_theory(const Args& args, std::ostream& out) {
  if (wants_help(args)) {
    out << kTheoryHelp;
    return 0;
  }
  for (std::size_t i = 0; i < args.size(); ++i) {
    const std::string& a = args[i];
    if (a == "--layers" || a == "--nk") {
      ++i;
      continue;
    }
    if (a.rfind("-", 0) == 0 && a != "--json" && a.rfind("--layers=", 0) != 0 && a.rfind("--nk=", 0) != 0)
      throw InputError("theory: unknown option '" + a + "' (see granwave theory --help)");
  }
  const auto pos = positionals(args, {"--layers", "--nk"});
  if (pos.size() != 1) throw InputError("theory: expected one case file (granwave theory --help)");
  const bool json = has_flag(args, "--json");
  int nk = 65;
  if (const auto s = option_value(args, "", "--nk"); !s.empty()) nk = parse_nk(s);
  const config::Case c = config::load_case(pos[0]);
  if (c.model == config::Model::impact) {  // Hertz, the damping's restitution, Coulomb's oblique impact
    impact::print_theory(c, json, out);
    return 0;
  }
  if (c.model != config::Model::crystal || !c.crystal)
    throw InputError(pos[0] + ": granwave theory covers crystal cases (eq. (10)); for a chain's Hertz numbers use granwave check");
  const auto& cr = *c.crystal;

  const crystal::Packing pk = crystal::make_packing(c);
  // The contact as eq. (10) sees it: the linear law's keys, or Hertz-Mindlin linearised at each
  // contact's overlap (delta_0 for a regular packing: k_n = 2 E* sqrt(R* delta_0), k_t = 8 G*
  // sqrt(R* delta_0)); the prestress f0 is each contact's own static force (k delta, or Hertz's).
  const config::ContactLawInfo& law = config::law_of(c.contact);
  const bool hertz = law.hertz_normal;  // Hertz's normal force: its two-body impact (theory/hertz.hpp)
  const double delta_0 = crystal::linearisation_overlap(c, pk);
  const crystal::ContactAt k0 = crystal::contact_at(c, delta_0);
  const theory::ContactNetwork net = crystal::contact_network(c, pk);

  theory::SlabSelection slab{pk.fixed_layers, pk.layers - 1 - pk.fixed_layers};
  if (pk.from_file()) {  // a file's packing: the bins between the source's and the top slab's
    int top = pk.layers;
    for (std::size_t q = 0; q < pk.size(); ++q)
      if (pk.role[q] == crystal::role_fixed_top) top = std::min(top, pk.layer[q]);
    slab = {pk.source_bins(), std::max(pk.source_bins(), top - 1)};
  }
  if (const auto s = option_value(args, "", "--layers"); !s.empty()) parse_layers(s, "layer indices", &slab.layer_lo, &slab.layer_hi);
  if (slab.layer_hi >= pk.layers) throw InputError("--layers: the case has " + std::to_string(pk.layers) + " layers");
  const auto r = theory::crystal_prediction(net, slab);
  const LatticePart L = lattice_part(c, net, slab, nk);
  const RelaxedPart relaxed = relaxed_part(c, pk, net);
  const theory::Vec3 ex = theory::Vec3::UnitX(), ey = theory::Vec3::UnitY(), ez = theory::Vec3::UnitZ();

  // Sec. 2.1: the collision of two particles of the mean radius.
  const double m = cr.density * 4.0 / 3.0 * std::numbers::pi * cr.radius * cr.radius * cr.radius;
  const bool clip = c.contact.friction().clip();
  const auto tc = theory::linear_contact_time(k0.kn, k0.gamma_n, 0.5 * m, clip);
  // Hertz: the two-body impact of two free mean particles (no confinement), closing at v_impact:
  // the excitation's velocity for a velocity drive, else 1 m/s (t_c scales as v^(-1/5)).
  theory::HertzImpact impact;
  theory::DampedHertzImpact damped;
  if (hertz) {
    damped = theory::damped_hertz_impact(c.contact.number("damping_ratio").value_or(0.0), clip);
    const double E = *c.contact.number("youngs_modulus"), nu = *c.contact.number("poisson_ratio"), E_star = E / (2.0 * (1.0 - nu * nu));
    const double A = 4.0 / 3.0 * E_star * std::sqrt(0.5 * cr.radius);
    const bool velocity = c.excitation.drive == config::Excitation::Drive::velocity;
    impact = theory::hertz_impact(A, m, m, velocity ? std::abs(c.excitation.amplitude) : 1.0);
  }

  if (json) {
    Json o = {{"case", c.name},
              {"model", "crystal"},
              {"contact_law", crystal::contact_law_name(c.contact)},
              {"k_n", quantity(k0.kn, "N/m")},
              {"k_t", quantity(k0.kt, "N/m")},
              {"gamma_n", quantity(k0.gamma_n, "kg/s")},
              {"f0", quantity(k0.f_n, "N")},
              {"delta_0", quantity(delta_0, "m")}};
    if (law.linearisation_note) o["linearisation"] = law.linearisation_note;
    if (hertz)
      o["hertz_impact"] = {
          {"velocity", quantity(impact.velocity, "m/s")},
          {"t_c", quantity(impact.contact_time, "s")},
          {"max_overlap", quantity(impact.max_overlap, "m")},
          {"peak_force", quantity(impact.peak_force, "N")},
          {"A", quantity(impact.hertz_constant, "N/m^1.5")},
          {"restitution", quantity(damped.restitution, "1")},
          {"t_c_damped", quantity(damped.time_ratio * impact.contact_time, "s")},
          {"note", "two free mean particles closing at velocity (the velocity drive's, else 1 m/s): t_c = 2.86827 "
                   "(m*^2/(R* E*^2 v))^(1/5), delta_max = (5 m* v^2/(4 A))^(2/5) (elastic); restitution and t_c_damped with "
                   "the case's damping_ratio (and normal_tension), the same at every velocity"}};
    o["V_pz"] = quantity(r.V_pz, "m/s");
    o["V_sz"] = quantity(r.V_sz, "m/s");
    o["V_sy"] = quantity(r.V_sy, "m/s");
    o["V_pz_frictionless"] = quantity(r.V_pz_frictionless, "m/s");
    o["V_sz_frictionless"] = quantity(r.V_sz_frictionless, "m/s");
    o["t_c"] = quantity(tc.t_c, "s");
    o["restitution"] = quantity(tc.restitution, "1");
    o["contact_omega"] = quantity(tc.omega, "1/s");
    o["eta_0"] = quantity(tc.eta0, "1/s");
    o["omega_0"] = quantity(r.omega0_p, "1/s");
    o["omega_0_s"] = quantity(r.omega0_s, "1/s");
    o["v_k0"] = quantity(r.V_k0_p, "m/s");
    o["v_k0_s"] = quantity(r.V_k0_s, "m/s");
    o["omega_0_prestressed"] = quantity(r.omega0_p_prestressed, "1/s");
    o["omega_0_s_prestressed"] = quantity(r.omega0_s_prestressed, "1/s");
    o["rho_bulk"] = quantity(r.rho_bulk, "kg/m^3");
    o["l0"] = quantity(r.l0, "m");
    o["d"] = quantity(pk.d, "m");
    o["d_prime"] = quantity(pk.d_prime, "m");
    o["coordination"] = quantity(r.coordination, "1");
    o["slab"] = {{"layer_lo", r.layer_lo},
                 {"layer_hi", r.layer_hi},
                 {"particles", r.n_particles},
                 {"volume", quantity(r.volume, "m^3")},
                 {"mass", quantity(r.mass, "kg")}};
    o["ratios"] = {{"C_xxxx/C_zzzz", quantity(r.ratio_xxxx_zzzz, "1")},
                   {"C_zxzx/C_yxyx", quantity(r.ratio_zxzx_yxyx, "1")},
                   {"C_zzzz/C_zxzx", quantity(r.ratio_zzzz_zxzx, "1")}};
    o["major_asymmetry"] = quantity(r.major_asymmetry, "1");
    o["minor_asymmetry"] = quantity(r.minor_asymmetry, "1");
    if (L.available) {
      o["V_pz_lattice"] = quantity(L.lw.speed_along(ez), "m/s");
      o["V_sz_lattice"] = quantity(L.lw.speed_along(ex), "m/s");
      o["V_sy_lattice"] = quantity(L.lw.speed_along(ey), "m/s");
      const std::vector<double> wr(L.lw.omega_rotation_k0.begin(), L.lw.omega_rotation_k0.end());
      o["lattice"] = {{"available", true},
                      {"note", "Bloch waves along z with rotations; speeds include the prestress's geometric stiffness "
                               "(unstressed: without it; affine: rotations held, eq. (10)'s kind)"},
                      {"mass", quantity(L.cell.mass, "kg")},
                      {"inertia", quantity(L.cell.inertia, "kg m^2")},
                      {"contacts", L.cell.bonds.size()},
                      {"lever_arm", quantity(L.arm, "m")},
                      {"lever_arm_convention", contact::lever_arm_name(c.contact.friction().lever_arm)},
                      {"f0", quantity(L.f0, "N")},
                      {"k_roll", quantity(L.cell.bonds.front().k_roll, "N m/rad")},
                      {"k_twist", quantity(L.cell.bonds.front().k_twist, "N m/rad")},
                      {"l0", quantity(L.l0, "m")},
                      {"V_pz_unstressed", quantity(L.lw_unstressed.speed_along(ez), "m/s")},
                      {"V_sz_unstressed", quantity(L.lw_unstressed.speed_along(ex), "m/s")},
                      {"V_pz_affine", quantity(L.lw.speed_along(ez, false), "m/s")},
                      {"V_sz_affine", quantity(L.lw.speed_along(ex, false), "m/s")},
                      {"omega_rotation_k0", values(wr, "1/s")}};
      o["dispersion"] = dispersion_json(L);
    } else {
      o["lattice"] = {{"available", false}, {"note", L.note}};
    }
    o["C"] = tensor_json(r.C, kCIndexOrder);
    o["C_frictionless"] = tensor_json(r.C_frictionless, kCIndexOrder);
    Json voigt = Json::array();
    for (int I = 0; I < 6; ++I) {
      Json row = Json::array();
      for (int J = 0; J < 6; ++J) row.push_back(r.C_voigt_sym(I, J));
      voigt.push_back(row);
    }
    o["C_voigt_sym"] = {{"unit", "Pa"}, {"order", {"xx", "yy", "zz", "yz", "xz", "xy"}}, {"values", voigt}};
    add_relaxed_json(o, relaxed);
    out << json_text(o);
    return 0;
  }

  if (pk.from_file())
    std::printf("case %s: a packing from %s (%s), %zu particles relaxed as a run starts, %d z-bins of h = %.6g m (free "
                "bins %d..%d), mean diameter %.6g m, k = %g N/m, kt = %g N/m\n",
                c.name.c_str(), pk.source_file.c_str(), pk.source_format.c_str(), pk.size(), pk.layers, pk.bin_width,
                slab.layer_lo, slab.layer_hi, pk.d, net.k, net.kt);
  else
    std::printf("case %s: FCC %d x %d x %d, d = %.6g m, d' = %.6g m, l0 = %.6g m, k = %g N/m, kt = %g N/m\n",
                c.name.c_str(), pk.nx, pk.ny, pk.layers, pk.d, pk.d_prime, r.l0, net.k, net.kt);
  if (hertz) {
    std::printf("Hertz-Mindlin linearised at delta_0 = %.6g m: k_n = 2 E* sqrt(R* delta_0) = %.6g N/m, k_t = 8 G* sqrt(R* "
                "delta_0) = %.6g N/m, f0 = %.6g N, gamma_n = %.6g kg/s\n",
                delta_0, k0.kn, k0.kt, k0.f_n, k0.gamma_n);
    std::printf("Hertz impact of two free particles at %.4g m/s: t_c = %.6g s, delta_max = %.6g m, peak force %.6g N "
                "(elastic); with damping_ratio %g: restitution %.6f, t_c = %.6g s (at any velocity: t_c ~ v^(-1/5))\n",
                impact.velocity, impact.contact_time, impact.max_overlap, impact.peak_force, c.contact.number("damping_ratio").value_or(0.0),
                damped.restitution, damped.time_ratio * impact.contact_time);
  }
  std::printf("representative slab: layers %d..%d, %d particles, coordination %.4f, rho_bulk = %.6g kg/m^3\n",
              r.layer_lo, r.layer_hi, r.n_particles, r.coordination, r.rho_bulk);
  std::printf("eq. (10): C_zzzz = %.6g Pa, C_zxzx = %.6g Pa, C_xxxx = %.6g Pa, C_yxyx = %.6g Pa\n", r.C(2, 2, 2, 2),
              r.C(2, 0, 2, 0), r.C(0, 0, 0, 0), r.C(1, 0, 1, 0));
  std::printf("ratios: C_xxxx/C_zzzz = %.6f, C_zxzx/C_yxyx = %.6f, C_zzzz/C_zxzx = %.6f\n", r.ratio_xxxx_zzzz,
              r.ratio_zxzx_yxyx, r.ratio_zzzz_zxzx);
  std::printf("symmetry: major %.2e, minor %.2e (kt term: major only)\n", r.major_asymmetry, r.minor_asymmetry);
  std::printf("V_pz = %.4f m/s, V_sz = %.4f m/s, V_sy = %.4f m/s (frictionless: %.4f, %.4f)%s\n", r.V_pz, r.V_sz, r.V_sy,
              r.V_pz_frictionless, r.V_sz_frictionless,
              law.stiffness_of_overlap ? " (no rotations; linearised at each contact's overlap)" : "");
  std::printf("lattice: omega_0 = %.1f 1/s (P), %.1f 1/s (S); v_k0 = omega_0 l0/2 = %.4f, %.4f m/s\n", r.omega0_p,
              r.omega0_s, r.V_k0_p, r.V_k0_s);
  std::printf("         with the static contact forces' geometric stiffness: %.1f, %.1f 1/s\n", r.omega0_p_prestressed,
              r.omega0_s_prestressed);
  std::printf("contact (sec. 2.1%s, m_ij = m/2 = %.6g kg, %s): t_c = %.6g s, restitution = %.6f, eta_0 = %.6g 1/s\n",
              law.stiffness_of_overlap ? ", linearised" : "", 0.5 * m, clip ? "clip" : "allow", tc.t_c, tc.restitution, tc.eta0);
  if (L.available) {
    std::printf("lattice dynamics along z (rotations, I = 2/5 m a^2, lever arm %.6g m (%s), prestress f0 = %.4g N):\n",
                L.arm, c.contact.friction().lever_arm == contact::LeverArm::contact_point ? "contact point" : "radius", L.f0);
    std::printf("  long waves: V_pz = %.4f m/s, V_sz = %.4f m/s, V_sy = %.4f m/s (without prestress %.4f, %.4f;\n"
                "  rotations held, eq. (10)'s kind: %.4f, %.4f)\n",
                L.lw.speed_along(ez), L.lw.speed_along(ex), L.lw.speed_along(ey), L.lw_unstressed.speed_along(ez),
                L.lw_unstressed.speed_along(ex), L.lw.speed_along(ez, false), L.lw.speed_along(ex, false));
    std::printf("  rotational modes at k = 0: %.1f, %.1f, %.1f 1/s\n", L.lw.omega_rotation_k0[0], L.lw.omega_rotation_k0[1],
                L.lw.omega_rotation_k0[2]);
    const auto& d = L.disp;
    std::printf("  branches omega (1/s) at k l0 =");
    const std::size_t mid = d.k.size() / 2, n = d.k.size() - 1 - mid;
    const std::size_t cols[] = {mid + n / 4, mid + n / 2, mid + 3 * n / 4, d.k.size() - 1};
    for (auto i : cols) std::printf(" %9.4f", d.k[i] * L.l0);
    std::printf("\n");
    for (int b = 0; b < 6; ++b) {
      std::printf("    %-8s %-13s", theory::kLatticeDof[d.dominant[b]], d.kind(b));
      for (auto i : cols) std::printf(" %9.0f", d.branches[b][i].omega);
      std::printf("\n");
    }
  } else {
    std::printf("lattice dynamics: %s\n", L.note.c_str());
  }
  std::printf("Voigt 6x6 of the symmetrised C (Pa; xx yy zz yz xz xy):\n");
  for (int I = 0; I < 6; ++I) {
    for (int J = 0; J < 6; ++J) std::printf(" %12.5e", r.C_voigt_sym(I, J));
    std::printf("\n");
  }
  print_relaxed(relaxed);
  return 0;
}

}  // namespace granwave::cli
