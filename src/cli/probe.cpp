// granwave probe CASE [--strain zz|zx|xx|yy|yx|all] [--amplitude E] [--tolerance T] [--json]: the static
// probe of issue 39 (crystal/probe.hpp) against the relaxed slab tensor of `granwave theory`.
#include <algorithm>
#include <cmath>
#include <iostream>
#include <string>
#include <vector>

#include "cli/theory_json.hpp"
#include "cli/verbs.hpp"
#include "config/case.hpp"
#include "core/error.hpp"
#include "core/format.hpp"
#include "core/json.hpp"
#include "crystal/derive.hpp"
#include "crystal/probe.hpp"
#include "crystal/relaxed_inputs.hpp"
#include "theory/relaxed_moduli.hpp"

namespace granwave::cli {
namespace {

constexpr const char* kProbeHelp = R"(usage: granwave probe CASE.toml [--strain zz|zx|xx|yy|yx|all] [--amplitude E] [--tolerance T] [--json]
  (--strain: one, a comma-separated list such as zz,yx, or all, the default)

The static probe (issue 39): the simulation strains the crystal case's packing (as a run starts from
it) by +-E, relaxes the free particles under the case's full contact law with FIRE (translations and
rotations; tangential springs stretched by the motion), and measures the change of the nominal stress
P_ab = (1/V) sum_c w_c B_a f_b (B the contact's unstrained branch, f the force on its second particle,
V and w_c the relaxed slab's of `granwave theory`): (P(+E) - P(-E)) / (2E), which the linear theory
predicts as A_relaxed[a][b][g][f] of the slab (the tensor with the initial-stress term) for the strain
eps_gf. The Cauchy stress's change is printed beside it.
  zz, zx   source and top slabs moved affinely relative to each other (zx: gradient z, displacement x)
  xx, yy   the periodic box and every position stretched
  yx       the box sheared (the +y images shifted in x by E box_y), every position by E y
  Every strain starts from the relaxed state, springs included; the affine step stretches each sticking
  contact's tangential spring by its relative displacement, across the box's faces too.
  --amplitude E   strain amplitude, (0, 1e-3] (default 1e-7: at 1e-6 a contact of the LAMMPS packing with
                  friction, whose normal force is ~1e-4 of the mean, already slides)
  --tolerance T   FIRE stops when every free particle's force (torque/radius) is below T e <k_n> <l>
                  (default 1e-6)
  --json          one JSON object (data/SCHEMA.md, `granwave probe --json`)
Error: max_ab |dP_ab - A_ab(strain)| / max_ab |A_ab(strain)|; also the largest |f_t|/(mu f_n) after
relaxing (below 1: no contact slides), the contacts at that limit, and the contacts gained or lost.
)";

Json matrix_json(const Eigen::Matrix3d& m) {
  Json rows = Json::array();
  for (int a = 0; a < 3; ++a) rows.push_back({m(a, 0), m(a, 1), m(a, 2)});
  return {{"unit", "Pa"}, {"index_order", "[a][b]: a branch (gradient), b force (displacement)"}, {"values", rows}};
}

double option_number(const Args& args, const char* name, double fallback) {
  const std::string s = option_value(args, "", name);
  if (s.empty()) return fallback;
  std::size_t used = 0;
  const double v = leading_number(s, &used);
  if (used != s.size()) throw InputError(std::string(name) + " " + s + ": not a number");
  return v;
}

}  // namespace

int cmd_probe(const Args& args) { return cmd_probe(args, std::cout); }

int cmd_probe(const Args& args, std::ostream& out) {
  if (wants_help(args)) {
    out << kProbeHelp;
    return 0;
  }
  const std::vector<std::string> valued = {"--strain", "--amplitude", "--tolerance"};
  for (std::size_t i = 0; i < args.size(); ++i) {
    const std::string& a = args[i];
    if (std::find(valued.begin(), valued.end(), a) != valued.end()) {
      ++i;
      continue;
    }
    if (a.rfind("-", 0) == 0 && a != "--json" && a.find('=') == std::string::npos)
      throw InputError("probe: unknown option '" + a + "' (see granwave probe --help)");
  }
  const auto pos = positionals(args, valued);
  if (pos.size() != 1) throw InputError("probe: expected one case file (granwave probe --help)");
  const bool json = has_flag(args, "--json");
  crystal::ProbeOptions opt;
  opt.amplitude = option_number(args, "--amplitude", opt.amplitude);
  opt.tolerance = option_number(args, "--tolerance", opt.tolerance);
  if (!(opt.amplitude > 0.0 && opt.amplitude <= 1e-3)) throw InputError("--amplitude must be in (0, 1e-3]");
  if (!(opt.tolerance > 0.0 && opt.tolerance < 1.0)) throw InputError("--tolerance must be in (0, 1)");
  std::vector<crystal::ProbeStrain> strains;
  const std::string which = option_value(args, "", "--strain");
  if (!which.empty() && which != "all")  // one name or a comma-separated list
    for (std::size_t at = 0; at <= which.size();) {
      const std::size_t end = std::min(which.find(',', at), which.size());
      const crystal::ProbeStrain one = crystal::parse_probe_strain(which.substr(at, end - at));
      if (std::find(strains.begin(), strains.end(), one) == strains.end()) strains.push_back(one);
      at = end + 1;
    }
  const config::Case c = config::load_case(pos[0]);
  if (c.model != config::Model::crystal || !c.crystal) throw InputError(pos[0] + ": granwave probe covers crystal cases");
  const crystal::Packing pk = crystal::make_packing(c);
  const theory::ContactNetwork net = crystal::contact_network(c, pk);
  const theory::RelaxedModuli th = theory::relaxed_moduli(net, crystal::relaxed_slab_options(c, pk));
  const crystal::StaticProbe probe(c, pk, net, th.volume, opt);
  if (strains.empty())
    strains = {crystal::ProbeStrain::zz, crystal::ProbeStrain::zx, crystal::ProbeStrain::xx, crystal::ProbeStrain::yy,
               crystal::ProbeStrain::yx};

  Json results = Json::array();
  if (!json)
    out << fmt("case %s: %zu particles, slab V = %.6g m^3, p = %.6g Pa; unstrained state relaxed under the full law in "
                "%ld FIRE steps (residual %.2e of e<k_n><l> = %.3g N); theory: rattlers %d, mechanisms %d, unstable %d\n",
                c.name.c_str(), pk.size(), th.volume, th.pressure, probe.base_steps, probe.base_residual,
                probe.force_scale, th.rattlers, th.mechanisms, th.unstable_modes);
  double worst = 0.0;
  for (const auto s : strains) {
    const crystal::ProbeResult r = probe.run(s);
    const auto [g, f] = crystal::probe_strain_indices(s);
    Eigen::Matrix3d A;
    for (int a = 0; a < 3; ++a)
      for (int b = 0; b < 3; ++b) A(a, b) = th.relaxed(a, b, g, f);
    const double err = (r.dP - A).cwiseAbs().maxCoeff() / A.cwiseAbs().maxCoeff();
    worst = std::max(worst, err);
    const double comp = A(g, f), meas = r.dP(g, f);
    if (json) {
      results.push_back({{"strain", crystal::probe_strain_name(s)},
                         {"component", fmt("A[%d][%d][%d][%d]", g, f, g, f)},
                         {"A_relaxed", quantity(comp, "Pa")},
                         {"dP", quantity(meas, "Pa")},
                         {"relative_error", err},
                         {"dP_de", matrix_json(r.dP)},
                         {"A_relaxed_column", matrix_json(A)},
                         {"dsigma_de", matrix_json(r.dsigma)},
                         {"fire_steps", {r.steps_plus, r.steps_minus}},
                         {"residual", r.residual},
                         {"max_slip", r.max_slip},
                         {"sliding", r.sliding},
                         {"contacts_changed", r.contacts_changed}});
    } else {
      out << fmt("strain %s: dP_%c%c/de = %.8g Pa, A_relaxed = %.8g Pa; max relative error over the column %.2e; "
                  "Cauchy d sigma = %.8g Pa; FIRE %ld + %ld steps, residual %.1e, max |f_t|/(mu f_n) %.2e (%d at "
                  "the limit), contacts changed %d\n",
                  crystal::probe_strain_name(s), "xyz"[g], "xyz"[f], meas, comp, err, r.dsigma(g, f), r.steps_plus,
                  r.steps_minus, r.residual, r.max_slip, r.sliding, r.contacts_changed);
    }
  }
  if (json) {
    const Json o = {{"case", c.name},
                    {"amplitude", opt.amplitude},
                    {"tolerance", opt.tolerance},
                    {"stress", "nominal (first Piola-Kirchhoff) P_ab = (1/V) sum_c w_c B_a f_b, tension positive; "
                               "dP/d eps_gf = A_abgf with the initial-stress term (theory/relaxed_moduli.hpp)"},
                    {"volume", quantity(th.volume, "m^3")},
                    {"pressure", quantity(th.pressure, "Pa")},
                    {"base_fire_steps", probe.base_steps},
                    {"base_residual", probe.base_residual},
                    {"force_scale", quantity(probe.force_scale, "N")},
                    {"P0", matrix_json(probe.P0)},
                    {"rattlers", th.rattlers},
                    {"mechanisms", th.mechanisms},
                    {"unstable_modes", th.unstable_modes},
                    {"max_relative_error", worst},
                    {"strains", results}};
    out << json_text(o);
  } else {
    out << fmt("largest relative error %.2e\n", worst);
  }
  return 0;
}

}  // namespace granwave::cli
