// The [contact] keys of rolling and torsion resistance (contact/rolling_torsion.hpp) for a law that
// carries it (linear, hertz_mindlin embed one): springs, dashpots and limits, the lever and history
// conventions, their reading and `granwave check`'s line.
#pragma once
#include <array>
#include <cmath>
#include <sstream>
#include <string>
#include <string_view>

#include "contact/case_keys.hpp"
#include "contact/friction.hpp"
#include "contact/rolling_torsion.hpp"

namespace granwave::contact {

struct RollingTorsionKeys {
  // springs (N/m) and dashpots (kg/s) on the lever a', limits mu f_n (absent: no limit); all zero: off.
  double kr = 0.0, gamma_r = 0.0, mu_r = HUGE_VAL;
  double ko = 0.0, gamma_o = 0.0, mu_o = HUGE_VAL;
  RollingLever rolling_lever = RollingLever::lever_arm;  // the arms of a'
  RollingHistory rolling_history = RollingHistory::rotated;

  static constexpr std::array<KeySpec, 8> keys{
      number_key("kr", "N/m", 0.0, false, 0.0, "rolling spring"),
      number_key("gamma_r", "kg/s", 0.0, false, 0.0, "rolling dashpot"),
      default_from(number_key("mu_r", "", 0.0, false, 0.0, "rolling limit mu_r f_n"), "no limit"),
      number_key("ko", "N/m", 0.0, false, 0.0, "torsion spring"),
      number_key("gamma_o", "kg/s", 0.0, false, 0.0, "torsion dashpot"),
      default_from(number_key("mu_o", "", 0.0, false, 0.0, "torsion limit mu_o f_n"), "no limit"),
      choice_key("rolling_lever", {"lever_arm", "radii"}, "the arms of the lever a' = arm_i arm_j/(arm_i + arm_j)"),
      choice_key("rolling_history", {"rotated", "fixed"}, "the rolling spring: turned with the contact or fixed in space")};

  // keys' order (an absent mu_r, mu_o stays "no limit"); the two choices are read apart.
  std::array<double*, 8> fields() { return {&kr, &gamma_r, &mu_r, &ko, &gamma_o, &mu_o, nullptr, nullptr}; }

  template <class Reader, class Table>
  static RollingTorsionKeys read(const Reader& r, const Table& t) {
    RollingTorsionKeys k;
    read_numbers(r, t, keys, k.fields());
    k.rolling_lever = read_choice(r, t, keys[6]) == "radii" ? RollingLever::radii : RollingLever::lever_arm;
    k.rolling_history = read_choice(r, t, keys[7]) == "fixed" ? RollingHistory::fixed : RollingHistory::rotated;
    return k;
  }
  // A number key by name (studies vary kr, ko); nullptr if it is not one of these.
  double* number(std::string_view key) { return number_field(keys, fields(), key); }

  RollingTorsionParams params(const Friction& f) const {
    return {kr, gamma_r, mu_r, ko, gamma_o, mu_o, f.magnitude(), rolling_lever, rolling_history};
  }
  bool active(const Friction& f) const { return params(f).active(); }
  // `granwave check`'s line about them ("" when off).
  std::string line(const Friction& f) const {
    if (!active(f)) return "";
    std::ostringstream o;
    o << "  rolling: kr = " << kr << " N/m, gamma_r = " << gamma_r << " kg/s, mu_r = " << mu_r
      << "; torsion: ko = " << ko << " N/m, gamma_o = " << gamma_o << " kg/s, mu_o = " << mu_o
      << " (lever a' = arm_i arm_j/(arm_i + arm_j), arms "
      << (rolling_lever == RollingLever::radii ? "the radii a_p" : "the lever arm's") << "; rolling spring "
      << rolling_history_name(rolling_history) << ")\n";
    return o.str();
  }
};

}  // namespace granwave::contact
