// A prepared periodic packing saved between the stages of a compression path (docs/random-packing.md,
// "A compression path"): the box, every particle's centre, radius and mass to the last bit, and what
// the stage's preparation reached, so that an interrupted study resumes from the last saved pressure.
#pragma once
#include <cstdint>
#include <optional>
#include <string>

#include "packing/packing.hpp"
#include "packing/random_packing.hpp"

namespace granwave::io {
class H5Writer;
}

namespace granwave::packing {

struct PreparedState {
  Packing packing;           // triply periodic, centres wrapped into the box
  Preparation preparation;   // the stage's record (springs: in the system file's group only; the path is frictionless)
  double pressure_target = 0.0;  // Pa
  double seconds = 0.0;      // wall time of the stage
  // The system file's group only: the case keys it was prepared with, checked when it is taken.
  std::uint64_t seed = 0;
  double friction = 0.0;     // random.friction (its springs are then in preparation.springs)
};

// Written to PATH.tmp and renamed when complete. Throws RunError when it cannot be written.
void save_prepared(const std::string& path, const PreparedState& state);
// Throws InputError naming the file and line on a damaged or foreign file.
PreparedState load_prepared(const std::string& path);

// The same state as the group /prepared of a random packing's system file (`granwave build`,
// data/SCHEMA.md §2), springs included, so that `granwave run CASE --system FILE` takes it instead
// of preparing the packing again. Written into an open writer (io/h5.hpp).
void write_prepared_group(io::H5Writer& w, const PreparedState& state);
// nullopt when the file has no /prepared (a lattice's system, or an older file); a damaged group is
// refused (InputError naming the file, the dataset or attribute and what is allowed).
std::optional<PreparedState> read_prepared_group(const std::string& path);
// read_prepared_group of a run's system file; nullopt for none ("") or a missing file (the run refuses that).
std::optional<PreparedState> prepared_of_system(const std::string& system_path);

}  // namespace granwave::packing
