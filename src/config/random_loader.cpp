// The [random] table of a crystal with lattice = "random" (config/random_loader.hpp): keys,
// refusals, and the preparation of the packing at its pressure.
#include "config/random_loader.hpp"

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <iostream>
#include <numbers>

#include "config/contact_laws.hpp"
#include "config/packing_loader.hpp"
#include "core/error.hpp"
#include "core/format.hpp"
#include "packing/checks.hpp"
#include "packing/prepared_state.hpp"

namespace granwave::config {

namespace {

using packing::RadiusLaw;

RadiusLaw read_radii(const TomlReader& r, const toml::table& t) {
  RadiusLaw law;
  const std::string kind = r.choice(t, "random", "distribution", {"monodisperse", "uniform", "lognormal", "mixture"}, "monodisperse");
  const auto refuse_key = [&](const char* key, const std::string& why) {
    if (t.contains(key)) r.fail(std::string("random.") + key, why, t.get(key));
  };
  if (kind == "mixture") {
    law.kind = RadiusLaw::Kind::mixture;
    refuse_key("radius", "is not used with distribution = \"mixture\" (random.radii gives the radii)");
    refuse_key("width", "is not used with distribution = \"mixture\"");
    law.radii = r.numbers(t, "random", "radii");
    law.fractions = r.numbers(t, "random", "fractions");
    if (law.radii.empty()) r.fail("random.radii", "missing: distribution = \"mixture\" needs radii (m) and fractions");
    if (law.fractions.size() != law.radii.size())
      r.fail("random.fractions", "must have one number fraction per radius (" + std::to_string(law.radii.size()) + ")", t.get("fractions"));
    double sum = 0.0;
    for (double a : law.radii)
      if (!(a > 0.0)) r.fail("random.radii", "must all be > 0 (m)", t.get("radii"));
    for (double f : law.fractions) {
      if (!(f >= 0.0)) r.fail("random.fractions", "must all be >= 0", t.get("fractions"));
      sum += f;
    }
    if (std::abs(sum - 1.0) > 1e-9) r.fail("random.fractions", "must sum to 1 (got " + fmt("%.10g", sum) + ")", t.get("fractions"));
    double mean = 0.0;
    for (std::size_t k = 0; k < law.radii.size(); ++k) mean += law.fractions[k] * law.radii[k];
    law.radius = mean;
    return law;
  }
  refuse_key("radii", "is for distribution = \"mixture\"");
  refuse_key("fractions", "is for distribution = \"mixture\"");
  law.radius = *r.number_in(t, "random", "radius", true, [](double v) { return v > 0; }, "> 0 (m, the mean radius)");
  if (kind == "monodisperse") {
    refuse_key("width", "is not used with distribution = \"monodisperse\"");
    return law;
  }
  law.kind = kind == "uniform" ? RadiusLaw::Kind::uniform : RadiusLaw::Kind::lognormal;
  const double w = *r.number(t, "random", "width", true);
  if (law.kind == RadiusLaw::Kind::uniform && !(w >= 0.0 && w < 1.0))
    r.fail("random.width", "= " + fmt("%.6g", w) + " makes the smallest radius radius (1 - width) " +
                               (w >= 1.0 ? "<= 0" : "larger than the mean") +
                               "; allowed: [0, 1) (the half-width of the uniform law over the mean radius)", t.get("width"));
  if (law.kind == RadiusLaw::Kind::lognormal && !(w > 0.0 && w <= 1.0))
    r.fail("random.width", "= " + fmt("%.6g", w) + ": allowed (0, 1] (the standard deviation of ln a)", t.get("width"));
  law.width = w;
  return law;
}

}  // namespace

void read_random(const TomlReader& r, const toml::table& root, Case& c, bool prepare, const packing::PreparedState* prepared) {
  CrystalCase& k = *c.crystal;
  const toml::node* node = root.get("random");
  if (k.lattice != "random") {
    if (node) r.fail("random", "belongs to crystal.lattice = \"random\" (this crystal is \"" + k.lattice + "\")", node);
    return;
  }
  const toml::table& crystal = *root.get("crystal")->as_table();
  for (const char* key : {"cells", "radius", "overlap", "polydispersity", "seed", "fixed_layers", "relax_tolerance"})
    if (crystal.contains(key))
      r.fail(std::string("crystal.") + key, "is not used with lattice = \"random\": [random] gives the particles", crystal.get(key));
  const toml::table& t = *r.table(root, "", "random", true);
  r.allow_only(t, "random", {"distribution", "radius", "width", "radii", "fractions", "count", "shape", "seed", "pressure",
                             "preparation_friction", "damping", "background_damping", "inertia_number", "servo_time", "initial_solid_fraction",
                             "minimise_from", "preload_overlap", "pressure_tolerance", "kinetic_ratio", "unbalanced_force", "max_steps", "max_overlap",
                             "start", "stop_at", "source_thickness", "fixed_thickness", "bin_width", "relax_tolerance"});
  packing::RandomSpec s;
  s.radii = read_radii(r, t);
  s.density = k.density;
  s.count = *r.integer_in(t, "random", "count", true, 1, 10000000);
  if (t.contains("shape")) {
    const std::vector<double> shape = r.numbers(t, "random", "shape");
    if (shape.size() != 3 || std::any_of(shape.begin(), shape.end(), [](double v) { return !(v > 0.0); }))
      r.fail("random.shape", "must be [x, y, z], three numbers > 0 (the box's proportions)", t.get("shape"));
    s.shape = {shape[0], shape[1], shape[2]};
  }
  s.seed = static_cast<std::uint64_t>(r.integer_in(t, "random", "seed", false, 0, std::int64_t{1} << 53).value_or(1));
  const auto in = [&](const char* key, double lo, double hi, bool lo_open, double fallback, const char* unit) {
    const std::string what = std::string("in ") + (lo_open ? "(" : "[") + fmt("%g", lo) + ", " + fmt("%g", hi) + "]" + unit;
    return r.number_in(t, "random", key, false, [&](double v) { return (lo_open ? v > lo : v >= lo) && v <= hi; }, what)
        .value_or(fallback);
  };
  s.pressure = *r.number_in(t, "random", "pressure", true, [](double v) { return v > 0; }, "> 0 (Pa, the target isotropic pressure)");
  s.friction = in("preparation_friction", 0.0, 10.0, false, 0.0, " (Coulomb's mu during the compression)");
  if (s.friction > 0.0 && t.contains("start"))  // before the friction's own refusals: the path is frictionless
    r.fail("random.start", "with random.preparation_friction > 0: a compression path loads by FIRE on the enthalpy, which a "
           "frictional packing does not minimise; allowed: no key, or preparation_friction = 0", t.get("start"));
  s.damping = in("damping", 0.0, 1.0, true, 0.98, " (fraction of the critical damping of a contact)");
  s.background_damping = in("background_damping", 0.0, 1e3, false, 1.0, " (drag rate in units of sqrt(d p / m))");
  s.inertia_number = in("inertia_number", 0.0, 0.1, true, 1e-2, "");
  s.servo_time = in("servo_time", 0.0, 1e6, true, 0.02, " (units of sqrt(m/(d p)))");
  s.initial_solid_fraction = in("initial_solid_fraction", 0.0, 0.3, true, 0.3, "");
  s.minimise_from = in("minimise_from", 0.0, 1.0, false, s.friction > 0.0 ? 0.0 : 0.05,
                       " (|p/p_target - 1| from which FIRE minimises the enthalpy; 0: never)");
  // A frictional packing is no enthalpy minimum: FIRE's finish is for frictionless compressions.
  if (s.friction > 0.0 && s.minimise_from != 0.0)
    r.fail("random.minimise_from", "= " + fmt("%g", s.minimise_from) + " with random.preparation_friction > 0: a frictional "
           "packing is not a minimum of the enthalpy (the damped servo finishes it); allowed: 0 or no key", t.get("minimise_from"));
  s.preload_overlap = in("preload_overlap", 0.0, 0.01, false, 1e-3, " (mean overlap / d of FIRE's first stage; 0: none)");
  s.pressure_tolerance = in("pressure_tolerance", 0.0, 0.1, true, 1e-3, " (of the target)");
  s.kinetic_ratio = in("kinetic_ratio", 0.0, 1.0, true, 1e-8, " (E_kin/E_pot)");
  s.unbalanced_force = in("unbalanced_force", 0.0, 1.0, true, 1e-3, " (largest net force / mean contact force)");
  s.max_steps = static_cast<long>(r.integer_in(t, "random", "max_steps", false, 1, std::int64_t{1} << 40).value_or(2000000));
  const double max_overlap = in("max_overlap", 0.0, 1.0, true, 0.05, " (of the smaller radius)");
  // "gas": the packing is the gas of step 1, uncompressed, for `granwave packing -o` to hand the same
  // initial state to the other codes' controllers (build and run refuse it).
  k.random_gas_only = r.choice(t, "random", "stop_at", {"static", "gas"}, "static") == "gas";
  PackingKeys p;
  p.format = "random";
  p.max_overlap = max_overlap;
  // As a file's packing (config/packing_loader.cpp), which says why 1e-14.
  p.relax_tolerance = in("relax_tolerance", 0.0, 1.0, true, 1e-14, "");

  // Refusals before the compression: the radii against the box, the pressure against the bounds.
  const std::vector<double> radii = packing::draw_radii(s.radii, s.count, s.seed);
  double a_min = 1e300, a_max = 0.0, v_solid = 0.0, a_sum = 0.0;
  for (double a : radii) {
    a_min = std::min(a_min, a), a_max = std::max(a_max, a), a_sum += a;
    v_solid += 4.0 / 3.0 * std::numbers::pi * a * a * a;
  }
  const double phi_rcp = 0.64;  // random close packing: the prepared box's size, roughly
  const double unit = std::cbrt(v_solid / phi_rcp / (s.shape[0] * s.shape[1] * s.shape[2]));
  const double across = std::min({s.shape[0], s.shape[1], s.shape[2]}) * unit;
  if (across < 6.0 * a_max) {
    const double need = std::ceil(static_cast<double>(s.count) * std::pow(6.0 * a_max / across, 3.0));
    r.fail("random.count", "= " + std::to_string(s.count) + " is too small for its box: at random close packing (0.64) the box "
           "would be " + fmt("%.4g", across) + " m across, less than three largest diameters (" + fmt("%.4g", 6.0 * a_max) +
           " m: YADE's periodic cell, and two for the cell list); allowed: count >= about " + fmt("%.0f", need) +
           " with this shape", t.get("count"));
  }
  const ContactLawInfo& info = law_of(c.contact);
  const contact::LawParams params = c.contact;
  const double density = k.density;
  const contact::NormalForm form = info.normal_form(params, density);
  if (s.friction > 0.0) {  // the case's tangential spring, k_t at a contact of two mean spheres
    const double a0 = a_sum / static_cast<double>(s.count);
    const contact::LinearisedContact at0 = info.at(params, density, a0, a0, 1e-4 * a0);
    if (!(at0.kt > 0.0))
      r.fail("random.preparation_friction", "= " + fmt("%g", s.friction) + " needs the case's tangential spring, and contact.law = \"" +
             std::string(info.name) + "\" has none here (k_t = 0); allowed: 0, or a law with k_t > 0 (linear: contact.kt; "
             "hertz_mindlin: tangential = \"mindlin\")", t.get("preparation_friction"));
    if (std::string(info.history_name(params)) != "displacement")
      r.fail("random.preparation_friction", "= " + fmt("%g", s.friction) + ": the preparation's springs xi go into the run's "
             "history as the spring itself, and contact.tangential_history = \"" + info.history_name(params) + "\" keeps " +
             "another; allowed: 0, or tangential_history = \"displacement\"", t.get("preparation_friction"));
    s.tangential = info.stiffness_of_overlap ? contact::TangentialForm{true, at0.kt / at0.kn}
                                             : contact::TangentialForm{false, at0.kt};
  }
  const auto law = [&form](double ai, double aj, double delta) {
    return contact::with_normal(form, [&](const auto& f) { return f(ai, aj, delta); });
  };
  // The largest contact force is about 4 mean ones (the exponential tail of the force distribution);
  // the mean f = pi d^2 p / (z Phi), z = 6, Phi = 0.64 (Love-Weber for a monodisperse packing).
  const double d_mean = 2.0 * a_sum / static_cast<double>(s.count);
  const double f_top = 4.0 * std::numbers::pi * d_mean * d_mean * s.pressure / (6.0 * phi_rcp);
  const double f_allowed = law(a_min, a_min, max_overlap * a_min).f;
  if (!(f_top <= f_allowed))
    r.fail("random.pressure", "= " + fmt("%.6g", s.pressure) + " Pa would press the smallest spheres' contacts beyond the overlap "
           "bound random.max_overlap = " + fmt("%g", max_overlap) + " of the smaller radius (the largest contact force, about 4 "
           "mean forces pi d^2 p / (6 x 0.64)); allowed: pressure <= " + fmt("%.4g", s.pressure * f_allowed / f_top) + " Pa",
           t.get("pressure"));
  if (c.integrator.dt) {  // the run's fixed time step against the stiffest contacts the pressure makes
    double lo = 0.0, hi = max_overlap * a_min;
    for (int it = 0; it < 100; ++it) (law(a_max, a_max, 0.5 * (lo + hi)).f < f_top ? lo : hi) = 0.5 * (lo + hi);
    const contact::LinearisedContact top = info.at(params, density, a_max, a_max, hi);
    const double m_min = density * 4.0 / 3.0 * std::numbers::pi * a_min * a_min * a_min;
    const double z = 12.0;  // as the FCC's bound (crystal/derive.cpp): no random packing has more
    const double omega = std::sqrt(2.0 * z * (top.kn + 3.5 * top.kt) / m_min);
    const double zeta = z * (top.gamma_n + top.gamma_t) / (2.0 * m_min) / omega;
    const double dt_stable = 2.0 / omega * (std::sqrt(1.0 + zeta * zeta) - zeta);
    if (*c.integrator.dt > dt_stable)
      r.fail("random.pressure", "= " + fmt("%.6g", s.pressure) + " Pa makes the stiffest contacts break the stability limit " +
             fmt("%.4g", dt_stable) + " s of velocity Verlet for integrator.dt = " + fmt("%.4g", *c.integrator.dt) +
             " s (2/omega_max, z = 12, the largest spheres at 4 mean contact forces); allowed: a lower pressure or a smaller dt",
             t.get("pressure"));
  }

  // A compression path's stage (docs/random-packing.md): a saved static packing instead of the gas.
  std::string start;
  if (auto v = r.string(t, "random", "start", false)) {
    std::filesystem::path sp(*v);
    if (sp.is_relative()) sp = std::filesystem::path(c.path).parent_path() / sp;
    start = sp.string();
    if (prepare && !prepared && !std::filesystem::exists(start)) r.fail("random.start", "no such saved packing: " + start, t.get("start"));
    s.start_static = true;
  }
  if (!prepare) {
    k.random = s;
    k.packing_file = p;
    return;
  }

  packing::Packing pk;
  std::vector<packing::Touch> touching;  // check_packing's, for the slabs' mean overlap
  packing::Preparation prep;
  try {  // the generator's refusals name their key; here they get the case file's name
    if (prepared) {  // the system file's packing as its build prepared it (wrapped): to the last bit
      const packing::PreparedState& g = *prepared;
      if (k.random_gas_only || g.seed != s.seed || static_cast<long>(g.packing.particles.size()) != s.count ||
          g.pressure_target != s.pressure || g.friction != s.friction)
        throw InputError(g.packing.source + ": prepared with random.seed = " + std::to_string(g.seed) + ", count = " +
                         std::to_string(g.packing.particles.size()) + ", pressure = " + fmt("%.17g", g.pressure_target) +
                         ", friction = " + fmt("%.17g", g.friction) + ", not this case's; allowed: a system file that " +
                         "`granwave build` wrote from this case");
      pk = g.packing;
      prep = g.preparation;
      for (packing::Particle& q : pk.particles) q.density = s.density;
    } else {
      if (start.empty()) {
        pk = packing::random_gas(s);
      } else {
        if (k.random_gas_only)
          throw InputError("random.start and random.stop_at = \"gas\" together: a saved packing is no gas; allowed: one of them");
        pk = packing::load_prepared(start).packing;
        if (static_cast<long>(pk.particles.size()) != s.count)
          throw InputError("random.start = " + start + " holds " + std::to_string(pk.particles.size()) + " particles, random.count = " +
                           std::to_string(s.count) + "; allowed: a saved packing of the same count");
      }
      if (!k.random_gas_only)
        prep = packing::compress(pk, s, form, [](const std::string& line) {
          std::cerr << "granwave: preparing the random packing: " << line << "\n";
        });
      packing::wrap_into_box(pk);
    }
    packing::Limits limits;
    limits.max_overlap = max_overlap;
    limits.touching = &touching;
    packing::check_packing(pk, limits);
  } catch (const InputError& e) {
    throw InputError(c.path + ": " + e.what());
  }
  resolve_slabs(r, t, "random", p, pk, touching, k);
  k.random = s;
  k.preparation = std::make_shared<const packing::Preparation>(prep);
  k.imported = std::make_shared<const packing::Packing>(std::move(pk));
}

}  // namespace granwave::config
