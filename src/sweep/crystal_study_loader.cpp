// The crystal study file (data/SCHEMA.md §6): TOML -> a validated CrystalStudy. Reading and error
// messages: config/toml_reader.hpp, shared with the case loader.
#include <cmath>
#include <filesystem>
#include <fstream>
#include <sstream>

#include "config/contact_laws.hpp"
#include "config/toml_reader.hpp"
#include "core/error.hpp"
#include "sweep/crystal_study.hpp"

namespace granwave::sweep {
bool is_crystal_study(const std::string& toml_text) { return config::study_kind(toml_text) == "crystal"; }

CrystalStudy parse_crystal_study(const std::string& text, const std::string& origin) {
  const config::TomlReader r(origin);
  const toml::table root = config::parse_toml(text, origin);
  CrystalStudy s;
  s.path = origin;
  s.text = text;
  r.allow_only(root, "", {"study", "run"});
  const toml::table* st = r.table(root, "", "study", true);
  r.allow_only(*st, "study", {"name", "kind", "case", "vary", "values", "modes", "positions", "batch", "kt_over_k"});
  s.name = *r.string(*st, "study", "name", true);
  if (s.name.empty()) r.fail("study.name", "must not be empty", st->get("name"));
  r.choice(*st, "study", "kind", {"crystal"});
  const std::string case_rel = r.string(*st, "study", "case", false).value_or("");
  if (case_rel.empty()) r.fail("study.case", "missing (a crystal case file, relative to the study file)", st->get("case"));
  std::filesystem::path cp(case_rel);
  if (cp.is_relative()) cp = std::filesystem::path(origin).parent_path() / cp;
  if (!std::filesystem::exists(cp)) r.fail("study.case", "no such case file: " + cp.string(), st->get("case"));
  s.base = config::load_case(cp.string());
  if (s.base.model != config::Model::crystal || !s.base.crystal)
    r.fail("study.case", "the base case must be a crystal case (model = \"crystal\")", st->get("case"));

  const std::string vary =
      r.choice(*st, "study", "vary", {"gamma_n", "kt_over_k", "polydispersity", "overlap", "kr_over_kt"});
  s.vary = vary == "gamma_n"      ? CrystalVary::gamma_n
           : vary == "kt_over_k"  ? CrystalVary::kt_over_k
           : vary == "overlap"    ? CrystalVary::overlap
           : vary == "kr_over_kt" ? CrystalVary::kr_over_kt
                                  : CrystalVary::polydispersity;
  // gamma_n, kt_over_k and kr_over_kt vary keys (gamma_n, kt, kr and kt) that the base case's law must have.
  const config::ContactLawInfo& law = config::law_of(s.base.contact);
  std::vector<const char*> varied;
  if (s.vary == CrystalVary::gamma_n) varied = {"gamma_n"};
  if (s.vary == CrystalVary::kt_over_k) varied = {"kt"};
  if (s.vary == CrystalVary::kr_over_kt) varied = {"kr", "kt"};
  for (const char* key : varied)
    if (!law.has_key(key))
      r.fail("study.vary", "\"" + vary + "\" varies a key of the " + config::contact_law_owners(key) +
             " law; the base case's law is \"" + law.name + "\"", st->get("vary"));
  if (st->contains("kt_over_k")) {
    if (s.vary != CrystalVary::kr_over_kt)
      r.fail("study.kt_over_k", "only with vary = \"kr_over_kt\" (the fixed kt/k of the rolling springs)", st->get("kt_over_k"));
    s.kt_over_k = r.number_in(*st, "study", "kt_over_k", true, [](double v) { return v > 0.0; }, "> 0");
  }
  // The springs are k_r = k_o = value * kt: without a tangential spring they would all be zero.
  if (s.vary == CrystalVary::kr_over_kt && !s.kt_over_k && !(s.base.contact.number("kt").value_or(0.0) > 0.0))
    r.fail("study.kt_over_k", "missing: the base case has kt = 0, and vary = \"kr_over_kt\" sets k_r = k_o = value * kt");
  s.values = r.numbers(*st, "study", "values");
  if (s.values.empty()) r.fail("study.values", "missing (the parameter values)");
  for (double v : s.values)
    if (v < 0.0) r.fail("study.values", "must be >= 0", st->get("values"));
  if (s.vary == CrystalVary::overlap)
    for (double v : s.values)
      if (!(v > 0.0 && v < 0.1)) r.fail("study.values", "overlaps delta_0/d must be in (0, 0.1)", st->get("values"));

  if (const toml::node* n = st->get("modes")) {
    const toml::array* a = n->as_array();
    if (!a || a->empty()) r.fail("study.modes", "must be a non-empty array of \"P\" / \"S\"", n);
    s.modes.clear();
    for (auto&& e : *a) {
      const std::string m = e.value_or(std::string());
      if (m != "P" && m != "S") r.fail("study.modes", "entries must be \"P\" or \"S\"", &e);
      s.modes.push_back(m[0]);
    }
  }
  if (st->contains("positions")) {  // absent: keep the default table positions
    s.positions = r.numbers(*st, "study", "positions");
    for (double z : s.positions)
      if (z < 1.0 || z != std::round(z)) r.fail("study.positions", "must be whole layer numbers z/l0 >= 1", st->get("positions"));
  }
  const auto whole = [](double lo) { return [lo](double v) { return v >= lo && v == std::round(v); }; };
  if (auto b = r.number_in(*st, "study", "batch", false, whole(1), "an integer >= 1")) s.batch = static_cast<std::size_t>(*b);

  if (const toml::table* run = r.table(root, "", "run", false)) {
    r.allow_only(*run, "run", {"layers", "t_end", "t_end_s", "dt", "interval"});
    const int min_layers = 2 * s.base.crystal->fixed_layers + 10;
    if (auto v = r.number_in(*run, "run", "layers", false, whole(min_layers),
                             "an integer >= 2 fixed_layers + 10 = " + std::to_string(min_layers)))
      s.layers = static_cast<int>(*v);
    const auto positive = [](double v) { return v > 0.0; };
    s.t_end = r.number_in(*run, "run", "t_end", false, positive, "> 0");
    s.t_end_s = r.number_in(*run, "run", "t_end_s", false, positive, "> 0");
    s.dt = r.number_in(*run, "run", "dt", false, positive, "> 0");
    s.interval = r.number_in(*run, "run", "interval", false, positive, "> 0");
  }
  const int layers = s.layers.value_or(s.base.crystal->cells[2]);
  for (double z : s.positions)
    if (z > layers - 2 * s.base.crystal->fixed_layers)
      r.fail("study.positions", "z/l0 beyond the last free layer of a " + std::to_string(layers) + "-layer crystal");
  return s;
}

CrystalStudy load_crystal_study(const std::string& path) { return parse_crystal_study(config::read_file_text(path, "study file"), path); }

}  // namespace granwave::sweep
