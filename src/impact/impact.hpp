// The impact model (model = "impact", data/SCHEMA.md §7): two spheres, or a sphere and a flat wall,
// in 3D with rotation and no gravity, under one contact law of the registry (Chung & Ooi's
// contact-level tests). Velocity Verlet with rotation as in the crystal; the contact's history as
// the law keeps it.
#pragma once
#include <iosfwd>
#include <string>
#include <vector>

#include "config/case.hpp"
#include "contact/vec3.hpp"
#include "core/trace_series.hpp"
#include "theory/impact.hpp"

namespace granwave::impact {

using contact::Vec3;

struct Body {
  double radius = 0.0, mass = 0.0, inertia = 0.0;  // inertia (2/5) m R^2: a solid sphere
  Vec3 x, v, w;
};

// The case resolved: masses, the pair's moduli, the law's parameters, the time step.
struct Setup {
  Body b1, b2;  // b2 unused with a wall
  bool wall = false;
  Vec3 wall_normal, wall_point;
  double e_star = 0.0, g_star = 0.0;  // the pair's (rigid wall: E2 -> infinity)
  // The law's like-sphere material with this pair's E*, G* (see setup.cpp) and the density whose
  // masses give this pair's m* (the damping's).
  double law_youngs_modulus = 0.0, law_poisson_ratio = 0.0, law_density = 0.0;
  contact::LawParams contact;  // the case's, the damping set from contact.restitution
  bool hertz = false;             // Hertz normal force (else the linear law)
  double approach_speed = 0.0;    // initial closing speed along the line of centres (m/s)
  double gap_time = 0.0;          // until first touch (s)
  double contact_time = 0.0;      // the law's closed-form elastic/damped contact time (s)
  double dt = 0.0, t_end = 0.0;   // t_end 0: separation + after_separation contact times
  double t_cap = 0.0;             // the run ends here at the latest
  double after_separation = 0.0;  // s
  double interval = 0.0;          // output interval (0: every step)
  theory::ImpactBodies bodies() const;
};
Setup resolve(const config::Case& c);  // throws InputError naming the key

// The series of one run (row-major [nt, 3] for vectors), as the trace file holds them.
struct Series {
  std::vector<double> time, overlap, force_normal, force_tangential;  // overlap: geometric (< 0: gap)
  std::vector<double> x1, v1, w1, x2, v2, w2;
  std::vector<double> kinetic, stored, dissipated;
  std::size_t size() const { return time.size(); }
};
Series simulate(const Setup& s);

// What analyze needs of a trace (any code's): the series and the geometry.
struct Trace {
  std::string case_name, code = "granwave", law;
  bool wall = false;
  Vec3 wall_normal;
  double radius1 = 0.0, radius2 = 0.0;
  Series series;
};
// The trace a run of `s` writes, in memory (what run and the tests measure).
Trace trace_of(const Setup& s, Series series);
void write_trace(const config::Case& c, const Setup& s, const Series& series, const std::string& path);
// Every dataset write_trace writes, under its path and shape, the series moved in (RunRequest::keep).
TraceSeries trace_series(const Setup& s, Series series);
Trace read_trace(const std::string& path);
bool is_impact_trace(const std::string& path);

// The rebound, measured on a trace (docs: data/SCHEMA.md §7.3). Tangential values along t (the
// incident tangential velocity of the contact point, else of the centres), spins about s = n x t.
struct Rebound {
  bool touched = false, separated = false;
  double peak_force = 0.0, peak_force_time = 0.0, peak_overlap = 0.0;
  double contact_start = 0.0, contact_end = 0.0, contact_time = 0.0;
  double vn_in = 0.0, vt_in = 0.0, vct_in = 0.0, w1_in = 0.0, w2_in = 0.0;  // vn: approach speed
  double vn_out = 0.0, vt_out = 0.0, vct_out = 0.0, w1_out = 0.0, w2_out = 0.0;  // vn: separation speed
  double normal_restitution = 0.0;
  double tangential_restitution = 0.0;     // vt_out/vt_in (NaN head-on)
  double contact_point_restitution = 0.0;  // -vct_out/vct_in (NaN without tangential slip)
  double incident_angle = 0.0;             // atan(vt_in/vn_in) (rad)
  double rebound_angle = 0.0;              // atan(vct_out/vn_out) (rad), the contact point's
  double rebound_angle_centre = 0.0;       // atan(vt_out/vn_out) (rad)
  Vec3 normal, tangent;
};
Rebound measure(const Trace& t);

// The verbs (src/models.hpp has check, build, run).
void print_theory(const config::Case& c, bool json, std::ostream& out);
void print_analysis(const Trace& t, bool json, std::ostream& out);

}  // namespace granwave::impact
