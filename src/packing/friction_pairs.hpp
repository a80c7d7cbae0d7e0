// The tangential side of a frictional compression (packing/compression.cpp, preparation_friction > 0):
// per Verlet pair its spring xi (the history, carried across rebuilds by the pair (i, j)), each step
// advanced and Coulomb-limited by the crystal's own tangential objects (contact/tangential_spring.hpp:
// the spring rotated with the contact frame, eq. (2), advanced by v_t dt, eq. (6), stick or slide,
// eqs. (5), (7), (8)); the pair's forces on i and the torque lever n x f_t stored for the gather.
#pragma once
#include <cstdint>
#include <vector>

#include "contact/normal_form.hpp"
#include "contact/tangential_spring.hpp"
#include "contact/vec3.hpp"
#include "packing/random_packing.hpp"
#include "packing/verlet_pairs.hpp"

namespace granwave::packing {

struct FrictionPairs {
  // Per pair: the spring (3), and once evaluated the forces on i (elastic, total), n x f_t (elastic,
  // total): 12 numbers; sliding 1 when the pair is at the Coulomb limit.
  std::vector<double> xi, out;
  std::vector<std::uint8_t> sliding;

  void resize(std::size_t pairs) {
    xi.assign(3 * pairs, 0.0);
    out.assign(12 * pairs, 0.0);
    sliding.assign(pairs, 0);
  }

  // After the list was rebuilt from `old` (both sorted by (i, j)): each pair still listed keeps its spring.
  void carry(const std::vector<std::uint32_t>& old_i, const std::vector<std::uint32_t>& old_j,
             const VerletPairs& now) {
    const std::vector<double> old_xi = xi;
    resize(now.i.size());
    std::size_t o = 0;
    for (std::size_t c = 0; c < now.i.size(); ++c) {
      while (o < old_i.size() && (old_i[o] < now.i[c] || (old_i[o] == now.i[c] && old_j[o] < now.j[c]))) ++o;
      if (o < old_i.size() && old_i[o] == now.i[c] && old_j[o] == now.j[c])
        for (int d = 0; d < 3; ++d) xi[3 * c + d] = old_xi[3 * o + d];
    }
  }

  // Pair c apart: its spring forgotten (a new contact starts unstretched).
  void apart(std::size_t c) {
    for (int d = 0; d < 3; ++d) xi[3 * c + d] = 0.0;
    sliding[c] = 0;
  }

  // Pair c touching: n from i to j, f_n the elastic normal force, k_t the tangential stiffness, gamma_t
  // its dashpot, v_ij the relative velocity of i's contact point against j's (rotations included).
  // Returns the spring's energy, k_t |xi|^2 / 2.
  double touch(std::size_t c, const contact::Vec3& n, double f_n, double kt, double gamma_t, double mu,
               const contact::Vec3& v_ij, double dt) {
    using contact::Vec3;
    const contact::TangentialSpringParams tp{kt, gamma_t, mu, mu, false};
    const Vec3 vt = contact::tangential_velocity(v_ij, n);
    const Vec3 prev{xi[3 * c], xi[3 * c + 1], xi[3 * c + 2]};
    const Vec3 spring = contact::advance_spring(tp, prev, n, vt, dt);
    const contact::TangentialResult r = contact::tangential_force<true>(tp, spring, vt, f_n, false);
    xi[3 * c] = r.spring.vx, xi[3 * c + 1] = r.spring.vy, xi[3 * c + 2] = r.spring.vz;
    sliding[c] = r.sliding ? 1 : 0;
    const Vec3 f_el = r.spring * (-kt);  // the spring's force on i (the static part)
    const Vec3 g_el = n.cross(f_el), g_tot = n.cross(r.force);
    double* o = &out[12 * c];
    const double vals[12] = {f_el.vx, f_el.vy, f_el.vz, r.force.vx, r.force.vy, r.force.vz,
                             g_el.vx, g_el.vy, g_el.vz, g_tot.vx, g_tot.vy, g_tot.vz};
    for (int k = 0; k < 12; ++k) o[k] = vals[k];
    return 0.5 * kt * r.spring.squaredNorm();
  }
};

}  // namespace granwave::packing
