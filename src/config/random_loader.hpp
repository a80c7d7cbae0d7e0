// A crystal's [random] table (lattice = "random", data/SCHEMA.md §1) for the case loader: its keys,
// their refusals before anything is compressed, and the preparation of the packing (packing/
// random_packing.hpp) that the run then takes as a periodic packing from a file. Only
// config/case_loader.cpp includes this (it brings toml++).
#pragma once
#include "config/case.hpp"
#include "config/toml_reader.hpp"

namespace granwave::config {

// With lattice = "random" (call after [contact] and [integrator] are read): refuses the lattice's
// own [crystal] keys, reads [random], refuses what cannot be prepared (exit 2 naming the key),
// prepares the packing (a progress line on stderr while it compresses) and fills c.crystal's
// imported, packing_file (format "random"), random, preparation, radius and overlap.
// With another lattice: refuses a [random] table. Without `prepare`, the keys and the refusals that
// need no file only (CaseParse::keys_only): no saved start opened, nothing compressed. With
// `prepared` (a system file's /prepared, load_case): its packing instead of a preparation.
void read_random(const TomlReader& r, const toml::table& root, Case& c, bool prepare = true,
                 const packing::PreparedState* prepared = nullptr);

}  // namespace granwave::config
