// Closed forms of a sphere's impact on a sphere or a wall (theory/impact.hpp).
#include "theory/impact.hpp"

#include <algorithm>
#include <cmath>
#include <numbers>
#include <vector>

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

const char* compliance_name(TangentialCompliance c) {
  switch (c) {
    case TangentialCompliance::mindlin_deresiewicz: return "mindlin_deresiewicz";
    case TangentialCompliance::force: return "force";
    case TangentialCompliance::displacement: return "displacement";
    case TangentialCompliance::displacement_rescale: return "displacement_rescale";
  }
  return "?";
}

double mbf_kappa(double e_star, double g_star) { return 4.0 * g_star / e_star; }
double mbf_chi(double kappa, const ImpactBodies& b) { return 0.5 * kappa * b.m_eff() * b.tangential_compliance(); }

double mbf_sliding_boundary(double chi, TangentialCompliance law) {
  const bool spring = law == TangentialCompliance::displacement || law == TangentialCompliance::displacement_rescale;
  return 4.0 * chi - (spring ? 2.0 / 3.0 : 1.0);
}

MbfRebound mbf_rebound(double chi, double psi1, TangentialCompliance law, double damping_ratio, bool clip_tension,
                       bool no_slip, MbfResolution res) {
  // Units: delta_max, delta_max/v_n; forces over m v_n^2/delta_max (tangential: also over mu); the
  // tangential displacement over mu delta_max/kappa. Then k_n = (15/8) x^(1/2) and k_t = k_n.
  const double dashpot = 2.0 * damping_ratio * std::sqrt(15.0 / 8.0);
  auto normal = [&](double x, double v) {
    const double p = 1.25 * x * std::sqrt(x) + dashpot * std::sqrt(std::sqrt(x)) * v;
    return clip_tension && p < 0.0 ? 0.0 : p;
  };
  // Mindlin-Deresiewicz by strips: the axisymmetric contact as independent strips at distance r from
  // the axis (r over sqrt(R* delta_max)), each with normal load (15/16)(x - r^2) and tangential load
  // (15/16) u per unit r, Coulomb at each: |u| <= (x - r^2) p/p_elastic (the dashpot's share spread as
  // the elastic pressure). A strip enters with u = 0 and leaves with its load. Summed, p = (5/4)
  // x^(3/2), and with no slip dq = k_n dxi: Mindlin's 8 G* a; slip annuli and their memory follow
  // from each strip's own history (the Abel-transform form of Mindlin-Deresiewicz's superposition;
  // Popov & Hess, Method of Dimensionality Reduction (2015), ch. 2 and 5).
  const int n = law == TangentialCompliance::mindlin_deresiewicz ? res.strips : 0;
  std::vector<double> u(n, 0.0);
  int reach = 0;  // strips [0, reach) are in contact
  const double dr = 1.0 / n;
  double x = 0.0, v = 1.0, psi = psi1, q = 0.0, s = 0.0, p = 0.0;
  bool slid = true, touched = false;
  const double h = res.dtau;
  const long cap = static_cast<long>(100.0 / h);
  for (long step = 0; step < cap; ++step) {
    v -= 0.5 * h * p;
    psi -= h * chi * q;  // half kick: psi' = -2 chi q
    x += h * v;
    if (!(x > 0.0)) {
      if (touched) break;
      continue;
    }
    touched = true;
    p = normal(x, v);
    const double kn = 1.875 * std::sqrt(x), d = psi * h;
    const double limit = no_slip ? kInfinite : std::max(p, 0.0);  // a pulling dashpot gives no friction
    bool slipping = false;
    switch (law) {
      case TangentialCompliance::mindlin_deresiewicz: {
        const double share = no_slip ? kInfinite : std::max(p, 0.0) / (1.25 * x * std::sqrt(x));
        double sum = 0.0;
        bool all = true;
        for (int j = 0; j < n; ++j) {
          const double r = (j + 0.5) * dr, room = x - r * r;
          if (!(room > 0.0)) {  // this strip and the ones beyond are out of contact: those that just left unload
            for (int k = j; k < reach; ++k) u[k] = 0.0;
            reach = j;
            break;
          }
          reach = std::max(reach, j + 1);
          const double c = room * share;
          double uj = u[j] + d;
          const bool over = std::abs(uj) >= c;
          if (over) uj = std::copysign(c, uj);
          all = all && over;
          u[j] = uj;
          sum += uj;
        }
        q = 0.9375 * 2.0 * sum * dr;  // both sides of the axis: (15/16) * 2 int_0^sqrt(x) u dr
        slipping = all;
        break;
      }
      case TangentialCompliance::force:
        q += kn * d;
        break;
      case TangentialCompliance::displacement_rescale:
      case TangentialCompliance::displacement: {
        // s: the spring; rescaled by a/a_old while a shrinks (x - h v: the previous x)
        if (law == TangentialCompliance::displacement_rescale && v < 0.0) s *= std::sqrt(x / (x - h * v));
        s += d;
        q = kn * s;
        break;
      }
    }
    if (law != TangentialCompliance::mindlin_deresiewicz) {
      slipping = std::abs(q) >= limit;
      if (slipping) {
        q = std::copysign(limit, q);
        s = q / kn;
      }
    }
    slid = slid && slipping;
    v -= 0.5 * h * p;
    psi -= h * chi * q;
  }
  MbfRebound r;
  r.psi2 = psi;
  r.restitution = -v;
  r.slid_throughout = slid && !no_slip;
  return r;
}

ObliqueImpact oblique_from_psi2(const ImpactBodies& b, const ObliqueIncidence& in, double mu, double kappa, double psi2,
                                double restitution) {
  ObliqueImpact r;
  const double K = b.tangential_compliance();
  const double inv_m = 1.0 / b.m1 + (std::isinf(b.m2) ? 0.0 : 1.0 / b.m2);
  const double vct = in.vt - b.R1 * in.w1 - (std::isinf(b.R2) ? 0.0 : b.R2 * in.w2);
  r.vct_after = psi2 * mu * in.vn / kappa;
  const double pt = (vct - r.vct_after) / K;
  r.sliding = false;
  r.boundary = std::nan("");
  r.vn_after = restitution * in.vn;
  r.vt_after = in.vt - pt * inv_m;
  r.w1_after = in.w1 + b.R1 * pt / b.I1;
  r.w2_after = std::isinf(b.I2) ? in.w2 : in.w2 + b.R2 * pt / b.I2;
  r.tangential_restitution = in.vt != 0.0 ? r.vt_after / in.vt : std::nan("");
  r.contact_point_restitution = vct != 0.0 ? -r.vct_after / vct : std::nan("");
  r.rebound_angle = std::atan2(r.vct_after, r.vn_after);
  r.rebound_angle_centre = std::atan2(r.vt_after, r.vn_after);
  return r;
}

}  // namespace granwave::theory
