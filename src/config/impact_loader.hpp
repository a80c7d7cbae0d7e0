// The impact case's tables for the case loader (config/impact_case.hpp, data/SCHEMA.md §7). Only
// config/case_loader.cpp includes this (it brings toml++).
#pragma once
#include <vector>

#include "config/case.hpp"
#include "config/toml_reader.hpp"

namespace granwave::config {

// [materials.NAME]: youngs_modulus, poisson_ratio, density (kg/m^3), source; the radius is the body's.
std::vector<Material> read_impact_materials(const TomlReader& r, const toml::table& root);
// [impact]: body1, and body2 or wall.
ImpactCase read_impact(const TomlReader& r, const toml::table& root, const std::vector<Material>& materials);
// The [contact] table as the crystal's reader takes it: the material constants of a Hertz law come
// from the bodies (refused in [contact], filled in from body1 for the law's own checks); the
// impact's own key `restitution` is taken out into c.impact.
toml::table impact_contact_table(const TomlReader& r, const toml::table& root, Case& c);

}  // namespace granwave::config
