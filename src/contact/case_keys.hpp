// What one [contact] key of a law is: its name, unit, allowed range, default and meaning, written
// once and used both to read the case (read_number, read_choice: the messages name the key and
// the range) and to export the law's description (`granwave laws --json`), in the manner of LAMMPS'
// granular sub-models' coefficients. The Reader is a template parameter (config::TomlReader), so
// contact/ needs neither config/ nor toml++.
#pragma once
#include <array>
#include <cmath>
#include <limits>
#include <optional>
#include <span>
#include <string>
#include <string_view>

namespace granwave::contact {

struct KeySpec {
  enum class Kind { number, choice };
  const char* key = "";
  Kind kind = Kind::number;
  const char* unit = "";   // SI unit of a number ("" for a pure number)
  // number: the range lo < v (lo_open) or lo <= v, v < hi (hi_open) or v <= hi
  double lo = -std::numeric_limits<double>::infinity();
  bool lo_open = false;
  double hi = std::numeric_limits<double>::infinity();
  bool hi_open = false;
  bool required = false;
  double fallback = 0.0;            // a number's default when absent (NaN: see default_note)
  const char* default_note = "";    // a default that is not a number ("mu_static", "no limit")
  std::array<std::string_view, 3> choices{};  // choice: the allowed values, the first the default
  const char* note = "";            // said in the range's parentheses in place of the unit
  const char* meaning = "";

  constexpr bool admits(double v) const {
    return (lo_open ? v > lo : v >= lo) && (hi_open ? v < hi : v <= hi);
  }
  std::span<const std::string_view> options() const {
    std::size_t n = 0;
    while (n < choices.size() && !choices[n].empty()) ++n;
    return {choices.data(), n};
  }
  // The range as the messages give it: "> 0 (N/m)", "in (-1, 0.5)", ">= 0".
  std::string range() const {
    auto num = [](double v) {
      std::string s = std::to_string(v);
      s.erase(s.find_last_not_of('0') + 1);
      if (!s.empty() && s.back() == '.') s.pop_back();
      return s;
    };
    std::string r;
    if (std::isfinite(hi))
      r = std::string("in ") + (lo_open ? "(" : "[") + num(lo) + ", " + num(hi) + (hi_open ? ")" : "]");
    else
      r = std::string(lo_open ? "> " : ">= ") + num(lo);
    if (*note) return r + " (" + note + ")";
    if (*unit) return r + " (" + unit + ")";
    return r;
  }
};

// Constructors of the two kinds (constexpr tables stay short).
constexpr KeySpec number_key(const char* key, const char* unit, double lo, bool lo_open, double fallback,
                             const char* meaning) {
  KeySpec s;
  s.key = key, s.unit = unit, s.lo = lo, s.lo_open = lo_open, s.fallback = fallback, s.meaning = meaning;
  return s;
}
constexpr KeySpec required_key(KeySpec s) {
  s.required = true;
  s.fallback = std::numeric_limits<double>::quiet_NaN();
  return s;
}
constexpr KeySpec below(KeySpec s, double hi, bool open) {
  s.hi = hi, s.hi_open = open;
  return s;
}
constexpr KeySpec with_note(KeySpec s, const char* note) {
  s.note = note;
  return s;
}
constexpr KeySpec default_from(KeySpec s, const char* what) {
  s.fallback = std::numeric_limits<double>::quiet_NaN();
  s.default_note = what;
  return s;
}
constexpr KeySpec choice_key(const char* key, std::array<std::string_view, 3> choices, const char* meaning) {
  KeySpec s;
  s.key = key, s.kind = KeySpec::Kind::choice, s.choices = choices, s.meaning = meaning;
  return s;
}

// A number key of [contact]; its default when absent (nullopt when it has none).
template <class Reader, class Table>
std::optional<double> read_number(const Reader& r, const Table& t, const KeySpec& s) {
  const std::optional<double> v = r.number_in(t, "contact", s.key, s.required, [&](double x) { return s.admits(x); }, s.range());
  if (v || std::isnan(s.fallback)) return v;
  return s.fallback;
}
// The number keys of `specs` read into their fields (`fields[i]` holds specs[i]'s value; nullptr for a
// choice key, read apart); an absent key without a default leaves its field as it is.
template <class Reader, class Table, std::size_t N>
void read_numbers(const Reader& r, const Table& t, const std::array<KeySpec, N>& specs,
                  const std::array<double*, N>& fields) {
  for (std::size_t i = 0; i < N; ++i)
    if (fields[i])
      if (const std::optional<double> v = read_number(r, t, specs[i])) *fields[i] = *v;
}
// The field of number key `key` (studies vary them by name); nullptr if `specs` has no such number key.
template <std::size_t N>
double* number_field(const std::array<KeySpec, N>& specs, const std::array<double*, N>& fields, std::string_view key) {
  for (std::size_t i = 0; i < N; ++i)
    if (fields[i] && key == specs[i].key) return fields[i];
  return nullptr;
}
// A choice key of [contact] (absent: the first choice).
template <class Reader, class Table>
std::string read_choice(const Reader& r, const Table& t, const KeySpec& s) {
  return r.choice(t, "contact", s.key, s.options(), std::string(s.choices[0]));
}

// The names of a list of keys.
template <std::size_t N>
constexpr std::array<const char*, N> names_of(const std::array<KeySpec, N>& specs) {
  std::array<const char*, N> n{};
  for (std::size_t i = 0; i < N; ++i) n[i] = specs[i].key;
  return n;
}
template <std::size_t N, std::size_t M>
constexpr std::array<KeySpec, N + M> joined(const std::array<KeySpec, N>& a, const std::array<KeySpec, M>& b) {
  std::array<KeySpec, N + M> out{};
  for (std::size_t i = 0; i < N; ++i) out[i] = a[i];
  for (std::size_t i = 0; i < M; ++i) out[N + i] = b[i];
  return out;
}

}  // namespace granwave::contact
