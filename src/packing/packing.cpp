// The packing's small operations: periodic wrapping, z-bins, boundary flags.
#include "packing/packing.hpp"

#include <cmath>
#include <sstream>

#include "core/error.hpp"

namespace granwave::packing {

int ZBins::bin_of(double z) const { return static_cast<int>(std::floor((z - origin) / h)); }

Vec3 wrap(const Box& box, Vec3 v) {
  double* c[3] = {&v.vx, &v.vy, &v.vz};
  for (int a = 0; a < 3; ++a) {
    if (!box.periodic[a]) continue;
    const double L = box.length(a);
    double r = std::fmod(*c[a] - box.lo[a], L);  // exact, whatever the distance
    if (r < 0.0) r += L;
    double x = box.lo[a] + r;
    if (!(x < box.hi[a])) x = box.lo[a];  // rounding of a point just below the period
    *c[a] = x;
  }
  return v;
}

void assign_bins(Packing& packing, double origin, double h) {
  if (!(h > 0.0) || !std::isfinite(origin))
    throw InputError(packing.source + ": z-bins need a finite origin and a width h > 0 (got origin " +
                     std::to_string(origin) + ", h " + std::to_string(h) + ")");
  packing.bins = {origin, h};
  packing.bin.resize(packing.particles.size());
  for (std::size_t i = 0; i < packing.particles.size(); ++i)
    packing.bin[i] = packing.bins.bin_of(packing.particles[i].centre.z());
}

std::array<bool, 3> parse_boundary(const std::string& text, const std::string& what) {
  std::istringstream in(text);
  std::array<bool, 3> periodic{};
  std::string word;
  int n = 0;
  while (in >> word) {
    if (n == 3 || word.empty() || word.size() > 2) n = 4;
    if (n < 3) {
      for (char c : word)
        if (c != 'p' && c != 'f' && c != 's' && c != 'm') n = 4;
      // LAMMPS writes one letter per axis ("p") or one per face ("pp", "fs"): periodic needs both.
      if (n < 3 && word.find('p') != std::string::npos && word != "p" && word != "pp") n = 4;
      if (n < 3) periodic[n] = word[0] == 'p';
    }
    ++n;
  }
  if (n != 3)
    throw InputError(what + ": boundary \"" + text +
                     "\" is not three LAMMPS boundary words (allowed per axis: p, f, s, m, or two of them as in "
                     "\"pp ff\"; periodic is p or pp)");
  return periodic;
}

}  // namespace granwave::packing
