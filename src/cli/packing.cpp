// `granwave packing CASE.toml [-o FILE.dump] [--min-contacts N] [--json]`: one reader of a periodic
// packing for every code (issue 40 item 4). The case's packing before any cut (a random case's
// prepared packing or, with random.stop_at = "gas", its gas; a file case's import of another code's
// packing) is measured under the case's normal law, and with -o written as a LAMMPS custom dump.
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <numbers>

#include "cli/verbs.hpp"
#include "config/contact_laws.hpp"
#include "core/error.hpp"
#include "core/format.hpp"
#include "packing/contacts.hpp"

namespace granwave::cli {

namespace {

struct PackingResiduals {
  double pressure = 0.0;    // Love-Weber of the normal elastic forces (Pa)
  double kinetic_ratio = 0.0;  // E_kin (translations, the file's velocities) / E_pot
  double unbalanced = 0.0;  // largest net normal force on a particle / mean normal contact force
  double unbalanced_mean = 0.0;  // the mean of the net forces / mean contact force (YADE's unbalancedForce)
  double mean_force = 0.0;  // N
};

PackingResiduals packing_residuals(const packing::Packing& pk, const contact::NormalForm& form, double density) {
  PackingResiduals r;
  const std::size_t n = pk.particles.size();
  std::vector<contact::Vec3> net(n, contact::Vec3{0.0, 0.0, 0.0});
  double virial = 0.0, e_pot = 0.0, f_sum = 0.0;
  const std::vector<packing::Touch> touches = packing::touching_pairs(pk);
  for (const packing::Touch& t : touches) {
    const packing::Particle &a = pk.particles[t.i], &b = pk.particles[t.j];
    const contact::Vec3& d = t.branch;
    const double len = std::sqrt(d.vx * d.vx + d.vy * d.vy + d.vz * d.vz);
    const contact::NormalForce nf =
        contact::with_normal(form, [&](const auto& law) { return law(a.radius, b.radius, t.overlap); });
    virial += nf.f * len;
    e_pot += nf.f * t.overlap / (nf.k * t.overlap / nf.f + 1.0);  // f ~ delta^m: E = f delta / (m + 1)
    f_sum += nf.f;
    const contact::Vec3 fij{nf.f * d.vx / len, nf.f * d.vy / len, nf.f * d.vz / len};  // on j, away from i
    net[t.j] = net[t.j] + fij;
    net[t.i] = net[t.i] - fij;
  }
  double e_kin = 0.0, worst = 0.0, sum_net = 0.0;
  for (std::size_t q = 0; q < n; ++q) {
    const packing::Particle& p = pk.particles[q];
    const double f = std::sqrt(net[q].vx * net[q].vx + net[q].vy * net[q].vy + net[q].vz * net[q].vz);
    worst = std::max(worst, f);
    sum_net += f;
    if (!p.velocity) continue;
    const double m = density * 4.0 / 3.0 * std::numbers::pi * p.radius * p.radius * p.radius;
    const contact::Vec3& v = *p.velocity;
    e_kin += 0.5 * m * (v.vx * v.vx + v.vy * v.vy + v.vz * v.vz);
  }
  r.pressure = virial / (3.0 * pk.box.volume());
  r.mean_force = touches.empty() ? 0.0 : f_sum / static_cast<double>(touches.size());
  r.unbalanced = r.mean_force > 0.0 ? worst / r.mean_force : 0.0;
  r.unbalanced_mean = r.mean_force > 0.0 ? sum_net / static_cast<double>(n) / r.mean_force : 0.0;
  r.kinetic_ratio = e_pot > 0.0 ? e_kin / e_pot : 0.0;
  return r;
}

void write_packing_dump(const packing::Packing& pk, double density, const std::string& path) {
  const std::string tmp = path + ".tmp";
  {
    std::ofstream f(tmp);
    if (!f) throw InputError("cannot write " + tmp);
    f << "ITEM: TIMESTEP\n0\nITEM: NUMBER OF ATOMS\n" << pk.particles.size() << "\nITEM: BOX BOUNDS pp pp pp\n";
    for (int a = 0; a < 3; ++a) f << fmt("%.17g %.17g\n", pk.box.lo[a], pk.box.hi[a]);
    f << "ITEM: ATOMS id type x y z radius mass vx vy vz\n";
    std::int64_t id = 0;
    for (const packing::Particle& p : pk.particles) {
      const double m = density * 4.0 / 3.0 * std::numbers::pi * p.radius * p.radius * p.radius;
      const contact::Vec3 v = p.velocity.value_or(contact::Vec3{0.0, 0.0, 0.0});
      f << fmt("%lld 1 %.17g %.17g %.17g %.17g %.17g %.17g %.17g %.17g\n", static_cast<long long>(++id), p.centre.vx, p.centre.vy,
               p.centre.vz, p.radius, m, v.vx, v.vy, v.vz);
    }
    if (!f) throw InputError("cannot write " + tmp);
  }
  std::filesystem::rename(tmp, path);
}

}  // namespace

int cmd_packing(const Args& args) {
  const char* usage =
      "usage: granwave packing CASE.toml [-o FILE.dump] [--min-contacts N] [--json]\n"
      "  the case's periodic packing before any cut (lattice = \"random\": the prepared packing, or with\n"
      "  random.stop_at = \"gas\" the gas; lattice = \"file\": the import of another code's packing), measured\n"
      "  under the case's normal law: solid fraction, coordination, z* and rattlers (fewer than N contacts,\n"
      "  default 4; 2 for a frictional packing), the Love-Weber pressure of the normal forces, E_kin/E_pot\n"
      "  (the file's velocities; a prepared random case's own record beside it: its packing carries none), the\n"
      "  largest and the mean net normal force over the mean contact force. -o writes the\n"
      "  packing as a LAMMPS custom dump (SI, %.17g, ids 1..n, masses of crystal.density)";
  if (wants_help(args)) {
    std::cout << usage << "\n";
    return 0;
  }
  const std::vector<std::string> valued{"-o", "--output", "--min-contacts"};
  for (std::size_t i = 0; i < args.size(); ++i) {
    if (args[i].rfind("-", 0) != 0) continue;
    if (std::find(valued.begin(), valued.end(), args[i]) != valued.end()) {
      ++i;
      continue;
    }
    if (args[i] != "--json") throw InputError("unknown option '" + args[i] + "'\n" + usage);
  }
  const std::vector<std::string> pos = positionals(args, valued);
  if (pos.size() != 1) throw InputError(std::string("expected one case file\n") + usage);
  int min_contacts = 4;
  if (const std::string v = option_value(args, "--min-contacts", "--min-contacts"); !v.empty()) {
    if (v != "1" && v != "2" && v != "3" && v != "4")
      throw InputError("--min-contacts " + v + ": allowed 1, 2, 3 or 4 (4 frictionless, 2 frictional)");
    min_contacts = std::stoi(v);
  }
  const config::Case c = config::load_case(pos[0]);
  if (!c.crystal || !c.crystal->imported)
    throw InputError(pos[0] + ": crystal.lattice must be \"random\" or \"file\" (a packing to measure)");
  const packing::Packing& pk = *c.crystal->imported;
  const double density = c.crystal->density;
  const contact::NormalForm form = config::law_of(c.contact).normal_form(c.contact, density);
  const packing::PackingStats st = packing::measure(pk, min_contacts);
  const PackingResiduals r = packing_residuals(pk, form, density);
  const std::string out = option_value(args, "-o", "--output");
  if (!out.empty()) write_packing_dump(pk, density, out);
  const double l[3] = {pk.box.length(0), pk.box.length(1), pk.box.length(2)};
  if (has_flag(args, "--json")) {
    std::cout << fmt("{\"schema\": \"granwave-packing/1\", \"particles\": %zu, \"contacts\": %zu, \"box\": [%.17g, %.17g, %.17g], ",
                     st.particles, st.contacts, l[0], l[1], l[2])
              << fmt("\"solid_fraction\": %.17g, \"coordination\": %.17g, \"coordination_backbone\": %.17g, \"rattlers\": %zu, ",
                     st.solid_fraction, st.mean_coordination, st.mean_coordination_nonrattler, st.rattlers)
              << fmt("\"min_contacts\": %d, \"pressure\": %.17g, \"kinetic_ratio\": %.17g, \"unbalanced\": %.17g, ", min_contacts,
                     r.pressure, r.kinetic_ratio, r.unbalanced)
              << fmt("\"unbalanced_mean\": %.17g, \"mean_force\": %.17g, \"max_overlap\": %.17g, \"mean_overlap\": %.17g",
                     r.unbalanced_mean, r.mean_force, st.max_overlap, st.mean_overlap);
    if (const auto& prep = c.crystal->preparation; prep && !c.crystal->random_gas_only)  // the preparation's own record
      std::cout << fmt(", \"prepared\": {\"steps\": %ld, \"minimise_steps\": %ld, \"pressure\": %.17g, \"kinetic_ratio\": %.17g, "
                       "\"unbalanced\": %.17g}", prep->steps, prep->minimise_steps, prep->pressure, prep->kinetic_ratio,
                       prep->unbalanced_force);
    std::cout << "}\n";
  } else {
    std::cout << fmt("%zu particles, box %.6g x %.6g x %.6g m: Phi %.5f, Z %.4f, z* %.4f, rattlers %zu (< %d contacts)\n",
                     st.particles, l[0], l[1], l[2], st.solid_fraction, st.mean_coordination, st.mean_coordination_nonrattler,
                     st.rattlers, min_contacts)
              << fmt("p %.6g Pa (normal forces), E_kin/E_pot %.3g, unbalanced %.3g (mean %.3g), max overlap %.3g\n", r.pressure,
                     r.kinetic_ratio, r.unbalanced, r.unbalanced_mean, st.max_overlap);
    if (!out.empty()) std::cout << "packing written to " << out << "\n";
  }
  return 0;
}

}  // namespace granwave::cli
