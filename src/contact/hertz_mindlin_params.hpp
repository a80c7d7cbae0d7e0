// The parameters of the case-file law "hertz_mindlin" (contact/hertz_mindlin_case.hpp): E, nu, the
// damping ratio, the tangential part and its history kind, their [contact] keys with units, ranges
// and defaults, and their reading; rolling and torsion resistance and friction embedded.
#pragma once
#include <array>
#include <string>
#include <string_view>

#include "contact/case_keys.hpp"
#include "contact/friction.hpp"
#include "contact/law_id.hpp"
#include "contact/rolling_torsion_keys.hpp"

namespace granwave::contact {

// What a Hertz-Mindlin contact keeps as its tangential history (contact/hertz_mindlin.hpp):
// displacement: f_t = -k_t(delta) xi (LAMMPS mindlin, LIGGGHTS tangential history);
// displacement_rescale: the same, xi scaled by a_new/a_old when the contact radius a shrinks
// (LAMMPS mindlin_rescale); force: incremental f_t += -k_t(delta) dxi (YADE Mindlin, LAMMPS mindlin/force).
enum class TangentialHistory { displacement, displacement_rescale, force };

struct HertzMindlinCaseParams {
  static constexpr ContactLaw law = ContactLaw::hertz_mindlin;
  double youngs_modulus = 0.0;  // E (Pa), both spheres
  double poisson_ratio = 0.0;   // nu, in (-1, 0.5)
  double damping_ratio = 0.0;   // beta: gamma_n(delta) = 2 beta sqrt(m* k_n(delta))
  bool mindlin = true;          // tangential = "mindlin" (false: "none", frictionless Hertz)
  TangentialHistory tangential_history = TangentialHistory::displacement;
  RollingTorsionKeys rolling;
  Friction friction;

  static constexpr std::array<KeySpec, 5> own_keys{
      below(required_key(number_key("youngs_modulus", "Pa", 0.0, true, 0.0, "Young's modulus E of both spheres")),
            HUGE_VAL, true),
      below(required_key(number_key("poisson_ratio", "", -1.0, true, 0.0, "Poisson's ratio nu")), 0.5, true),
      with_note(below(number_key("damping_ratio", "", 0.0, false, 0.0, "damping ratio beta"), 1.0, true),
                "gamma_n = 2 damping_ratio sqrt(m* k_n(delta)); 1 overdamps"),
      choice_key("tangential", {"mindlin", "none"}, "Mindlin's tangential spring, or frictionless Hertz"),
      choice_key("tangential_history", {"displacement", "displacement_rescale", "force"},
                 "what the Mindlin spring keeps: the displacement (rescaled when a shrinks) or the force")};
  static constexpr auto keys = joined(own_keys, RollingTorsionKeys::keys);
  // own_keys' order; the two choices are read apart.
  std::array<double*, 5> fields() { return {&youngs_modulus, &poisson_ratio, &damping_ratio, nullptr, nullptr}; }

  template <class Reader, class Table>
  static HertzMindlinCaseParams read(const Reader& r, const Table& t) {
    HertzMindlinCaseParams p;
    read_numbers(r, t, own_keys, p.fields());
    p.mindlin = read_choice(r, t, own_keys[3]) == "mindlin";
    const std::string h = read_choice(r, t, own_keys[4]);
    p.tangential_history = h == "force"                  ? TangentialHistory::force
                           : h == "displacement_rescale" ? TangentialHistory::displacement_rescale
                                                         : TangentialHistory::displacement;
    p.rolling = RollingTorsionKeys::read(r, t);
    if (p.rolling.rolling_history == RollingHistory::fixed)
      r.fail("contact.rolling_history", "\"fixed\" is for law = \"linear\" (LIGGGHTS' rolling_friction luding, whose history it "
             "is, runs on its linear model luding); hertz_mindlin takes \"rotated\"", t.get("rolling_history"));
    // The decorator needs the Mindlin spring's law (its torques and its deferral).
    if (!p.mindlin && p.rolling.params({}).active())
      for (const KeySpec& k : RollingTorsionKeys::keys)
        if (t.contains(k.key))
          r.fail(std::string("contact.") + k.key, "needs contact.tangential = \"mindlin\" (rolling and torsion resistance "
                 "on the frictionless Hertz law are not supported)", t.get(k.key));
    p.friction = Friction::read(r, t);
    return p;
  }
  double* number(std::string_view key) {
    double* f = number_field(own_keys, fields(), key);
    return f ? f : rolling.number(key);
  }
};

constexpr const char* tangential_history_name(TangentialHistory h) {
  switch (h) {
    case TangentialHistory::displacement: return "displacement";
    case TangentialHistory::displacement_rescale: return "displacement_rescale";
    case TangentialHistory::force: return "force";
  }
  return "";
}

}  // namespace granwave::contact
