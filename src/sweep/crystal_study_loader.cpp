// The crystal study file (data/SCHEMA.md §6): TOML -> a validated CrystalStudy. The crystal
// studies' only toml++ translation unit. Unknown keys are errors, as in the case loader.
#include <toml++/toml.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <sstream>

#include "core/error.hpp"
#include "sweep/crystal_study.hpp"

namespace granwave::sweep {
namespace {

std::string where(const std::string& origin, const toml::node* n) {
  std::ostringstream o;
  o << origin;
  if (n && n->source().begin) o << ":" << n->source().begin.line << ":" << n->source().begin.column;
  return o.str();
}
[[noreturn]] void fail(const std::string& origin, const std::string& key, const std::string& what, const toml::node* n = nullptr) {
  throw InputError(where(origin, n) + ": key '" + key + "': " + what);
}
void allow_only(const std::string& origin, const toml::table& t, const std::string& path,
                std::initializer_list<std::string_view> keys) {
  for (auto&& [k, v] : t)
    if (std::find(keys.begin(), keys.end(), k.str()) == keys.end()) {
      std::string allowed;
      for (auto a : keys) allowed += (allowed.empty() ? "" : ", ") + std::string(a);
      fail(origin, path + "." + std::string(k.str()), "unknown key (allowed here: " + allowed + ")", &v);
    }
}
std::optional<double> number(const std::string& origin, const toml::table& t, const std::string& path, const char* key) {
  const toml::node* n = t.get(key);
  if (!n) return std::nullopt;
  if (auto d = n->value_exact<double>()) return *d;
  if (auto i = n->value_exact<int64_t>()) return static_cast<double>(*i);
  fail(origin, path + "." + key, "must be a number", n);
}
std::vector<double> numbers(const std::string& origin, const toml::table& t, const std::string& path, const char* key) {
  const toml::node* n = t.get(key);
  if (!n) return {};
  const toml::array* a = n->as_array();
  if (!a || a->empty()) fail(origin, path + "." + key, "must be a non-empty array of numbers", n);
  std::vector<double> v;
  for (auto&& e : *a) {
    if (auto d = e.value_exact<double>()) v.push_back(*d);
    else if (auto i = e.value_exact<int64_t>()) v.push_back(static_cast<double>(*i));
    else fail(origin, path + "." + key, "must be an array of numbers", &e);
    if (!std::isfinite(v.back())) fail(origin, path + "." + key, "must be finite", &e);
  }
  return v;
}
std::string text_of(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  if (!in) throw InputError(path + ": cannot read the study file");
  std::ostringstream s;
  s << in.rdbuf();
  return s.str();
}

}  // namespace

bool is_crystal_study(const std::string& toml_text) {
  try {
    const toml::table root = toml::parse(toml_text);
    const auto kind = root["study"]["kind"].value<std::string>();
    return kind && *kind == "crystal";
  } catch (const toml::parse_error&) {
    return false;
  }
}

CrystalStudy parse_crystal_study(const std::string& text, const std::string& origin) {
  toml::table root;
  try {
    root = toml::parse(text, origin);
  } catch (const toml::parse_error& e) {
    std::ostringstream m;
    m << origin << ":" << e.source().begin.line << ":" << e.source().begin.column << ": " << e.description();
    throw InputError(m.str());
  }
  CrystalStudy s;
  s.path = origin;
  s.text = text;
  allow_only(origin, root, "", {"study", "run"});
  const toml::table* st = root["study"].as_table();
  if (!st) fail(origin, "study", "missing (a table is required)");
  allow_only(origin, *st, "study", {"name", "kind", "case", "vary", "values", "modes", "positions", "batch"});
  s.name = st->get("name") ? st->get("name")->value_or(std::string()) : "";
  if (s.name.empty()) fail(origin, "study.name", "missing or empty (a string)", st->get("name"));
  if (st->get("kind") == nullptr || st->get("kind")->value_or(std::string()) != "crystal")
    fail(origin, "study.kind", "must be \"crystal\"", st->get("kind"));
  const std::string case_rel = st->get("case") ? st->get("case")->value_or(std::string()) : "";
  if (case_rel.empty()) fail(origin, "study.case", "missing (a crystal case file, relative to the study file)");
  std::filesystem::path cp(case_rel);
  if (cp.is_relative()) cp = std::filesystem::path(origin).parent_path() / cp;
  if (!std::filesystem::exists(cp)) fail(origin, "study.case", "no such case file: " + cp.string(), st->get("case"));
  s.base = config::load_case(cp.string());
  if (s.base.model != config::Model::crystal || !s.base.crystal)
    fail(origin, "study.case", "the base case must be a crystal case (model = \"crystal\")", st->get("case"));

  const std::string vary = st->get("vary") ? st->get("vary")->value_or(std::string()) : "";
  if (vary == "gamma_n") s.vary = CrystalVary::gamma_n;
  else if (vary == "kt_over_k") s.vary = CrystalVary::kt_over_k;
  else if (vary == "polydispersity") s.vary = CrystalVary::polydispersity;
  else fail(origin, "study.vary", "must be \"gamma_n\", \"kt_over_k\" or \"polydispersity\"", st->get("vary"));
  s.values = numbers(origin, *st, "study", "values");
  if (s.values.empty()) fail(origin, "study.values", "missing (the parameter values)");
  for (double v : s.values)
    if (v < 0.0) fail(origin, "study.values", "must be >= 0", st->get("values"));

  if (const toml::node* n = st->get("modes")) {
    const toml::array* a = n->as_array();
    if (!a || a->empty()) fail(origin, "study.modes", "must be a non-empty array of \"P\" / \"S\"", n);
    s.modes.clear();
    for (auto&& e : *a) {
      const std::string m = e.value_or(std::string());
      if (m != "P" && m != "S") fail(origin, "study.modes", "entries must be \"P\" or \"S\"", &e);
      s.modes.push_back(m[0]);
    }
  }
  if (st->get("positions")) {
    s.positions = numbers(origin, *st, "study", "positions");
    for (double z : s.positions)
      if (z < 1.0 || z != std::round(z)) fail(origin, "study.positions", "must be whole layer numbers z/l0 >= 1", st->get("positions"));
  }
  if (auto b = number(origin, *st, "study", "batch")) {
    if (*b < 1 || *b != std::round(*b)) fail(origin, "study.batch", "must be an integer >= 1", st->get("batch"));
    s.batch = static_cast<std::size_t>(*b);
  }

  if (const toml::table* run = root["run"].as_table()) {
    allow_only(origin, *run, "run", {"layers", "t_end", "t_end_s", "dt", "interval"});
    if (auto v = number(origin, *run, "run", "layers")) {
      if (*v < 2 * s.base.crystal->fixed_layers + 10 || *v != std::round(*v))
        fail(origin, "run.layers", "must be an integer, at least 2 fixed_layers + 10", run->get("layers"));
      s.layers = static_cast<int>(*v);
    }
    auto positive = [&](const char* key, std::optional<double>& into) {
      if (auto v = number(origin, *run, "run", key)) {
        if (!(*v > 0.0)) fail(origin, std::string("run.") + key, "must be > 0", run->get(key));
        into = *v;
      }
    };
    positive("t_end", s.t_end);
    positive("t_end_s", s.t_end_s);
    positive("dt", s.dt);
    positive("interval", s.interval);
  }
  const int layers = s.layers.value_or(s.base.crystal->cells[2]);
  for (double z : s.positions)
    if (z > layers - 2 * s.base.crystal->fixed_layers)
      fail(origin, "study.positions", "z/l0 beyond the last free layer of a " + std::to_string(layers) + "-layer crystal");
  return s;
}

CrystalStudy load_crystal_study(const std::string& path) { return parse_crystal_study(text_of(path), path); }

}  // namespace granwave::sweep
