// Closed forms of the impact of two spheres, or of a sphere on a flat wall (Chung & Ooi 2011;
// docs/research/contact_models_sources.md A.1, A.3): Hertz's normal impact, the restitution of a
// damping law, and the oblique impact of rigid bodies with Coulomb friction.
#pragma once
#include <limits>

#include "theory/hertz.hpp"

namespace granwave::theory {

inline constexpr double kInfinite = std::numeric_limits<double>::infinity();

// 1/E* = (1 - nu1^2)/E1 + (1 - nu2^2)/E2; E2 = infinity: a rigid second body.
double effective_modulus(double E1, double nu1, double E2, double nu2);
// 1/G* = (2 - nu1)/G1 + (2 - nu2)/G2, G = E/(2(1 + nu)) (Mindlin's no-slip stiffness 8 G* a).
double effective_shear_modulus(double E1, double nu1, double E2, double nu2);

// Two bodies as the closed forms see them; a wall: m2, I2, R2 infinite.
struct ImpactBodies {
  double m1 = 0.0, R1 = 0.0, I1 = 0.0;
  double m2 = kInfinite, R2 = kInfinite, I2 = kInfinite;
  double r_eff() const;  // R* (R1 for a wall)
  double m_eff() const;  // m* (m1 for a wall)
  // Tangential compliance of the contact point: 1/m1 + 1/m2 + R1^2/I1 + R2^2/I2 (7/(2 m) for a
  // solid sphere on a wall).
  double tangential_compliance() const;
};

// Hertz's elastic normal impact at approach speed v (theory::hertz_impact with A = (4/3) E* sqrt(R*)),
// the contact time (4/5) B(2/5, 1/2) delta_max/v = 2.943 delta_max/v to double precision.
HertzImpact hertz_normal_impact(const ImpactBodies& b, double e_star, double v);

// The damping that makes a law realise the normal restitution e (in (0, 1]):
// Hertz-Mindlin's damping_ratio beta (the inverse of damped_hertz_impact: secant iterations
// from the LIGGGHTS/LAMMPS mapping below, to 1e-11 in e), and the linear law's gamma_n for
// stiffness k and reduced mass m (the inverse of linear_contact_time).
double hertz_damping_ratio_for(double e, bool clip_tension);
double linear_damping_for(double e, double k, double m_eff, bool clip_tension);
// The beta of the mapping LIGGGHTS (coefficientRestitution) and LAMMPS (coeff_restitution) use for
// Hertz: ln e / sqrt(ln^2 e + pi^2) = -beta sqrt(6/5) (docs/design.md §2.5.1). It is the linear
// oscillator's mapping: with Hertz's stiffness the realised restitution differs (damped_hertz_impact).
double mapped_damping_ratio(double e);

// Oblique impact of rigid bodies with Coulomb friction mu and normal restitution e (impulse
// theory). Tangential values are components along t, the direction of the incident tangential
// velocity of the contact point (of body 1 relative to body 2); spins about s = n x t (n from body
// 2 to body 1), positive in the rolling sense, so that v_ct = v_t - R1 w1_s - R2 w2_s.
struct ObliqueIncidence {
  double vn = 0.0;   // approach speed (> 0)
  double vt = 0.0;   // relative centre velocity along t
  double w1 = 0.0;   // body 1's spin about s
  double w2 = 0.0;   // body 2's spin about s (0 for a wall)
};
struct ObliqueImpact {
  bool sliding = false;      // gross sliding throughout (else the contact point ends at rest: rigid stick)
  double boundary = 0.0;     // v_ct/v_n at the regime boundary: mu (1 + e) m* K_t (3.5 mu (1 + e) on a wall)
  double vn_after = 0.0;     // separation speed e v_n
  double vt_after = 0.0;     // relative centre velocity along t
  double vct_after = 0.0;    // contact point's
  double w1_after = 0.0, w2_after = 0.0;  // spins about s
  double tangential_restitution = 0.0;    // vt_after/vt (centre; Chung & Ooi T4's e_t)
  double contact_point_restitution = 0.0; // -vct_after/vct (Walton's beta)
  double rebound_angle = 0.0;             // atan(vct_after/vn_after) (rad), the contact point's
  double rebound_angle_centre = 0.0;      // atan(vt_after/vn_after) (rad)
};
ObliqueImpact coulomb_oblique(const ImpactBodies& b, const ObliqueIncidence& in, double mu, double e);

// Maw, Barber & Fawcett's normalisation for a solid sphere of Poisson ratio nu: chi =
// (1 - nu)/(2 - nu) (1 + R^2/k^2) = 3.5 (1 - nu)/(2 - nu), psi1 = 2 (1 - nu)/((2 - nu) mu) v_ct/v_n.
// The rigid-body sliding boundary is psi1 = 2 chi (1 + e).
double mbf_chi(double nu);
double mbf_psi(double nu, double mu, double vct_over_vn);

}  // namespace granwave::theory

namespace granwave::theory {

// Oblique impact with Mindlin's tangential compliance (Maw, Barber & Fawcett, Wear 38 (1976); Johnson,
// Contact Mechanics (1985) ch. 7, Mindlin-Deresiewicz, and ch. 11, oblique impact; derivation:
// data/impact/README.md, "Maw, Barber & Fawcett"). Hertz normal contact (k_n = 2 E* a), Mindlin's no-slip tangential stiffness
// k_t = 8 G* a, Coulomb friction mu. In MBF's variables
//   kappa = k_t/k_n = 4 G*/E*                  (2 (1 - nu)/(2 - nu) for like materials or a rigid wall),
//   chi   = (kappa/2) m* K_t                   (K_t: ImpactBodies::tangential_compliance;
//                                               a solid sphere: m* K_t = 1 + m R^2/I = 7/2),
//   psi   = kappa v_ct/(mu v_n)                (v_n: the incident normal speed, before and after),
// the rebound psi2(psi1) depends on chi (and the normal damping) alone. Elastic normal history:
// gross sliding throughout iff psi1 >= 4 chi - 1 (2 chi (1 + e) - e with restitution e, where the
// tangential cap follows the normal force), and there psi2 = psi1 - 2 chi (1 + e); psi1 <= 1 starts
// with no slip (the contact's initial dQ/dP = mu psi1 < mu: Johnson ch. 7, oblique forces).
enum class TangentialCompliance {
  mindlin_deresiewicz,  // MBF's: slip annuli with their load history (integrated by strips, below)
  force,                // df_t = -k_t(delta) dv_t dt, capped at mu f_n (tangential_history "force", YADE)
  displacement,         // f_t = -k_t(delta) xi, capped (tangential_history "displacement", LIGGGHTS)
  displacement_rescale  // the same, xi scaled by a/a_old while a shrinks (LAMMPS mindlin_rescale)
};
const char* compliance_name(TangentialCompliance c);

double mbf_kappa(double e_star, double g_star);
double mbf_chi(double kappa, const ImpactBodies& b);

// Steps of the normalised integration: time in delta_max/v_n (the elastic contact lasts 2.943),
// strips across the largest contact radius. The defaults resolve psi2 to about 1e-5 (tests).
struct MbfResolution {
  double dtau = 2e-4;
  int strips = 2000;
};
struct MbfRebound {
  double psi2 = 0.0;         // kappa v_ct'/(mu v_n), v_n the incident normal speed
  double restitution = 1.0;  // the normal history's
  bool slid_throughout = false;  // the tangential force stood at mu f_n at every step in contact
};
// The normalised impact: x = delta/delta_max, x'' = -p, p = (5/4) x^(3/2) + 2 beta sqrt(15/8) x^(1/4) x'
// (granwave's Hertz dashpot; clipped at 0 with clip_tension), psi' = -2 chi q, q the tangential force
// over mu m v_n^2/delta_max, by the chosen compliance; no_slip: mu -> infinity (the sticking limit,
// psi2/psi1 then independent of psi1).
MbfRebound mbf_rebound(double chi, double psi1, TangentialCompliance law, double damping_ratio = 0.0,
                       bool clip_tension = false, bool no_slip = false, MbfResolution res = {});
// The sliding boundary psi1 of an elastic normal history: 4 chi - 1 (Mindlin-Deresiewicz and the force
// history: slip lasts while psi > x'/v_n), 4 chi - 2/3 (the displacement histories: while psi > (2/3) x'/v_n,
// since their slipping spring holds xi = mu f_n/k_t = (2/3)(mu/kappa) delta).
double mbf_sliding_boundary(double chi, TangentialCompliance law);

// The rebound of an incidence from psi2: the tangential impulse (v_ct - v_ct')/K_t as coulomb_oblique applies it.
ObliqueImpact oblique_from_psi2(const ImpactBodies& b, const ObliqueIncidence& in, double mu, double kappa,
                                double psi2, double restitution);

}  // namespace granwave::theory
