// What theory/relaxed_moduli.hpp needs of a crystal case beyond its contact network (issue 39): the
// relaxed slab's options, and for a packing from a file its bulk state - the imported packing,
// triply periodic as the file gives it (before crystal/file_packing.cpp cuts it open in z), relaxed
// under the case's normal law (frictionless, no tangential history, every particle free, the box
// fixed) by FIRE, with its contact network.
#pragma once
#include "config/case.hpp"
#include "crystal/packing.hpp"
#include "theory/crystal_theory.hpp"
#include "theory/relaxed_moduli.hpp"

namespace granwave::crystal {

// The relaxed slab of the case (`granwave theory`'s and `granwave probe`'s): the FCC's fixed layers,
// or a file's source and top slabs (by role; every contact weighted 1; V = box_x box_y times the
// file's z length, so the contacts the cut across z removed are missing from it: data/SCHEMA.md).
theory::RelaxedOptions relaxed_slab_options(const config::Case& c, const Packing& pk);

struct PeriodicBulk {
  theory::ContactNetwork net;  // every contact the case's law at its own overlap (k, kt, f0 per contact)
  double box_z = 0.0;          // the file's z period (m)
  long steps = 0;              // FIRE steps
  double unbalanced = 0.0;     // largest net force on a particle / mean contact force at the stop
};

// Throws InputError when the file's packing is not periodic in z, RunError when FIRE does not bring
// the largest net force below tolerance times the mean contact force within max_steps.
PeriodicBulk periodic_bulk(const config::Case& c, double tolerance = 1e-10, long max_steps = 2000000);

}  // namespace granwave::crystal
