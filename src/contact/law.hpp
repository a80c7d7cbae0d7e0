// What a contact law is to the crystal's kernel (src/crystal/kernel.hpp), in the pattern of
// HOOMD-blue's PotentialPair<Evaluator>: the kernel owns geometry, storage, blocking, threads and
// vectorisation; a law owns the physics of one contact. A law is a small copyable type with
//
//   struct History { double ...; };   per-contact state, doubles only (flags as 0.0/1.0), zero =
//                                     "no history" (a new or opened contact); an empty struct
//                                     for a law without history
//   static constexpr bool torques;    true when the law has tangential forces (then the kernel
//                                     gathers angular velocities and sums torques)
//   Response evaluate(const Contact&, History&) const;
//                                     force, n x f^t, dissipated energy of one touching contact,
//                                     history updated in place; inline and branch-free (selects,
//                                     no calls) so that the kernel's loop over contacts vectorises
//   double opening_loss(const History&) const;
//                                     energy lost when the contact opens with this history
//   template <class Energy> void add_stored_energy(Energy& e, double delta, const History&) const;
//                                     adds the contact's elastic energy to e, term by term, each
//                                     with e += t and as many for every contact (e: a double, or
//                                     the kernel's recorder of the terms, crystal/kernel.hpp)
//   LeverArm lever_arm() const;       lever arm of f^t: a_p - arm_shift(lever_arm()) delta
//                                     (contact/lever_arm.hpp: radius or contact_point)
//   bool dissipates() const;          false when loss is always zero (the kernel then skips it)
//   <Law> without_rates() const;      the same law for a jump of positions (no dashpots)
//
// and optionally, for a law whose stored energy depends on the radii (Hertz: R*), instead of the
// form above:
//   template <class Energy> void add_stored_energy(Energy& e, double delta, const History&, double a_i, double a_j) const;
//
// and optionally, with it, for a law whose history keeps what that energy needs from the radii
// and the overlap as its last evaluation made it (Hertz-Mindlin: the contact radius a):
//   template <class Energy> void add_evaluated_energy(Energy& e, double delta, const History&) const;
//                                     the same terms, bit for bit, when delta is the overlap that
//                                     evaluation stored (the kernel's list after any pass: its
//                                     samples take it, without the root and R*'s division)
//
// and optionally, for a law whose exact evaluation is expensive for a few contacts only (the
// roots and divisions of sliding):
//   Response evaluate(const Contact&, History&, Deferrable) const;
//                                     the cheap, vectorised evaluation; a contact it cannot
//                                     finish returns deferred = true and is evaluated again,
//                                     from the same history, by evaluate(Contact, History&) in a
//                                     scalar sweep (its vector results are discarded).
// and optionally, with it:
//   static constexpr bool lossless_sweep;
//                                     true when the Deferrable evaluation's loss is always 0 (no
//                                     dashpots: a sticking contact dissipates nothing); the
//                                     kernel's vector sweep then skips the dissipated-energy
//                                     bookkeeping and defers a contact that opens with a nonzero
//                                     opening_loss to the exact sweep (the same sums: x + 0 = x).
// and optionally, for a law with couples beyond the tangential force's torques (rolling and
// torsion resistance, contact/rolling_torsion.hpp):
//   static constexpr bool couples;    true: Response::couple is the torque on i beyond
//                                     -arm_i n x f^t (j gets minus it); the kernel then sums it
//                                     (a law without the member never has one: its instantiations
//                                     are those of a kernel without couples)
// and optionally, for a law that reads the reduced radius Contact::r_eff (Hertz: R*):
//   static constexpr bool reads_reduced_radius;
//                                     true: the kernel's gather takes R* for it (a law with
//                                     torques that does not declare it reads NaN there)
// Every contact writes only its own entries, so results do not depend on the sweep, the block
// or the thread that evaluates it.
#pragma once
#include <array>
#include <bit>
#include <concepts>
#include <cstddef>
#include <type_traits>

#include "contact/lever_arm.hpp"
#include "core/inline.hpp"
#include "contact/vec3.hpp"

namespace granwave::contact {

// R* = a_i a_j/(a_i + a_j), the reduced radius of two spheres (also lane-wise on the kernel's vectors).
template <class T>
GRANWAVE_ALWAYS_INLINE inline T reduced_radius(const T& a_i, const T& a_j) {
  return a_i * a_j / (a_i + a_j);
}

// One contact between spheres i and j as the kernel sees it (after the periodic image shift).
struct Contact {
  Vec3 n;            // unit normal (r_i - r_j)/|r_i - r_j|
  double delta;      // overlap a_i + a_j - |r_i - r_j| (> 0: touching)
  double delta_dot;  // d delta/dt = -n . (v_i - v_j) (> 0: approaching)
  Vec3 dv;           // v_i - v_j
  Vec3 w_i, w_j;     // angular velocities (zero unless the law has torques)
  double a_i, a_j;   // radii
  double r_eff;      // reduced_radius(a_i, a_j) (ReadsReducedRadius)
  double dt;         // time since the last evaluation (springs advance by v dt; 0 for a state set from outside)
};

// What a law returns for one touching contact.
struct Response {
  Vec3 force;             // on i; j gets -force
  Vec3 nf;                // n x f^t: the torque on sphere p is -arm_p nf, arm_p = a_p - arm_shift delta
  double loss = 0.0;      // energy dissipated over this step (J)
  bool deferred = false;  // Deferrable evaluation only: evaluate again in the exact sweep
  Vec3 couple{};          // a law with couples only: torque on i beyond -arm_i nf; j gets -couple
};

// Tag of the cheap, vectorised evaluation of a law that defers the rare expensive contacts.
struct Deferrable {};

template <class Law>
concept StoredEnergyOfRadii = requires(const Law& law, double& e, const typename Law::History& h) {
  law.add_stored_energy(e, 0.0, h, 0.0, 0.0);
};

template <class Law>
concept StoredEnergyOfEvaluation = requires(const Law& law, double& e, const typename Law::History& h) {
  law.add_evaluated_energy(e, 0.0, h);
};

template <class Law>
concept DefersContacts = requires(const Law& law, const Contact& c, typename Law::History& h) {
  { law.evaluate(c, h, Deferrable{}) } -> std::same_as<Response>;
};

// A law that reads Contact::r_eff: the kernel's gather takes it (a division off the head of the
// law's chain); for the other laws the gathered pass leaves it NaN.
template <class Law>
concept ReadsReducedRadius = requires { requires Law::reads_reduced_radius; };

template <class Law>
concept HasCouples = requires { requires Law::couples; };

template <class Law>
concept LosslessSweep = DefersContacts<Law> && requires { requires Law::lossless_sweep; };

// Number of double columns a law's history takes in the flat per-contact storage.
template <class History>
inline constexpr std::size_t history_columns = std::is_empty_v<History> ? 0 : sizeof(History) / sizeof(double);

template <class History>
concept FlatHistory = std::is_trivially_copyable_v<History> && std::is_default_constructible_v<History> &&
                      (std::is_empty_v<History> || sizeof(History) % sizeof(double) == 0);

// History <-> its columns, as plain doubles (the kernel stores each column as a flat array).
template <class History>
History history_from(const std::array<double, history_columns<History>>& a) {
  if constexpr (history_columns<History> == 0)
    return History{};
  else
    return std::bit_cast<History>(a);
}
template <class History>
std::array<double, history_columns<History>> history_to(const History& h) {
  if constexpr (history_columns<History> == 0)
    return {};
  else
    return std::bit_cast<std::array<double, history_columns<History>>>(h);
}

}  // namespace granwave::contact
