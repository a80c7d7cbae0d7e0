// The relaxed (non-affine) moduli and the effective-medium affine estimate of a crystal case's
// packing for `granwave theory` (issue 39): the packing's network relaxed as a slab (its fixed
// layers moved affinely) and as a triply periodic bulk (the network closed across z), and the
// Walton / linear-spring affine estimate at the packing's own Z, phi and p.
#pragma once
#include <string>

#include "config/case.hpp"
#include "core/json.hpp"
#include "crystal/packing.hpp"
#include "theory/crystal_theory.hpp"
#include "theory/effective_medium.hpp"
#include "theory/relaxed_moduli.hpp"

namespace granwave::cli {

struct RelaxedPart {
  theory::RelaxedModuli slab, bulk;
  bool bulk_available = false;
  std::string bulk_note;
  // Effective medium (affine estimate) at the bulk's (else the slab's) non-rattler Z, phi = rho/density, p.
  std::string medium_model;  // "walton_hertz_mindlin" or "linear_springs"
  theory::EffectiveMedium medium;
  double Z = 0.0, phi = 0.0, p = 0.0;
};

RelaxedPart relaxed_part(const config::Case& c, const crystal::Packing& pk, const theory::ContactNetwork& net);
// Adds "relaxed" and "effective_medium" to the theory verb's JSON object.
void add_relaxed_json(Json& o, const RelaxedPart& r);
void print_relaxed(const RelaxedPart& r);

}  // namespace granwave::cli
