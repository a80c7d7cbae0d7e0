// The [contact] table's law-particular part for the case loader: the law's name, its keys (and
// the refusal of another law's), what it needs of the rest of the case. Asked of the registry
// (config/contact_laws.cpp); only loaders include this (it brings toml++).
#pragma once
#include <string_view>
#include <vector>

#include "config/case.hpp"
#include "config/toml_reader.hpp"

namespace granwave::config {

// Every key a [contact] table may hold: "law", the laws' own keys, then `common`.
std::vector<std::string_view> contact_keys(const std::vector<std::string_view>& common);
// [contact] law (default: the registry's first) and that law's parameters (its keys, then
// friction's); another law's key is refused.
contact::LawParams read_contact_law(const TomlReader& r, const toml::table& contact);
// What the law needs of the rest of the case (root: the case file's table).
void check_contact_law(const TomlReader& r, const toml::table& root, const Case& c);

}  // namespace granwave::config
