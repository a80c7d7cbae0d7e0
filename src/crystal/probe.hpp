// The static probe (issue 39 item 2): the simulation itself strains a packing by a small homogeneous
// strain, relaxes its free particles under the case's full law (FIRE on translations and rotations,
// tangential springs stretched by the motion) and measures the change of the mean stress, to be
// compared with the relaxed slab tensor A_relaxed of theory/relaxed_moduli.hpp.
//
// Strains (eps_gf = dU_f/dx_g, U = eps^T x; "zx" is gradient z, displacement x):
//   zz, zx   the source and top slabs moved affinely relative to each other (the free particles start
//            from the affine field too)
//   xx, yy   the periodic box and every position stretched along x (y)
//   yx       the box sheared: the +y images shifted by e box_y in x (Dynamics::ImageMotion), every
//            position by e y
// Every strain starts from the relaxed state with its springs and is made as velocities over one force
// evaluation, the periodic images moving with the box's rates (ImageMotion), so every sticking
// contact's tangential spring stretches by its affine relative displacement, across the box's faces
// too, as it would in a run. Box strains compare with the slab tensor as zz and zx do: the source
// and top slabs move with the box (affinely), the rest relaxes.
// Measured: the nominal (first Piola-Kirchhoff) stress P_ab = (1/V) sum_c w_c B_a f_b, B the contact's
// branch (i to j) in the unstrained state, f the force on j, V and w_c the theory slab's volume and
// weights. dP/d eps_gf = A_abgf exactly (A the tensor with the initial-stress term), so the probe
// reports (P(+e) - P(-e)) / (2 e) (the central difference: the unstrained state's own residual and
// the O(e^2) terms cancel). The Cauchy stress's change is reported beside it:
// d sigma_af = dP_af + eps_ga P_gf - tr(eps) P_af.
#pragma once
#include <memory>
#include <string>
#include <vector>

#include "config/case.hpp"
#include "crystal/dynamics.hpp"
#include "crystal/packing.hpp"
#include "theory/crystal_theory.hpp"

namespace granwave::crystal {

enum class ProbeStrain { zz, zx, xx, yy, yx };
const char* probe_strain_name(ProbeStrain s);
// "zz", "zx", "xx", "yy", "yx"; InputError naming what is allowed otherwise.
ProbeStrain parse_probe_strain(const std::string& s);
// The (gradient, displacement) directions of the strain.
std::pair<int, int> probe_strain_indices(ProbeStrain s);

struct ProbeOptions {
  // e: at 1e-6 one contact of the LAMMPS packing with friction (f0 ~ 1e-4 of the mean) reaches the
  // Coulomb limit and one opens; at 1e-7 none (docs/validation.md)
  double amplitude = 1e-7;
  // Converged when every free particle's force (and torque / radius) is below tolerance times the
  // strain's force scale e <k_n> <l> (the mean contact stiffness and branch length)
  double tolerance = 1e-6;
  long max_steps = 5000000;  // FIRE steps per relaxation
};

struct ProbeResult {
  ProbeStrain strain = ProbeStrain::zz;
  Eigen::Matrix3d dP = Eigen::Matrix3d::Zero();      // dP_ab / de (Pa): A_ab(strain) if linear theory holds
  Eigen::Matrix3d dsigma = Eigen::Matrix3d::Zero();  // d sigma_ab / de (Cauchy, tension positive), measured
  long steps_plus = 0, steps_minus = 0;              // FIRE steps of the two relaxations
  double residual = 0.0;          // the largest force at the stop / the force scale (both signs)
  double max_slip = 0.0;          // max |f_t| / (mu |f_n|) over touching contacts after relaxing (0: no friction)
  int sliding = 0;                // contacts at the Coulomb limit after relaxing (the larger of +-e)
  int contacts_changed = 0;       // touching contacts gained or lost against the unstrained state (the larger of +-e)
};

class StaticProbe {
 public:
  // `volume` and the weights: the theory slab's (relaxed_moduli.hpp). Relaxes the unstrained state
  // first (under the full law, from the packing as built).
  StaticProbe(const config::Case& c, const Packing& pk, const theory::ContactNetwork& net, double volume,
              const ProbeOptions& opt);
  ProbeResult run(ProbeStrain s) const;
  long base_steps = 0;
  double base_residual = 0.0;         // largest force / force scale of the relaxed unstrained state
  double force_scale = 0.0;           // e <k_n> <l> (N)
  Eigen::Matrix3d P0 = Eigen::Matrix3d::Zero();  // the unstrained state's stress (Pa, tension positive)
  bool tangential = false;            // the law has tangential forces (torques)

 private:
  struct Strained;
  Strained strained(ProbeStrain s, double e) const;
  Packing pk_;
  ProbeOptions opt_;
  std::shared_ptr<const ContactModel> model_;
  double volume_ = 0.0, t_c_ = 0.0, mu_ = 0.0;
  std::unique_ptr<Dynamics> base_, pairs_;  // relaxed state; every particle mobile (prescribed pairs)
};

}  // namespace granwave::crystal
