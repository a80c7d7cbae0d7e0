// check, build, run, theory and analyze of an impact case (src/models.hpp, impact/impact.hpp).
#include <cmath>
#include <numbers>
#include <ostream>
#include <sstream>

#include "config/contact_laws.hpp"
#include "contact/hertz_mindlin_params.hpp"
#include "core/error.hpp"
#include "core/format.hpp"
#include "core/json.hpp"
#include "impact/impact.hpp"
#include "models.hpp"
#include "theory/crystal_theory.hpp"

namespace granwave::impact {
namespace {

using json = Json;

constexpr double kDeg = 180.0 / std::numbers::pi;

json number(double x) { return std::isfinite(x) ? json(x) : json(nullptr); }
json vec(const Vec3& v) { return json::array({v.x(), v.y(), v.z()}); }

std::string g6(double x) { return fmt("%.6g", x); }

double steps_of(const Setup& s) { return std::ceil(s.t_cap / s.dt); }

// The case's own initial state measured as a trace of one sample: the incidence of the closed forms.
Rebound incidence(const Setup& s) {
  Series x;
  auto put = [](std::vector<double>& to, const Vec3& v) { to = {v.x(), v.y(), v.z()}; };
  x.time = {0.0}, x.overlap = {-1.0}, x.force_normal = {0.0};
  put(x.x1, s.b1.x), put(x.v1, s.b1.v), put(x.w1, s.b1.w);
  if (!s.wall) put(x.x2, s.b2.x), put(x.v2, s.b2.v), put(x.w2, s.b2.w);
  return measure(trace_of(s, std::move(x)));
}

json rebound_json(const Rebound& r) {
  return {{"touched", r.touched},
          {"separated", r.separated},
          {"peak_force", number(r.peak_force)},
          {"peak_force_time", number(r.peak_force_time)},
          {"peak_overlap", number(r.peak_overlap)},
          {"contact_start", number(r.contact_start)},
          {"contact_time", number(r.contact_time)},
          {"normal_restitution", number(r.normal_restitution)},
          {"tangential_restitution", number(r.tangential_restitution)},
          {"contact_point_restitution", number(r.contact_point_restitution)},
          {"incident_angle_deg", number(r.incident_angle * kDeg)},
          {"rebound_angle_deg", number(r.rebound_angle * kDeg)},
          {"rebound_angle_centre_deg", number(r.rebound_angle_centre * kDeg)},
          {"spin_after", number(r.w1_out)},
          {"spin2_after", number(r.w2_out)},
          {"in", {{"vn", r.vn_in}, {"vt", r.vt_in}, {"vct", r.vct_in}, {"w1", r.w1_in}, {"w2", r.w2_in}}},
          {"out", {{"vn", r.vn_out}, {"vt", r.vt_out}, {"vct", r.vct_out}, {"w1", r.w1_out}, {"w2", r.w2_out}}},
          {"normal", vec(r.normal)},
          {"tangent", vec(r.tangent)}};
}

std::string rebound_text(const Rebound& r) {
  std::ostringstream o;
  if (!r.touched) return "  the bodies never touched\n";
  o << "  peak force " << g6(r.peak_force) << " N at t = " << g6(r.peak_force_time) << " s, peak overlap "
    << g6(r.peak_overlap) << " m\n";
  o << "  contact time " << g6(r.contact_time) << " s (from t = " << g6(r.contact_start) << " s)"
    << (r.separated ? "" : "; the bodies had not separated at the end of the trace") << "\n";
  o << "  normal restitution " << g6(r.normal_restitution) << " (approach " << g6(r.vn_in) << " m/s, separation "
    << g6(r.vn_out) << " m/s)\n";
  if (r.tangent.squaredNorm() > 0.0) {
    o << "  incident angle " << g6(r.incident_angle * kDeg) << " deg; tangential restitution (centre) "
      << g6(r.tangential_restitution) << ", of the contact point " << g6(r.contact_point_restitution) << "\n";
    o << "  rebound angle " << g6(r.rebound_angle * kDeg) << " deg (contact point), " << g6(r.rebound_angle_centre * kDeg)
      << " deg (centre); spin after " << g6(r.w1_out) << " rad/s (about n x t)\n";
  } else {
    o << "  head-on: spin after |w1| = " << g6(r.w1_out) << " rad/s\n";
  }
  return o.str();
}


using theory::TangentialCompliance;

// The rebound values of a theory's ObliqueImpact, as `granwave theory --json` names them.
json rebound_values(const theory::ObliqueImpact& ob) {
  return {{"tangential_restitution", number(ob.tangential_restitution)},
          {"contact_point_restitution", number(ob.contact_point_restitution)},
          {"rebound_angle_deg", ob.rebound_angle * kDeg},
          {"rebound_angle_centre_deg", ob.rebound_angle_centre * kDeg},
          {"spin_after", ob.w1_after}};
}

TangentialCompliance compliance_of(contact::TangentialHistory h) {
  switch (h) {
    case contact::TangentialHistory::displacement: return TangentialCompliance::displacement;
    case contact::TangentialHistory::displacement_rescale: return TangentialCompliance::displacement_rescale;
    case contact::TangentialHistory::force: return TangentialCompliance::force;
  }
  return TangentialCompliance::displacement;
}

// Mindlin's compliance (theory::mbf_rebound): Maw, Barber & Fawcett's Mindlin-Deresiewicz rebound and
// the simplified Mindlin laws' (the three tangential histories), with the case's normal damping.
void compliance_theory(const Setup& s, const theory::ImpactBodies& b, const Rebound& in, double mu, json& j,
                       std::ostream& o) {
  const bool clip = s.contact.friction().clip();
  const double beta = *s.contact.number("damping_ratio");
  const double kappa = theory::mbf_kappa(s.e_star, s.g_star), chi = theory::mbf_chi(kappa, b);
  const double psi1 = kappa * in.vct_in / (mu * in.vn_in);
  const double boundary = theory::mbf_sliding_boundary(chi, TangentialCompliance::mindlin_deresiewicz);
  const TangentialCompliance own = compliance_of(s.contact.get<contact::HertzMindlinCaseParams>().tangential_history);
  j["mbf_kappa"] = kappa;
  j["mbf_chi"] = chi;
  j["mbf_psi1"] = psi1;
  j["mbf_regime"] = psi1 >= boundary ? "gross_sliding" : psi1 > 1.0 ? "slip_stick" : "stick_microslip";
  j["mbf_sliding_boundary"] = boundary;
  j["law_tangential_history"] = theory::compliance_name(own);
  json curves = json::object();
  o << "    kappa = 4 G*/E* = " << g6(kappa) << ", chi = (kappa/2) m* K_t = " << g6(chi) << ", psi1 = kappa v_ct/(mu v_n) = "
    << g6(psi1) << ": " << (psi1 >= boundary ? "gross sliding" : psi1 > 1.0 ? "slip at first, then stick and microslip"
                                                                             : "stick at first, then microslip")
    << " (elastic boundaries psi1 = 1 and 4 chi - 1 = " << g6(boundary) << ")\n";
  for (TangentialCompliance c : {TangentialCompliance::mindlin_deresiewicz, TangentialCompliance::force,
                                 TangentialCompliance::displacement, TangentialCompliance::displacement_rescale}) {
    const theory::MbfRebound r = theory::mbf_rebound(chi, psi1, c, beta, clip);
    const double slope = theory::mbf_rebound(chi, 1.0, c, beta, clip, true).psi2;
    const theory::ObliqueImpact ob =
        theory::oblique_from_psi2(b, {in.vn_in, in.vt_in, in.w1_in, in.w2_in}, mu, kappa, r.psi2, r.restitution);
    json curve = rebound_values(ob);
    curve.update({{"psi2", r.psi2},
                  {"sliding_boundary", theory::mbf_sliding_boundary(chi, c)},
                  {"stick_slope", slope},
                  {"slid_throughout", r.slid_throughout},
                  {"restitution", r.restitution}});
    curves[theory::compliance_name(c)] = curve;
    o << "    " << (c == TangentialCompliance::mindlin_deresiewicz ? "Mindlin-Deresiewicz (MBF)" : theory::compliance_name(c))
      << (c == own ? " [this case's law]" : "") << ": psi2 = " << g6(r.psi2) << " (sticking limit psi2/psi1 = " << g6(slope)
      << "), rebound angle " << g6(ob.rebound_angle * kDeg) << " deg (contact point), spin after " << g6(ob.w1_after)
      << " rad/s\n";
  }
  j["mbf_psi2"] = curves["mindlin_deresiewicz"]["psi2"];
  j["compliance"] = curves;
}
}  // namespace

void print_analysis(const Trace& t, bool json_out, std::ostream& out) {
  const Rebound r = measure(t);
  if (json_out) {
    json j = {{"schema", "granwave-analyze/1"}, {"model", "impact"},     {"case_name", t.case_name},
              {"code", t.code},                 {"contact_law", t.law}, {"geometry", t.wall ? "sphere_wall" : "sphere_sphere"},
              {"rebound", rebound_json(r)}};
    out << json_text(j);
    return;
  }
  out << "impact trace of " << (t.code.empty() ? "?" : t.code) << ", case " << t.case_name << " ("
      << (t.wall ? "sphere on a wall" : "two spheres") << ", " << t.series.size() << " samples)\n"
      << rebound_text(r);
}

void print_theory(const config::Case& c, bool json_out, std::ostream& out) {
  const Setup s = resolve(c);
  const theory::ImpactBodies b = s.bodies();
  const Rebound in = incidence(s);
  const bool clip = s.contact.friction().clip();
  json j = {{"schema", "granwave-theory-impact/1"}, {"case", c.name}, {"model", "impact"},
            {"effective_modulus", s.e_star}, {"effective_shear_modulus", s.g_star}, {"effective_radius", b.r_eff()},
            {"effective_mass", b.m_eff()}, {"approach_speed", s.approach_speed}};
  std::ostringstream o;
  o << "impact " << c.name << ": " << (s.wall ? "sphere on a wall" : "two spheres") << ", E* = " << g6(s.e_star)
    << " Pa, G* = " << g6(s.g_star) << " Pa, R* = " << g6(b.r_eff()) << " m, m* = " << g6(b.m_eff())
    << " kg, approach speed " << g6(s.approach_speed) << " m/s\n";
  double e = 1.0;
  if (s.hertz) {
    const theory::HertzImpact h = theory::hertz_normal_impact(b, s.e_star, s.approach_speed);
    const theory::DampedHertzImpact d = theory::damped_hertz_impact(s.contact.number("damping_ratio").value_or(0.0), clip);
    e = d.restitution;
    j["hertz"] = {{"peak_overlap", h.max_overlap}, {"peak_force", h.peak_force}, {"contact_time", h.contact_time}};
    j["damping_ratio"] = s.contact.number("damping_ratio").value_or(0.0);
    j["restitution"] = e;
    j["contact_time_damped"] = h.contact_time * d.time_ratio;
    o << "  Hertz (elastic): peak overlap " << g6(h.max_overlap) << " m, peak force " << g6(h.peak_force)
      << " N, contact time " << g6(h.contact_time) << " s\n";
    o << "  damping_ratio " << g6(s.contact.number("damping_ratio").value_or(0.0)) << " (normal_tension " << (clip ? "clip" : "allow")
      << "): restitution " << g6(e) << ", contact time " << g6(h.contact_time * d.time_ratio) << " s\n";
    if (s.contact.number("damping_ratio").value_or(0.0) > 0.0) {
      const double beta = theory::mapped_damping_ratio(e);
      const double e_mapped = theory::damped_hertz_impact(beta, clip).restitution;
      j["mapped_damping_ratio"] = beta;
      j["mapped_restitution"] = e_mapped;
      o << "  the LIGGGHTS/LAMMPS mapping ln e/sqrt(ln^2 e + pi^2) = -beta sqrt(6/5) of this e gives beta = " << g6(beta)
        << ", which realises e = " << g6(e_mapped) << " with this law\n";
    }
  } else {
    const theory::ContactTime ct = theory::linear_contact_time(s.contact.number("kn").value_or(0.0), s.contact.number("gamma_n").value_or(0.0), b.m_eff(), clip);
    e = ct.restitution;
    j["linear"] = {{"contact_time", ct.t_c}, {"peak_overlap_elastic", s.approach_speed * std::sqrt(b.m_eff() / s.contact.number("kn").value_or(0.0))}};
    j["gamma_n"] = s.contact.number("gamma_n").value_or(0.0);
    j["restitution"] = e;
    o << "  linear law: contact time " << g6(ct.t_c) << " s, restitution " << g6(e) << " (gamma_n "
      << g6(s.contact.number("gamma_n").value_or(0.0)) << " kg/s)\n";
  }
  if (in.tangent.squaredNorm() > 0.0) {
    const double mu = s.contact.friction().mu_dynamic;
    const theory::ObliqueImpact ob = theory::coulomb_oblique(b, {in.vn_in, in.vt_in, in.w1_in, in.w2_in}, mu, e);
    const double nu = c.material(c.impact->body1.material).poisson_ratio;
    const double psi = theory::mbf_psi(nu, mu, in.vct_in / in.vn_in), chi = theory::mbf_chi(nu);
    j["oblique"] = rebound_values(ob);
    j["oblique"].update({{"mu", mu},
                         {"incident_angle_deg", in.incident_angle * kDeg},
                         {"sliding", ob.sliding},
                         {"boundary_vct_over_vn", ob.boundary},
                         {"mbf_psi1", psi},
                         {"mbf_chi", chi}});
    o << "  oblique, Coulomb mu = " << g6(mu) << ", rigid bodies: incident angle " << g6(in.incident_angle * kDeg)
      << " deg, v_ct/v_n = " << g6(in.vct_in / in.vn_in) << " against the sliding boundary " << g6(ob.boundary)
      << ": " << (ob.sliding ? "gross sliding" : "rigid stick (Mindlin's compliance changes this regime)") << "\n";
    o << "    tangential restitution " << g6(ob.tangential_restitution) << " (centre), "
      << g6(ob.contact_point_restitution) << " (contact point); rebound angle " << g6(ob.rebound_angle * kDeg)
      << " deg (contact point), " << g6(ob.rebound_angle_centre * kDeg) << " deg (centre); spin after "
      << g6(ob.w1_after) << " rad/s\n";
    o << "    Maw, Barber & Fawcett: psi1 = " << g6(psi) << ", chi = " << g6(chi) << "; rigid sliding for psi1 >= 2 chi (1 + e) = "
      << g6(2.0 * chi * (1.0 + e)) << "\n";
    if (s.hertz && config::law_of(s.contact).torques(s.contact) && mu > 0.0) compliance_theory(s, b, in, mu, j["oblique"], o);
  } else if (in.w1_in != 0.0 || in.w2_in != 0.0) {
    // Spins whose contact points move together (Chung & Ooi T7's +-w): no relative tangential velocity, no
    // tangential force, so the spins and the tangential velocities come out as they went in.
    j["rolling"] = {{"spin_after", in.w1_in}, {"spin2_after", in.w2_in}};
    o << "  no sliding at the contact (the contact points move together): spins " << g6(in.w1_in) << ", " << g6(in.w2_in)
      << " rad/s kept, no tangential velocity after\n";
  }
  out << (json_out ? json_text(j) : o.str());
}

}  // namespace granwave::impact

namespace granwave::impact {

void check(const config::Case& c, std::ostream& out, const ResourceLimits& limits) {
  const Setup s = resolve(c);
  const double steps = steps_of(s);
  if (steps > limits.max_steps)
    throw InputError(c.path + ": key 'integrator.dt': " + g6(steps) + " steps exceed --max-steps " + g6(limits.max_steps));
  const config::ContactLawInfo& law = config::law_of(c.contact);
  out << "case " << c.name << " (impact, " << (s.wall ? "sphere on a wall" : "two spheres") << ")\n";
  auto body = [&](const char* name, const config::ImpactBody& k, const Body& b) {
    out << "  " << name << ": " << k.material << ", R = " << g6(b.radius) << " m, m = " << g6(b.mass) << " kg, I = "
        << g6(b.inertia) << " kg m^2, v = (" << g6(b.v.x()) << ", " << g6(b.v.y()) << ", " << g6(b.v.z()) << ") m/s, w = ("
        << g6(b.w.x()) << ", " << g6(b.w.y()) << ", " << g6(b.w.z()) << ") rad/s\n";
  };
  body("body1", c.impact->body1, s.b1);
  if (s.wall)
    out << "  wall: " << c.impact->wall->material << ", normal (" << g6(s.wall_normal.x()) << ", " << g6(s.wall_normal.y())
        << ", " << g6(s.wall_normal.z()) << ")\n";
  else
    body("body2", *c.impact->body2, s.b2);
  out << "  contact law " << law.name << " (tangential history " << law.history_name(c.contact) << "), E* = " << g6(s.e_star)
      << " Pa, G* = " << g6(s.g_star) << " Pa";
  if (s.hertz)
    out << " (the law's like-sphere material: E = " << g6(s.law_youngs_modulus) << " Pa, nu = " << g6(s.law_poisson_ratio)
        << "), damping_ratio " << g6(s.contact.number("damping_ratio").value_or(0.0));
  else
    out << ", gamma_n " << g6(s.contact.number("gamma_n").value_or(0.0)) << " kg/s";
  if (c.impact->restitution) out << " (set by contact.restitution = " << g6(*c.impact->restitution) << ")";
  out << "\n" << law.tangential_line(c.contact);
  out << "  closing speed " << g6(s.approach_speed) << " m/s, first touch at t = " << g6(s.gap_time) << " s, contact time "
      << g6(s.contact_time) << " s\n";
  out << "  dt = " << g6(s.dt) << " s (" << g6(s.contact_time / s.dt) << " steps per contact), at most " << g6(steps)
      << " steps, ending " << (s.t_end > 0.0 ? "at integrator.t_end" : "after separation + impact.after_separation") << "\n";
  if (s.dt > s.contact_time / 50.0)
    out << "  warning: dt above t_c/50 (" << g6(s.contact_time / 50.0) << " s): the peaks are good to about (dt/t_c)^2\n";
}

void build(const config::Case& c, const std::string&) {
  throw InputError(c.path + ": an impact case has no system file: its two bodies are given in full by the case "
                   "(nothing random or derived to resolve); `granwave check` prints what is derived, and the other "
                   "codes read the case itself");
}

int run(const config::Case& c, const RunRequest& request, std::ostream& out) {
  const Setup s = resolve(c);
  const double steps = steps_of(s);
  if (steps > request.limits.max_steps)
    throw InputError(c.path + ": key 'integrator.dt': " + g6(steps) + " steps exceed --max-steps " + g6(request.limits.max_steps));
  if (!request.system_path.empty()) throw InputError("--system: an impact case has no system file (granwave build)");
  const Series series = simulate(s);
  if (!request.in_memory) write_trace(c, s, series, request.trace_path);  // in memory: measured below all the same
  Trace t = trace_of(s, series);
  t.law = config::law_of(c.contact).name;
  const Rebound r = measure(t);
  if (request.keep) request.keep(trace_series(s, std::move(t.series)));
  if (request.json) {
    json j = {{"schema", "granwave-run/1"},
              {"case", c.name},
              {"model", "impact"},
              {"trace", request.trace_path},
              {"dt", s.dt},
              {"steps", static_cast<long>(std::llround(series.time.back() / s.dt))},
              {"samples", series.size()},
              {"analysis", {{"schema", "granwave-analyze/1"}, {"model", "impact"}, {"case_name", c.name}, {"code", "granwave"},
                            {"contact_law", t.law}, {"geometry", s.wall ? "sphere_wall" : "sphere_sphere"},
                            {"rebound", rebound_json(r)}}}};
    out << json_text(j);
  } else {
    out << "impact " << c.name << ": " << series.size() << " samples to t = " << g6(series.time.back()) << " s, dt = "
        << g6(s.dt) << " s; trace " << request.trace_path << "\n"
        << rebound_text(r);
  }
  return 0;
}

}  // namespace granwave::impact
