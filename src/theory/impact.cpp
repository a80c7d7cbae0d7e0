#include "theory/impact.hpp"

#include <cmath>
#include <numbers>

#include "core/error.hpp"
#include "theory/crystal_theory.hpp"

namespace granwave::theory {

double effective_modulus(double E1, double nu1, double E2, double nu2) {
  const double c2 = std::isinf(E2) ? 0.0 : (1.0 - nu2 * nu2) / E2;
  return 1.0 / ((1.0 - nu1 * nu1) / E1 + c2);
}

double effective_shear_modulus(double E1, double nu1, double E2, double nu2) {
  auto compliance = [](double E, double nu) { return std::isinf(E) ? 0.0 : (2.0 - nu) / (E / (2.0 * (1.0 + nu))); };
  return 1.0 / (compliance(E1, nu1) + compliance(E2, nu2));
}

double ImpactBodies::r_eff() const { return std::isinf(R2) ? R1 : R1 * R2 / (R1 + R2); }
double ImpactBodies::m_eff() const { return std::isinf(m2) ? m1 : m1 * m2 / (m1 + m2); }
double ImpactBodies::tangential_compliance() const {
  auto part = [](double x) { return std::isinf(x) ? 0.0 : x; };
  return 1.0 / m1 + part(1.0 / m2) + R1 * R1 / I1 + (std::isinf(I2) ? 0.0 : R2 * R2 / I2);
}

HertzImpact hertz_normal_impact(const ImpactBodies& b, double e_star, double v) {
  HertzImpact h = hertz_impact(4.0 / 3.0 * e_star * std::sqrt(b.r_eff()), b.m1, b.m2, v);
  // t_c = 2 (delta_max/v) int_0^1 dx/sqrt(1 - x^(5/2)) = (4/5) B(2/5, 1/2) delta_max/v: exact, where the
  // constant 2.86827 of hertz_impact carries 6 digits (the impact's peaks converge to 1e-7).
  h.contact_time = 0.8 * std::beta(0.4, 0.5) * h.max_overlap / v;
  return h;
}

double mapped_damping_ratio(double e) {
  const double l = std::log(e);
  return -l / std::sqrt(l * l + std::numbers::pi * std::numbers::pi) / std::sqrt(1.2);
}

double hertz_damping_ratio_for(double e, bool clip_tension) {
  if (!(e > 0.0 && e <= 1.0)) throw InputError("contact.restitution = " + std::to_string(e) + ": must be in (0, 1]");
  if (e == 1.0) return 0.0;
  auto miss = [&](double beta) { return damped_hertz_impact(beta, clip_tension).restitution - e; };
  // Secant from the oscillator's mapping (close: the realised e differs by a few per cent).
  double b0 = mapped_damping_ratio(e), b1 = 1.02 * b0;
  double f0 = miss(b0), f1 = miss(b1);
  for (int k = 0; k < 30 && std::abs(f1) > 1e-11 && f1 != f0; ++k) {
    double b2 = b1 - f1 * (b1 - b0) / (f1 - f0);
    if (!(b2 > 0.0)) b2 = 0.5 * b1;
    if (!(b2 < 1.0)) b2 = 0.5 * (b1 + 1.0);
    b0 = b1, f0 = f1, b1 = b2, f1 = miss(b2);
  }
  if (!(std::abs(f1) <= 1e-9))
    throw InputError("contact.restitution = " + std::to_string(e) + ": no damping_ratio in [0, 1) realises it");
  return b1;
}

double linear_damping_for(double e, double k, double m_eff, bool clip_tension) {
  if (!(e > 0.0 && e <= 1.0)) throw InputError("contact.restitution = " + std::to_string(e) + ": must be in (0, 1]");
  if (e == 1.0) return 0.0;
  // Restitution falls monotonically with gamma_n up to the overdamped limit 2 sqrt(k m*): bisection.
  double lo = 0.0, hi = 2.0 * std::sqrt(k * m_eff) * (1.0 - 1e-9);
  if (linear_contact_time(k, hi, m_eff, clip_tension).restitution > e)
    throw InputError("contact.restitution = " + std::to_string(e) + ": below what an underdamped contact realises");
  for (int i = 0; i < 200 && hi - lo > 1e-15 * hi; ++i) {
    const double mid = 0.5 * (lo + hi);
    (linear_contact_time(k, mid, m_eff, clip_tension).restitution > e ? lo : hi) = mid;
  }
  return 0.5 * (lo + hi);
}

ObliqueImpact coulomb_oblique(const ImpactBodies& b, const ObliqueIncidence& in, double mu, double e) {
  ObliqueImpact r;
  const double m = b.m_eff(), K = b.tangential_compliance();
  const double inv_m = 1.0 / b.m1 + (std::isinf(b.m2) ? 0.0 : 1.0 / b.m2);
  const double pn = (1.0 + e) * in.vn * m;  // normal impulse
  const double vct = in.vt - b.R1 * in.w1 - (std::isinf(b.R2) ? 0.0 : b.R2 * in.w2);
  r.boundary = mu * (1.0 + e) * m * K;
  r.sliding = std::abs(vct) >= r.boundary * in.vn;
  const double pt = r.sliding ? mu * pn * (vct >= 0.0 ? 1.0 : -1.0) : vct / K;  // tangential impulse on 1, along -t
  r.vn_after = e * in.vn;
  r.vt_after = in.vt - pt * inv_m;
  r.w1_after = in.w1 + b.R1 * pt / b.I1;
  r.w2_after = std::isinf(b.I2) ? in.w2 : in.w2 + b.R2 * pt / b.I2;
  r.vct_after = vct - pt * K;
  r.tangential_restitution = in.vt != 0.0 ? r.vt_after / in.vt : std::nan("");
  r.contact_point_restitution = vct != 0.0 ? -r.vct_after / vct : std::nan("");
  r.rebound_angle = std::atan2(r.vct_after, r.vn_after);
  r.rebound_angle_centre = std::atan2(r.vt_after, r.vn_after);
  return r;
}

double mbf_chi(double nu) { return 3.5 * (1.0 - nu) / (2.0 - nu); }
double mbf_psi(double nu, double mu, double vct_over_vn) { return 2.0 * (1.0 - nu) / ((2.0 - nu) * mu) * vct_over_vn; }

}  // namespace granwave::theory
