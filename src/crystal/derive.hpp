// The numbers derived from a crystal case before a run: the contact linearised at the static
// overlap, the time step and its limit, the prestress, eq. (10)'s speeds; the theory's network.
#pragma once
#include <string>

#include "config/case.hpp"
#include "contact/case_law.hpp"
#include "crystal/packing.hpp"
#include "theory/crystal_theory.hpp"
#include "theory/lattice_dynamics.hpp"

namespace granwave::crystal {

// Derived numbers of a case (crystal check prints them; run uses dt and the limits).
struct Derived {
  double mass = 0.0, m_ij = 0.0;        // mean particle mass, reduced mass of a contact
  double omega = 0.0, t_c = 0.0;        // eq. (1) text: omega = sqrt(k/m_ij - eta_0^2), t_c = pi/omega
  double restitution = 1.0;             // exp(-eta_0 t_c) ("allow")
  double dt = 0.0;                      // resolved time step
  double dt_stable = 0.0;               // velocity-Verlet limit (conservative estimate)
  double sigma_0 = 0.0;                 // isotropic prestress 2 sqrt(2) k delta / d'^2 (monodisperse);
                                        // "file": the initial network's Love-Weber sigma_zz
  double v_p = 0.0, v_s = 0.0;          // long-wave speeds along z from eq. (10) with branch d';
                                        // "file": eq. (10) affine over the packing's contact network
  int max_coordination = 12;            // the stability bound's z (FCC: 12; "file": the network's largest)
  // The contact as eq. (10) and the guards see it: linear law, the keys kn, kt, gamma_n and
  // f0 = k delta; hertz_mindlin, linearised at the static overlap delta_0 = overlap d:
  // k_n = 2 E* sqrt(R* delta_0), k_t = 8 G* sqrt(R* delta_0) (0 with tangential = "none"),
  // gamma_n = 2 beta sqrt(m* k_n), f0 = (4/3) E* sqrt(R*) delta_0^(3/2).
  double kn = 0.0, kt = 0.0, gamma_n = 0.0, f0 = 0.0;
  double delta_max = 0.0;               // the overlap bound of the guards (initial + the source's)
  long steps = 0, sample_every = 1;     // time steps, steps between samples
};
// Throws InputError for refused cases (stability, geometry, contact parameters). A run derives its
// case once (crystal::run: in the guards, then handed on); derivations() counts the calls in this
// process, for the test that says so.
Derived derive(const config::Case& c);
long derivations();

// The case's contact between two particles of the mean radius at overlap delta: normal force,
// tangent stiffnesses, normal damping (linear law: kn delta, kn, kt, gamma_n at any delta).
using ContactAt = contact::LinearisedContact;  // f_n, kn, kt, gamma_n, gamma_t
// The overlap a packing's law is linearised at: the lattice's delta_0, or for a file's packing (no lattice
// overlap) the contacts' mean overlap, 2 crystal.radius crystal.overlap, as derive takes it.
double linearisation_overlap(const config::Case& c, const Packing& pk);
ContactAt contact_at(const config::Case& c, double delta);
// The same for a contact of radii a_i, a_j (Hertz: R* = a_i a_j/(a_i + a_j), m* of the two masses).
ContactAt contact_between(const config::Case& c, double a_i, double a_j, double delta);
// The packing's contact network for the theory (theory/crystal_theory.hpp): particles, contacts
// with their static normal forces (the prestress), the law's stiffnesses (linear: the keys; Hertz-
// Mindlin: each contact's own, linearised at its overlap; the network's k, kt at delta_0).
theory::ContactNetwork contact_network(const config::Case& c, const Packing& packing);
// The lattice dynamics' options of the case's law (theory/lattice_dynamics.hpp): its lever arm and
// its rolling and torsion springs; bonds must agree to `tolerance`.
theory::LatticeCellOptions lattice_options(const config::Case& c, double tolerance);
// The static normal force of a contact of radii a_i, a_j at overlap delta (theory's prestress).
double static_normal_force(const config::Case& c, double a_i, double a_j, double delta);
// The trace's name of the law and of its tangential history (root attributes contact_law,
// tangential_history; the linear law's spring is a displacement history).
std::string contact_law_name(const contact::LawParams& contact);
std::string tangential_history_name(const contact::LawParams& contact);

}  // namespace granwave::crystal
