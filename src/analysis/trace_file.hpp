// Reading a trace file (data/SCHEMA.md §3) of any code -- granwave, YADE, LIGGGHTS, LAMMPS -- into
// memory: the crystal's layer series or the chain's contact forces, with what the root attributes
// and the case text say (excitation mode, the case's [analysis] readings). Nothing is measured here.
// Which /crystal datasets a trace may hold, and their shapes, is the crystal's table of observables
// (crystal/observables.hpp), which the caller hands over: a new observable is read as it is written.
#pragma once
#include <algorithm>
#include <cstddef>
#include <limits>
#include <map>
#include <optional>
#include <string>
#include <utility>
#include <vector>

#include "analysis/measures.hpp"
#include "core/numbers.hpp"

namespace granwave::io {
class H5Reader;
}
namespace granwave::crystal {
struct Observable;
}

namespace granwave::analysis {


// A packing's free bins from its particles' roles (data/SCHEMA.md §2: 0 free, 1 source, 2 held at the
// top) and bins: {after the last bin holding a source particle, before the first holding a top one}. The
// trace reader (/system/role, /system/layer) and a run measured in memory (crystal::analysis_trace) both.
template <class Roles, class Bins>
std::pair<int, int> packing_free_bins(const Roles& role, const Bins& layer, std::size_t nlayers) {
  long long last_source = -1, first_top = static_cast<long long>(nlayers);
  for (std::size_t q = 0; q < role.size(); ++q) {
    if (role[q] == 1) last_source = std::max<long long>(last_source, layer[q]);
    if (role[q] == 2) first_top = std::min<long long>(first_top, layer[q]);
  }
  return {static_cast<int>(last_source + 1), static_cast<int>(first_top - 1)};
}

// A crystal trace's description: everything but its series (what a derived trace, e.g. a smoothed
// one, copies from the trace it is made of).
struct CrystalTraceHeader {
  std::vector<double> time;      // [nt] s
  std::vector<double> layer_z;   // [nlayers] m, from the innermost driven layer
  std::size_t nt = 0, nlayers = 0;
  double l0 = 0.0;               // layer spacing (m): /system attr l0, else from layer_z
  int fixed_layers = 0;          // at each end (a packing's: the source bins)
  bool packing_bins = false;     // z-bins of a packing that is not the FCC (/system attribute generator)
  // A packing's free bins by role (/system/role, /system/layer): after the last bin holding a source particle,
  // before the first holding a top one (the bins the crosscheck judges); -1 without roles.
  int first_free_bin = -1, last_free_bin = -1;
  char mode = 'P';               // 'P' or 'S' (from case_toml, else from the field amplitudes)
  std::string mode_source;       // "case_toml" | "inferred"
  // The case's `[analysis] period` (data/SCHEMA.md §1), when its text is in the trace and sets it.
  std::optional<PeriodReading> period;
  // The case's `[analysis] wavenumber_speed`, likewise.
  std::optional<WavenumberSpeed> wavenumber_speed;
};

struct CrystalTrace : CrystalTraceHeader {
  // Row-major [nt, nlayers]; empty when the trace lacks the dataset.
  std::vector<double> stress_zz, stress_zx, displacement_z, displacement_x, velocity_z, velocity_x;
  std::vector<double> coordination;
  // The table's other /crystal series (none of the above: e.g. the test-only one), by dataset name.
  std::map<std::string, std::vector<double>> other;
  // Where the series of /crystal dataset `name` is held: the member above of that name, else other[name].
  std::vector<double>& series(const std::string& name);
};

struct ChainTrace {
  std::vector<double> time;
  std::size_t nt = 0, ncontacts = 0;
  std::vector<double> contact_force;     // [nt, ncontacts]
  std::vector<double> contact_position;  // [ncontacts] m along the chain (NaN if no system)
};

struct TraceFile {
  std::string path, code, code_version, case_name, time_convention;
  std::string case_toml;  // the case's text (root attribute), empty when the trace has none
  std::string model;  // "crystal" | "chain"
  CrystalTrace crystal;
  ChainTrace chain;
};
// `observables`: the table (crystal::observables()); its /crystal entries are read where present, each
// checked for its shape and finite values. A chain's trace needs none (no_observables()). Throws InputError.
TraceFile read_trace(const std::string& path, const std::vector<crystal::Observable>& observables);
const std::vector<crystal::Observable>& no_observables();  // an empty table, for a reader of chains
// The same, of an open file (or an image in memory).
TraceFile read_trace(const io::H5Reader& r, const std::vector<crystal::Observable>& observables);

}  // namespace granwave::analysis
