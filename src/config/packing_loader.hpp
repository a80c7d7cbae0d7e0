// A crystal's [packing] table (lattice = "file", data/SCHEMA.md §1) for the case loader: its keys,
// the import of the file they name, and the defaults that need the packing. Only
// config/case_loader.cpp includes this (it brings toml++).
#pragma once
#include "config/case.hpp"
#include "config/toml_reader.hpp"

namespace granwave::config {

// With lattice = "file": refuses the lattice's own [crystal] keys, reads [packing], imports the file
// (src/packing: exit 2 naming file, line and particle for a bad one), applies the density rule,
// resolves the slabs' and bins' defaults and fills k.radius and k.overlap from the packing.
// With lattice = "fcc": refuses a [packing] table. `origin` is the case file's path.
void read_packing(const TomlReader& r, const toml::table& root, const toml::table& crystal, CrystalCase& k,
                  const std::string& origin);

}  // namespace granwave::config
