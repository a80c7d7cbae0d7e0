// A crystal's [packing] table (lattice = "file", data/SCHEMA.md §1) for the case loader: its keys,
// the import of the file they name, and the defaults that need the packing. Only
// config/case_loader.cpp includes this (it brings toml++).
#pragma once
#include "config/case.hpp"
#include "config/toml_reader.hpp"
#include "packing/contacts.hpp"

namespace granwave::config {

// With lattice = "file": refuses the lattice's own [crystal] keys, reads [packing], imports the file
// (src/packing: exit 2 naming file, line and particle for a bad one), applies the density rule,
// resolves the slabs' and bins' defaults and fills k.radius and k.overlap from the packing.
// With lattice = "fcc": refuses a [packing] table. `origin` is the case file's path. Without
// `import_file`, the keys only (CaseParse::keys_only): no import, no slabs resolved.
void read_packing(const TomlReader& r, const toml::table& root, const toml::table& crystal, CrystalCase& k,
                  const std::string& origin, bool import_file = true);

// The slabs' and bins' keys of a periodic packing `pk` (in table `table`: "packing" or "random")
// with their defaults (source 2 largest diameters deep, top as deep, bins a mean diameter), their
// refusals, and what the law is linearised at (k.radius, k.overlap from pk's touching pairs, as
// check_packing found them: packing::Limits::touching); sets k.packing_file = p (p's other keys as
// the caller filled them).
void resolve_slabs(const TomlReader& r, const toml::table& t, const std::string& table, PackingKeys& p,
                   const packing::Packing& pk, const std::vector<packing::Touch>& touching, CrystalCase& k);

}  // namespace granwave::config
