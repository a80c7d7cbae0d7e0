// The study file (data/SCHEMA.md §4): TOML -> a validated SpinStudy. Reading and error messages:
// config/toml_reader.hpp, shared with the case loader.
#include <cstdint>
#include <filesystem>
#include <fstream>
#include <sstream>

#include "config/toml_reader.hpp"
#include "core/error.hpp"
#include "sweep/spin_study.hpp"

namespace granwave::sweep {
SpinStudy parse_spin_study(const std::string& text, const std::string& origin) {
  const config::TomlReader r(origin);
  const toml::table root = config::parse_toml(text, origin);
  r.allow_only(root, "", {"study", "spin_chain", "run"});
  SpinStudy s;
  s.path = origin;
  s.text = text;

  const toml::table& st = *r.table(root, "", "study", true);
  r.allow_only(st, "study", {"name", "kind", "case", "case_toml", "seed", "configurations", "batch", "bootstrap"});
  s.name = *r.string(st, "study", "name", true);
  if (s.name.empty()) r.fail("study.name", "must not be empty", st.get("name"));
  const std::string kind = *r.string(st, "study", "kind", true);
  if (kind != "spin_chain") r.fail("study.kind", "must be \"spin_chain\" (the crystal studies come with issue 5)", st.get("kind"));
  auto case_path = r.string(st, "study", "case", false);
  auto case_toml = r.string(st, "study", "case_toml", false);
  if (case_path.has_value() == case_toml.has_value())
    r.fail("study.case", "give exactly one of 'case' (a case file, relative to the study file) and 'case_toml' (inline)", st.get("case"));
  if (case_path) {
    std::filesystem::path p(*case_path);
    if (p.is_relative()) p = std::filesystem::path(origin).parent_path() / p;
    if (!std::filesystem::exists(p)) r.fail("study.case", "no such case file: " + p.string(), st.get("case"));
    s.base = config::load_case(p.string());
    s.base_text = s.base.toml_text;
  } else {
    s.base = config::parse_case(*case_toml, origin + " [study.case_toml]");
    s.base_text = *case_toml;
  }
  if (s.base.model != config::Model::chain || !s.base.chain)
    r.fail("study.case", "the base case must be a chain case (model = \"chain\")", st.get("case"));
  s.seed = static_cast<std::uint64_t>(*r.integer_in(st, "study", "seed", true, 0, INT64_MAX));
  s.configurations = static_cast<int>(r.integer_in(st, "study", "configurations", false, 1, 100000).value_or(20));
  s.batch = static_cast<std::size_t>(r.integer_in(st, "study", "batch", false, 1, 100000).value_or(32));
  s.bootstrap = static_cast<std::size_t>(r.integer_in(st, "study", "bootstrap", false, 0, 1000000).value_or(1000));

  const toml::table* sc = r.table(root, "", "spin_chain", true);
  r.allow_only(*sc, "spin_chain", {"layout", "n_total", "tail_dimers", "measure_beads", "profile_interval",
                                   "decay_skip_beads", "transmission_dimers"});
  const std::string layout = r.string(*sc, "spin_chain", "layout", false).value_or("tail");
  if (layout == "tail") s.layout = SpinStudy::Layout::tail;
  else if (layout == "base") s.layout = SpinStudy::Layout::base;
  else r.fail("spin_chain.layout", "must be \"tail\" (N_total flippable dimers + tail_dimers fixed ones) or \"base\" (the base case's segments)", sc->get("layout"));
  for (auto n : r.integers_in(*sc, "spin_chain", "n_total", 2, 100000)) s.n_total.push_back(static_cast<int>(n));
  if (s.layout == SpinStudy::Layout::tail && s.n_total.empty()) r.fail("spin_chain.n_total", "missing (layout \"tail\" needs the chain lengths)");
  if (s.layout == SpinStudy::Layout::base && !s.n_total.empty())
    r.fail("spin_chain.n_total", "not allowed with layout \"base\" (N_total = the base case's cells that count for M)", sc->get("n_total"));
  s.tail_dimers = static_cast<int>(r.integer_in(*sc, "spin_chain", "tail_dimers", false, 0, 100000).value_or(15));
  if (const toml::node* n = sc->get("measure_beads")) {
    auto mb = r.integers_in(*sc, "spin_chain", "measure_beads", 1, 1000);
    if (mb.size() != 2 || mb[0] > mb[1]) r.fail("spin_chain.measure_beads", "must be [first, last] with 1 <= first <= last", n);
    s.measure_first = static_cast<int>(mb[0]);
    s.measure_last = static_cast<int>(mb[1]);
  }
  if (s.layout == SpinStudy::Layout::tail && s.tail_dimers * 2 < s.measure_last)
    r.fail("spin_chain.tail_dimers", "the tail must hold the measured beads (2 tail_dimers >= " + std::to_string(s.measure_last) + ")", sc->get("tail_dimers"));
  s.profile_interval =
      r.number_in(*sc, "spin_chain", "profile_interval", false, [](double v) { return v > 0 && v < 1e-3; }, "in (0, 1e-3) s").value_or(2e-6);
  s.decay_skip_beads = static_cast<int>(r.integer_in(*sc, "spin_chain", "decay_skip_beads", false, 0, 100000).value_or(10));
  s.transmission_dimers = static_cast<int>(r.integer_in(*sc, "spin_chain", "transmission_dimers", false, 10, 100000).value_or(60));

  if (const toml::table* run = r.table(root, "", "run", false)) {
    r.allow_only(*run, "run", {"dt", "stop", "margin_beads", "front_threshold", "max_time_per_bead"});
    s.dt = r.number_in(*run, "run", "dt", false, [](double v) { return v > 0 && v < 1e-4; }, "in (0, 1e-4) s");
    s.stop = r.boolean(*run, "run", "stop").value_or(true);
    s.margin_beads = static_cast<int>(r.integer_in(*run, "run", "margin_beads", false, 1, 100000).value_or(10));
    s.front_threshold = r.number_in(*run, "run", "front_threshold", false, [](double v) { return v > 0 && v < 1; }, "in (0, 1)").value_or(1e-3);
    s.max_time_per_bead = r.number_in(*run, "run", "max_time_per_bead", false, [](double v) { return v > 0 && v < 1; }, "in (0, 1) s").value_or(4e-5);
  }
  if (!s.dt && !s.base.integrator.dt && !s.base.integrator.dt_over_tc)
    r.fail("run.dt", "missing: neither the study nor the base case gives a time step");
  return s;
}

SpinStudy load_spin_study(const std::string& path) {
  return parse_spin_study(config::read_file_text(path, "study file"), path);
}

}  // namespace granwave::sweep
