// A sphere packing: particles and the box that holds them, and the z-bins the per-layer measures sum
// over. Generators (the FCC crystal today, a prepared random packing later) and the importers of
// other codes' files (importers.hpp) fill the same type; check_packing (checks.hpp) judges it.
#pragma once
#include <array>
#include <cstddef>
#include <cstdint>
#include <limits>
#include <optional>
#include <string>
#include <vector>

#include "contact/vec3.hpp"

namespace granwave::packing {

using contact::Vec3;

// What a particle does in a run: moves freely, is driven (the source), or is held still.
enum class Role { free, source, fixed };

struct Particle {
  std::int64_t id = 0;  // the file's atom id, or 1-based order where the format has none
  int type = 1;         // the file's atom type (1 where the format has none): roles may follow it
  Vec3 centre;          // m
  double radius = 0.0;  // m
  // As the file gives them (NaN where it gives none): the case's materials fill the rest, by the
  // rule of docs/packing-import.md.
  double mass = std::numeric_limits<double>::quiet_NaN();     // kg
  double density = std::numeric_limits<double>::quiet_NaN();  // kg/m^3
  Role role = Role::free;
  std::optional<Vec3> velocity;  // m/s, where the file gives one
  std::size_t line = 0;          // line of the file it was read from (0: made by a generator)
};

// An axis-aligned box. x and y must be periodic (lateral walls are refused); z is periodic or held
// between flat walls at lo[2] and hi[2].
struct Box {
  std::array<double, 3> lo{0.0, 0.0, 0.0}, hi{0.0, 0.0, 0.0};
  std::array<bool, 3> periodic{true, true, true};
  double length(int axis) const { return hi[axis] - lo[axis]; }
  double volume() const { return length(0) * length(1) * length(2); }
  bool z_walls() const { return !periodic[2]; }
};

// Bins of equal width h along z from `origin`; a particle's bin is fixed by its initial centre.
// The FCC crystal's bins are its layers (origin half a layer below the first, h = l0).
struct ZBins {
  double origin = 0.0;
  double h = 0.0;
  int bin_of(double z) const;  // floor((z - origin) / h)
};

struct Packing {
  Box box;
  std::vector<Particle> particles;
  std::string source;  // the file it was read from, or the generator's name: errors name it
  ZBins bins;
  std::vector<int> bin;  // per particle, set by assign_bins
};

// Maps v into [lo, hi) along every periodic axis of the box (a periodic image is the same particle).
Vec3 wrap(const Box& box, Vec3 v);

// Sets packing.bins and each particle's bin from its current centre (call once, before any motion).
void assign_bins(Packing& packing, double origin, double h);

// Parses a LAMMPS-style boundary word list, "p p f": p periodic, f/s/m not periodic.
std::array<bool, 3> parse_boundary(const std::string& text, const std::string& what);

}  // namespace granwave::packing
