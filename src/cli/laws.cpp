// granwave laws [--json]: every contact law of this build's registry with its [contact] keys,
// defaults, units and ranges, from each law's own description (src/contact/*_params.hpp); the
// crosscheck's mapping (crosscheck/xclib/lawdesc.py) reads the JSON instead of a copy.
#include <cmath>
#include <iomanip>
#include <iostream>
#include <sstream>
#include <string>

#include "cli/verbs.hpp"
#include "config/contact_laws.hpp"
#include "contact/friction.hpp"
#include "contact/rolling_torsion_keys.hpp"
#include "core/error.hpp"
#include "core/json.hpp"

namespace granwave::cli {
namespace {

constexpr const char* kLawsHelp = R"(usage: granwave laws [--json]

Every contact law this build runs ([contact] law = NAME; the first is the default), with each of
its [contact] keys: unit, allowed range, default and meaning. Friction's keys (mu_static,
mu_dynamic, normal_tension, lever_arm, coulomb_normal) belong to every law; rolling and torsion
keys to the laws that carry them.

  --json   one JSON object (schema "granwave-laws/1"): {"laws": [{"name", "summary", "default",
           "stiffness_of_overlap", "hertz_normal", "linearisation", "keys": [{"key", "group"
           ("law", "rolling_torsion" or "friction"), "kind" ("number" or "choice"), "unit",
           "required", "default" (null: none, see "default_note"), "default_note", "range" (the
           text the messages give), "min", "min_open", "max", "max_open" (numbers; null: unbounded),
           "choices" (choices; the first is the default), "meaning"}]}]}
)";

bool in(const contact::KeySpec& k, const auto& list) {
  for (const contact::KeySpec& o : list)
    if (std::string_view(o.key) == k.key) return true;
  return false;
}

const char* group_of(const contact::KeySpec& k) {
  if (in(k, contact::Friction::keys)) return "friction";
  if (in(k, contact::RollingTorsionKeys::keys)) return "rolling_torsion";
  return "law";
}

Json key_json(const contact::KeySpec& k) {
  Json j{{"key", k.key}, {"group", group_of(k)}};
  if (k.kind == contact::KeySpec::Kind::choice) {
    j["kind"] = "choice";
    Json choices = Json::array();
    for (std::string_view c : k.options()) choices.push_back(std::string(c));
    j["required"] = false;
    j["default"] = std::string(k.choices[0]);
    j["choices"] = choices;
  } else {
    j["kind"] = "number";
    j["unit"] = k.unit;
    j["required"] = k.required;
    j["default"] = std::isnan(k.fallback) ? Json(nullptr) : Json(k.fallback);
    if (*k.default_note) j["default_note"] = k.default_note;
    j["range"] = k.range();
    j["min"] = std::isfinite(k.lo) ? Json(k.lo) : Json(nullptr);
    j["min_open"] = k.lo_open;
    j["max"] = std::isfinite(k.hi) ? Json(k.hi) : Json(nullptr);
    j["max_open"] = k.hi_open;
  }
  j["meaning"] = k.meaning;
  return j;
}

std::string default_text(const contact::KeySpec& k) {
  if (k.kind == contact::KeySpec::Kind::choice) return "\"" + std::string(k.choices[0]) + "\"";
  if (k.required) return "required";
  if (*k.default_note) return k.default_note;
  std::ostringstream o;
  o << k.fallback;
  return o.str();
}

}  // namespace

int cmd_laws(const Args& args) { return cmd_laws(args, std::cout); }

int cmd_laws(const Args& args, std::ostream& out) {
  if (wants_help(args)) {
    out << kLawsHelp;
    return 0;
  }
  for (const std::string& a : args)
    if (a != "--json") throw InputError("laws: unknown argument '" + a + "' (granwave laws --help)");
  const auto laws = config::contact_laws();
  if (has_flag(args, "--json")) {
    Json list = Json::array();
    for (const config::ContactLawInfo* law : laws) {
      Json keys = Json::array();
      for (const contact::KeySpec& k : law->specs) keys.push_back(key_json(k));
      list.push_back({{"name", law->name},
                      {"summary", law->summary},
                      {"default", law == laws.front()},
                      {"stiffness_of_overlap", law->stiffness_of_overlap},
                      {"hertz_normal", law->hertz_normal},
                      {"linearisation", law->linearisation_note ? Json(law->linearisation_note) : Json(nullptr)},
                      {"keys", keys}});
    }
    out << json_text(Json{{"schema", "granwave-laws/1"}, {"laws", list}}) << "\n";
    return 0;
  }
  for (const config::ContactLawInfo* law : laws) {
    out << "law " << law->name << (law == laws.front() ? " (the default)" : "") << ": " << law->summary << "\n";
    for (const contact::KeySpec& k : law->specs) {
      const bool number = k.kind == contact::KeySpec::Kind::number;
      std::string allowed;
      if (number) {
        allowed = k.range();
      } else {
        for (std::string_view c : k.options()) allowed += (allowed.empty() ? "" : " | ") + std::string(c);
      }
      out << "  " << std::left << std::setw(19) << k.key << std::setw(6) << (number ? k.unit : "") << std::setw(34)
          << allowed << " default " << std::setw(12) << default_text(k) << " " << k.meaning << "\n";
    }
  }
  return 0;
}

}  // namespace granwave::cli
