// The packing study file (data/SCHEMA.md §6b): TOML -> a validated PackingStudy. Reading and error
// messages: config/toml_reader.hpp, shared with the case loader.
#include <algorithm>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <sstream>

#include "config/toml_reader.hpp"
#include "core/error.hpp"
#include "sweep/packing_study.hpp"

namespace granwave::sweep {
bool is_packing_study(const std::string& toml_text) { return config::study_kind(toml_text) == "packing"; }

PackingStudy parse_packing_study(const std::string& text, const std::string& origin) {
  const config::TomlReader r(origin);
  const toml::table root = config::parse_toml(text, origin);
  PackingStudy s;
  s.path = origin;
  s.text = text;
  r.allow_only(root, "", {"study"});
  const toml::table* st = r.table(root, "", "study", true);
  r.allow_only(*st, "study", {"name", "kind", "case", "pressures", "seeds", "widths", "count", "shape", "modes", "amplitude", "run_length",
                              "samples_per_bin", "batch", "path"});
  s.name = *r.string(*st, "study", "name", true);
  if (s.name.empty()) r.fail("study.name", "must not be empty", st->get("name"));
  r.choice(*st, "study", "kind", {"packing"});
  const std::string case_rel = r.string(*st, "study", "case", false).value_or("");
  if (case_rel.empty()) r.fail("study.case", "missing (a case with crystal.lattice = \"random\", relative to the study file)", st->get("case"));
  std::filesystem::path cp(case_rel);
  if (cp.is_relative()) cp = std::filesystem::path(origin).parent_path() / cp;
  if (!std::filesystem::exists(cp)) r.fail("study.case", "no such case file: " + cp.string(), st->get("case"));
  s.case_path = cp.string();
  s.case_text = config::read_file_text(s.case_path, "case file");
  {  // The base case is prepared member by member (each at its own pressure and seed); here only its shape.
    const toml::table base = config::parse_toml(s.case_text, s.case_path);
    const auto lattice = base["crystal"]["lattice"].value<std::string>();
    if (base["case"]["model"].value<std::string>().value_or("") != "crystal" || !lattice || *lattice != "random" ||
        !base["random"].as_table())
      r.fail("study.case", "the base case must be a crystal with lattice = \"random\" and a [random] table: " + s.case_path,
             st->get("case"));
  }
  s.pressures = r.numbers(*st, "study", "pressures");
  if (s.pressures.empty()) r.fail("study.pressures", "missing (random.pressure of the members, Pa)");
  for (double p : s.pressures)
    if (!(p > 0.0)) r.fail("study.pressures", "must all be > 0 (Pa)", st->get("pressures"));
  const std::vector<double> seeds = r.numbers(*st, "study", "seeds");
  if (seeds.empty()) r.fail("study.seeds", "missing (random.seed of the members)");
  for (double v : seeds) {
    if (!(v >= 0.0 && v == std::round(v) && v < 9007199254740992.0))
      r.fail("study.seeds", "must be whole numbers in [0, 2^53]", st->get("seeds"));
    s.seeds.push_back(static_cast<std::int64_t>(v));
  }
  if (st->contains("widths")) {
    s.widths = r.numbers(*st, "study", "widths");
    for (double w : s.widths)
      if (!(w >= 0.0 && w < 1.0))
        r.fail("study.widths", "must be in [0, 1) (the uniform radius law's half-width over the mean radius)", st->get("widths"));
    const toml::table base = config::parse_toml(s.case_text, s.case_path);
    if (base["random"]["distribution"].value<std::string>().value_or("monodisperse") == "mixture")
      r.fail("study.widths", "the base case's distribution is a mixture (random.radii): widths set a uniform law about "
             "random.radius, which a mixture does not have", st->get("widths"));
  }
  const auto whole = [](double lo) { return [lo](double v) { return v >= lo && v == std::round(v); }; };
  if (auto n = r.number_in(*st, "study", "count", false, whole(1), "an integer >= 1 (random.count of every member)"))
    s.count = static_cast<std::int64_t>(*n);
  if (st->contains("shape")) {
    s.shape = r.numbers(*st, "study", "shape");
    if (s.shape.size() != 3 || !(s.shape[0] > 0.0 && s.shape[1] > 0.0 && s.shape[2] > 0.0))
      r.fail("study.shape", "must be [x, y, z], three numbers > 0 (random.shape of every member)", st->get("shape"));
  }
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
  const auto in = [&](const char* key, double lo, double hi, double fallback) {
    return r.number_in(*st, "study", key, false, [&](double v) { return v > lo && v <= hi; },
                       "in (" + std::to_string(lo) + ", " + std::to_string(hi) + "]")
        .value_or(fallback);
  };
  s.amplitude = in("amplitude", 0.0, 1.0, s.amplitude);
  s.run_length = in("run_length", 0.0, 20.0, s.run_length);
  s.samples_per_bin = in("samples_per_bin", 0.0, 1000.0, s.samples_per_bin);
  if (r.choice(*st, "study", "path", {"direct", "compression"}, "direct") == "compression") {
    s.preparation_path = PackingStudy::Path::compression;
    if (!std::is_sorted(s.pressures.begin(), s.pressures.end()) ||
        std::adjacent_find(s.pressures.begin(), s.pressures.end()) != s.pressures.end())
      r.fail("study.pressures", "must rise strictly with path = \"compression\" (each seed's packing is loaded from the lowest "
             "pressure to the next)", st->get("pressures"));
  }
  if (auto b = r.number_in(*st, "study", "batch", false, whole(1), "an integer >= 1")) s.batch = static_cast<std::size_t>(*b);
  return s;
}

PackingStudy load_packing_study(const std::string& path) { return parse_packing_study(config::read_file_text(path, "study file"), path); }

}  // namespace granwave::sweep
