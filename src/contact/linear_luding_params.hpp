// The parameters of the case-file law "linear" (contact/linear_luding_case.hpp): their [contact]
// keys with units, ranges and defaults, and their reading. Seed 002 sec. 2.1: k, gamma_0 and
// Luding's tangential spring and dashpot; rolling and torsion resistance and friction embedded.
#pragma once
#include <array>
#include <string_view>

#include "contact/case_keys.hpp"
#include "contact/friction.hpp"
#include "contact/law_id.hpp"
#include "contact/rolling_torsion_keys.hpp"

namespace granwave::contact {

struct LinearLudingParams {
  static constexpr ContactLaw law = ContactLaw::linear;
  double kn = 0.0;       // N/m
  double gamma_n = 0.0;  // kg/s
  double kt = 0.0;       // N/m
  double gamma_t = 0.0;  // kg/s
  RollingTorsionKeys rolling;
  Friction friction;

  static constexpr std::array<KeySpec, 4> own_keys{
      required_key(number_key("kn", "N/m", 0.0, true, 0.0, "normal spring k")),
      number_key("kt", "N/m", 0.0, false, 0.0, "tangential spring k_t"),
      number_key("gamma_n", "kg/s", 0.0, false, 0.0, "normal dashpot gamma_0"),
      number_key("gamma_t", "kg/s", 0.0, false, 0.0, "tangential dashpot gamma_t")};
  static constexpr auto keys = joined(own_keys, RollingTorsionKeys::keys);
  std::array<double*, 4> fields() { return {&kn, &kt, &gamma_n, &gamma_t}; }  // own_keys' order

  template <class Reader, class Table>
  static LinearLudingParams read(const Reader& r, const Table& t) {
    LinearLudingParams p;
    read_numbers(r, t, own_keys, p.fields());
    p.rolling = RollingTorsionKeys::read(r, t);
    p.friction = Friction::read(r, t);
    return p;
  }
  double* number(std::string_view key) {
    double* f = number_field(own_keys, fields(), key);
    return f ? f : rolling.number(key);
  }
};

}  // namespace granwave::contact
