// The slab plan of one crystal run over MPI ranks (crystal/slab.hpp): who owns which layers, the halo.
#include "crystal/slab.hpp"

#include <algorithm>
#include <cmath>
#include <sstream>

#include "core/error.hpp"
#include "crystal/packing.hpp"

namespace granwave::crystal {

SlabPlan plan_slab(const Packing& pk, double skin, std::shared_ptr<SlabComm> comm, const std::string& case_path) {
  SlabPlan s;
  s.comm = comm;
  s.rank = comm->rank();
  s.ranks = comm->ranks();
  const int nl = pk.layers, R = s.ranks;
  const std::string key = case_path + ": crystal.cells[2] = " + std::to_string(nl) + " layers";
  if (R > nl)
    throw InputError(key + " cannot be split over " + std::to_string(R) + " MPI ranks: each rank owns whole layers, so " +
                     "at most " + std::to_string(nl) + " ranks (run with mpirun -n " + std::to_string(nl) + " or fewer)");
  // Particles stored layer by layer (lattice_packing and every system file granwave writes).
  s.layer_start.assign(static_cast<std::size_t>(nl) + 1, 0);
  for (std::size_t p = 0; p < pk.size(); ++p) {
    if (pk.layer[p] < 0 || pk.layer[p] >= nl || (p > 0 && pk.layer[p] < pk.layer[p - 1]))
      throw InputError(case_path + ": the packing's particles are not stored layer by layer (particle " +
                       std::to_string(p) + "), which the split over MPI ranks needs");
    ++s.layer_start[static_cast<std::size_t>(pk.layer[p]) + 1];
  }
  for (int L = 0; L < nl; ++L) {
    if (s.layer_start[L + 1] == 0) throw InputError(key + ": layer " + std::to_string(L) + " has no particle");
    s.layer_start[L + 1] += s.layer_start[L];
  }
  // Layer heights and how far a particle may stray from its layer's.
  s.layer_z.assign(static_cast<std::size_t>(nl), 0.0);
  for (std::size_t p = 0; p < pk.size(); ++p) s.layer_z[pk.layer[p]] += pk.z[p];
  for (int L = 0; L < nl; ++L) s.layer_z[L] /= static_cast<double>(s.layer_start[L + 1] - s.layer_start[L]);
  double spread = 0.0, a_max = 0.0;
  for (std::size_t p = 0; p < pk.size(); ++p) {
    spread = std::max(spread, std::abs(pk.z[p] - s.layer_z[pk.layer[p]]));
    a_max = std::max(a_max, pk.radius[p]);
  }
  for (int L = 0; L + 1 < nl; ++L)
    if (!(s.layer_z[L + 1] > s.layer_z[L])) throw InputError(key + ": layer heights do not increase with the layer");
  // Halo depth h: particles h + 1 layers apart never become list candidates (z distance at least
  // a_i + a_j + skin) as long as each stays within z_tolerance of its layer's height. The
  // smallest h whose tolerance exceeds the packing's own spread; FCC: h = 1 (the next layer but
  // one is sqrt(2) d' away, the reach 1.05 d), tolerance 0.18 d.
  for (s.halo = 1; s.halo < nl; ++s.halo) {
    double gap = INFINITY;
    for (int L = 0; L + s.halo + 1 < nl; ++L) gap = std::min(gap, s.layer_z[L + s.halo + 1] - s.layer_z[L]);
    s.z_tolerance = 0.5 * (gap - 2.0 * a_max - skin);
    if (s.z_tolerance > spread) break;
  }
  const int most = nl / s.halo;
  if (R > most)
    throw InputError(key + " cannot be split over " + std::to_string(R) + " MPI ranks: contacts reach " +
                     std::to_string(s.halo) + " layers, which each rank must own, so at most " + std::to_string(most) +
                     " ranks");
  // The first nl mod R ranks take one layer more.
  s.first_layer.assign(static_cast<std::size_t>(R) + 1, 0);
  for (int r = 0; r < R; ++r) s.first_layer[r + 1] = s.first_layer[r] + nl / R + (r < nl % R ? 1 : 0);
  const int L0 = s.first_layer[s.rank], L1 = s.first_layer[s.rank + 1];
  s.own_lo = s.layer_start[L0];
  s.own_hi = s.layer_start[L1];
  s.held_lo = s.layer_start[std::max(0, L0 - s.halo)];
  s.held_hi = s.layer_start[std::min(nl, L1 + s.halo)];
  return s;
}

}  // namespace granwave::crystal
