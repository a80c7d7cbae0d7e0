// The validating TOML reader shared by the case and study loaders. Include it from .cpp files only:
// toml++ is a private dependency of the libraries, so no public header may pull it in.
// Every error names the file (with line:column where known), the dotted key and what is allowed;
// unknown keys are errors (allow_only).
#pragma once

#include <toml++/toml.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <fstream>
#include <initializer_list>
#include <optional>
#include <sstream>
#include <span>
#include <string>
#include <string_view>
#include <utility>
#include <vector>

#include "core/error.hpp"

namespace granwave::config {

// The whole of a study's or case's file; `what` names it in the error ("study file").
inline std::string read_file_text(const std::string& path, const std::string& what) {
  std::ifstream in(path, std::ios::binary);
  if (!in) throw InputError(path + ": cannot read the " + what);
  std::ostringstream text;
  text << in.rdbuf();
  return text.str();
}

// [study] kind of a study file's text, or nothing (no such key, or not TOML): which loader takes it.
inline std::optional<std::string> study_kind(const std::string& toml_text) {
  try {
    return toml::parse(toml_text)["study"]["kind"].value<std::string>();
  } catch (const toml::parse_error&) {
    return std::nullopt;
  }
}

// Parses `text`; a syntax error becomes an InputError that names origin:line:col.
inline toml::table parse_toml(const std::string& text, const std::string& origin) {
  try {
    return toml::parse(text, origin);
  } catch (const toml::parse_error& e) {
    std::ostringstream msg;
    msg << origin << ":" << e.source().begin.line << ":" << e.source().begin.column << ": not valid TOML: " << e.description();
    throw InputError(msg.str());
  }
}

class TomlReader {
 public:
  explicit TomlReader(std::string origin) : origin_(std::move(origin)) {}

  static std::string join(const std::string& path, const std::string& key) { return path.empty() ? key : path + "." + key; }

  [[noreturn]] void fail(const std::string& key, const std::string& what, const toml::node* where = nullptr) const {
    std::ostringstream msg;
    msg << origin_;
    if (where && where->source().begin) msg << ":" << where->source().begin.line << ":" << where->source().begin.column;
    msg << ": key '" << key << "': " << what;
    throw InputError(msg.str());
  }

  // Only these keys may appear in `table` (whose dotted name is `path`).
  void allow_only(const toml::table& table, const std::string& path, std::initializer_list<std::string_view> keys) const {
    allow_only(table, path, std::span<const std::string_view>(keys.begin(), keys.size()));
  }
  void allow_only(const toml::table& table, const std::string& path, std::span<const std::string_view> keys) const {
    for (auto&& [k, v] : table) {
      if (std::find(keys.begin(), keys.end(), k.str()) == keys.end()) {
        fail(join(path, std::string(k.str())), "unknown key (allowed here: " + list(keys, "") + ")", &v);
      }
    }
  }

  const toml::table* table(const toml::table& parent, const std::string& path, const std::string& key, bool required) const {
    const toml::node* n = lookup(parent, path, key, required, "a table");
    if (!n) return nullptr;
    if (!n->is_table()) fail(join(path, key), "must be a table", n);
    return n->as_table();
  }

  std::optional<double> number(const toml::table& t, const std::string& path, const std::string& key, bool required) const {
    const toml::node* n = lookup(t, path, key, required, "a number");
    if (!n) return std::nullopt;
    auto v = as_number(*n);
    if (!v) fail(join(path, key), "must be a number", n);
    if (!std::isfinite(*v)) fail(join(path, key), "must be a finite number", n);
    return v;
  }

  // A finite number with a range check: `ok` decides, `allowed` describes the range in the messages.
  template <class Pred>
  std::optional<double> number_in(const toml::table& t, const std::string& path, const std::string& key, bool required,
                                  Pred ok, const std::string& allowed) const {
    const toml::node* n = lookup(t, path, key, required, "a number " + allowed);
    if (!n) return std::nullopt;
    auto v = as_number(*n);
    if (!v) fail(join(path, key), "must be a number " + allowed, n);
    if (!std::isfinite(*v) || !ok(*v)) {
      std::ostringstream s;
      s << "must be " << allowed << " (got " << *v << ")";
      fail(join(path, key), s.str(), n);
    }
    return v;
  }

  // A non-empty array of finite numbers; empty result if the key is absent.
  std::vector<double> numbers(const toml::table& t, const std::string& path, const std::string& key) const {
    const toml::node* n = t.get(key);
    if (!n) return {};
    const toml::array* a = n->as_array();
    if (!a || a->empty()) fail(join(path, key), "must be a non-empty array of numbers", n);
    std::vector<double> out;
    for (auto&& e : *a) {
      auto v = as_number(e);
      if (!v) fail(join(path, key), "must be an array of numbers", &e);
      if (!std::isfinite(*v)) fail(join(path, key), "must be finite", &e);
      out.push_back(*v);
    }
    return out;
  }

  std::optional<std::int64_t> integer(const toml::table& t, const std::string& path, const std::string& key, bool required) const {
    return scalar<std::int64_t>(t, path, key, required, "an integer");
  }

  std::optional<std::int64_t> integer_in(const toml::table& t, const std::string& path, const std::string& key, bool required,
                                         std::int64_t lo, std::int64_t hi) const {
    const std::string range = "an integer in [" + std::to_string(lo) + ", " + std::to_string(hi) + "]";
    const toml::node* n = lookup(t, path, key, required, range);
    if (!n) return std::nullopt;
    auto i = n->value_exact<std::int64_t>();
    if (!i) fail(join(path, key), "must be " + range, n);
    if (*i < lo || *i > hi) fail(join(path, key), "must be " + range + " (got " + std::to_string(*i) + ")", n);
    return *i;
  }

  // An array of integers, possibly empty; empty result if the key is absent.
  std::vector<std::int64_t> integers(const toml::table& t, const std::string& path, const std::string& key) const {
    return array_of<std::int64_t>(t, path, key, false, "integers");
  }

  // A non-empty array of integers in [lo, hi]; empty result if the key is absent.
  std::vector<std::int64_t> integers_in(const toml::table& t, const std::string& path, const std::string& key, std::int64_t lo,
                                        std::int64_t hi) const {
    const toml::node* n = t.get(key);
    if (!n) return {};
    const toml::array* a = n->as_array();
    const std::string what = "must be a non-empty array of integers in [" + std::to_string(lo) + ", " + std::to_string(hi) + "]";
    if (!a || a->empty()) fail(join(path, key), what, n);
    std::vector<std::int64_t> out;
    for (auto&& e : *a) {
      auto i = e.value_exact<std::int64_t>();
      if (!i || *i < lo || *i > hi) fail(join(path, key), what, &e);
      out.push_back(*i);
    }
    return out;
  }

  std::optional<std::string> string(const toml::table& t, const std::string& path, const std::string& key, bool required) const {
    return scalar<std::string>(t, path, key, required, "a string");
  }

  // One of `options`; `fallback` if the key is absent.
  std::string choice(const toml::table& t, const std::string& path, const std::string& key, std::initializer_list<std::string_view> options,
                     std::string fallback) const {
    return choice(t, path, key, std::span<const std::string_view>(options.begin(), options.size()), std::move(fallback));
  }
  std::string choice(const toml::table& t, const std::string& path, const std::string& key,
                     std::span<const std::string_view> options, std::string fallback) const {
    auto s = string(t, path, key, false);
    if (!s) return fallback;
    if (std::find(options.begin(), options.end(), *s) == options.end()) {
      fail(join(path, key), "must be one of " + list(options, "\"") + " (got \"" + *s + "\")", t.get(key));
    }
    return *s;
  }

  // One of `options`, required.
  std::string choice(const toml::table& t, const std::string& path, const std::string& key,
                     std::initializer_list<std::string_view> options) const {
    if (!t.contains(key)) fail(join(path, key), "missing (one of " + list(options, "\"") + ")");
    return choice(t, path, key, options, "");
  }

  std::optional<bool> boolean(const toml::table& t, const std::string& path, const std::string& key) const {
    const toml::node* n = t.get(key);
    if (!n) return std::nullopt;
    if (auto b = n->value_exact<bool>()) return *b;
    fail(join(path, key), "must be true or false", n);
  }

  std::vector<std::string> strings(const toml::table& t, const std::string& path, const std::string& key, bool required) const {
    return array_of<std::string>(t, path, key, required, "strings");
  }

 private:
  // The node at `key`, or nullptr if it is absent and optional; `what` names the expected value.
  const toml::node* lookup(const toml::table& t, const std::string& path, const std::string& key, bool required,
                           const std::string& what) const {
    const toml::node* n = t.get(key);
    if (!n && required) fail(join(path, key), "missing (" + what + " is required)");
    return n;
  }

  // A value of exactly type T (no conversions); `what` names it in the messages ("an integer").
  template <class T>
  std::optional<T> scalar(const toml::table& t, const std::string& path, const std::string& key, bool required,
                          const std::string& what) const {
    const toml::node* n = lookup(t, path, key, required, what);
    if (!n) return std::nullopt;
    if (auto v = n->value_exact<T>()) return *v;
    fail(join(path, key), "must be " + what, n);
  }

  // An array of exactly type T, possibly empty; `what` is the plural ("strings").
  template <class T>
  std::vector<T> array_of(const toml::table& t, const std::string& path, const std::string& key, bool required,
                          const std::string& what) const {
    const toml::node* n = lookup(t, path, key, required, "an array of " + what);
    if (!n) return {};
    const toml::array* a = n->as_array();
    if (!a) fail(join(path, key), "must be an array of " + what, n);
    std::vector<T> out;
    for (auto&& e : *a) {
      auto v = e.value_exact<T>();
      if (!v) fail(join(path, key), "must be an array of " + what, &e);
      out.push_back(*v);
    }
    return out;
  }

  // TOML integers count as numbers.
  static std::optional<double> as_number(const toml::node& n) {
    if (auto d = n.value_exact<double>()) return *d;
    if (auto i = n.value_exact<std::int64_t>()) return static_cast<double>(*i);
    return std::nullopt;
  }

  static std::string list(std::initializer_list<std::string_view> items, const char* quote) {
    return list(std::span<const std::string_view>(items.begin(), items.size()), quote);
  }
  static std::string list(std::span<const std::string_view> items, const char* quote) {
    std::string s;
    for (auto i : items) s += (s.empty() ? "" : ", ") + (quote + std::string(i) + quote);
    return s;
  }

  std::string origin_;
};

}  // namespace granwave::config
