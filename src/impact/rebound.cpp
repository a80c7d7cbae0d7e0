// The rebound measured on an impact trace (impact/impact.hpp, data/SCHEMA.md §7.3): the one ruler
// for granwave's and the other codes' traces. Peaks and crossings are analysis/measures.hpp's.
#include <cmath>

#include "analysis/measures.hpp"
#include "impact/impact.hpp"

namespace granwave::impact {
namespace {

Vec3 row(const std::vector<double>& v, std::size_t i) { return {v[3 * i], v[3 * i + 1], v[3 * i + 2]}; }

}  // namespace

Rebound measure(const Trace& tr) {
  const Series& s = tr.series;
  const std::size_t nt = s.size(), last = nt - 1;
  Rebound r;
  const analysis::Peak fmax = analysis::first_peak(s.time, s.force_normal);
  const analysis::Peak dmax = analysis::first_peak(s.time, s.overlap);
  const analysis::Arrival start = analysis::first_crossing(s.time, s.overlap, 0.0);
  std::size_t i0 = 0;
  while (i0 < nt && !(s.overlap[i0] > 0.0)) ++i0;
  r.touched = i0 < nt;
  if (r.touched) {
    std::vector<double> gap(nt);
    for (std::size_t i = 0; i < nt; ++i) gap[i] = -s.overlap[i];
    const analysis::Arrival end = analysis::first_crossing(s.time, gap, 0.0, i0);
    r.separated = end.found;
    r.contact_start = start.time;
    r.contact_end = end.found ? end.time : std::nan("");
    r.contact_time = r.contact_end - r.contact_start;
    r.peak_force = fmax.value, r.peak_force_time = fmax.time;
    r.peak_overlap = dmax.value;
  }

  // The normal at first touch (from body 2 to body 1), fixed for the in and out states.
  const std::size_t at = r.touched ? i0 : 0;
  const Vec3 n = tr.wall ? tr.wall_normal : (row(s.x1, at) - row(s.x2, at)).normalized();
  struct State {
    Vec3 dv, vt, vct, w1, w2;
  };
  auto state = [&](std::size_t i) {
    State st;
    st.w1 = row(s.w1, i);
    st.dv = row(s.v1, i);
    if (!tr.wall) st.dv = st.dv - row(s.v2, i), st.w2 = row(s.w2, i);
    st.vt = st.dv - n.dot(st.dv) * n;
    const Vec3 rolling = tr.radius1 * n.cross(st.w1) + (tr.wall ? Vec3{} : tr.radius2 * n.cross(st.w2));
    st.vct = st.vt + rolling - n.dot(rolling) * n;
    return st;
  };
  const State in = state(0), out = state(last);
  const double scale = in.dv.norm() + tr.radius1 * in.w1.norm() + (tr.wall ? 0.0 : tr.radius2 * in.w2.norm());
  const double tiny = 1e-12 * scale;
  Vec3 t = in.vct.norm() > tiny ? in.vct.normalized() : in.vt.norm() > tiny ? in.vt.normalized() : Vec3{};
  const bool oblique = t.squaredNorm() > 0.0;
  const Vec3 sp = n.cross(t);
  r.normal = n, r.tangent = t;
  r.vn_in = -n.dot(in.dv), r.vn_out = n.dot(out.dv);
  r.vt_in = in.vt.dot(t), r.vt_out = out.vt.dot(t);
  r.vct_in = in.vct.dot(t), r.vct_out = out.vct.dot(t);
  r.w1_in = oblique ? in.w1.dot(sp) : in.w1.norm(), r.w1_out = oblique ? out.w1.dot(sp) : out.w1.norm();
  r.w2_in = oblique ? in.w2.dot(sp) : in.w2.norm(), r.w2_out = oblique ? out.w2.dot(sp) : out.w2.norm();
  r.normal_restitution = r.vn_out / r.vn_in;
  r.tangential_restitution = std::abs(r.vt_in) > tiny ? r.vt_out / r.vt_in : std::nan("");
  r.contact_point_restitution = std::abs(r.vct_in) > tiny ? -r.vct_out / r.vct_in : std::nan("");
  r.incident_angle = std::atan2(in.vt.norm(), r.vn_in);
  r.rebound_angle = std::atan2(r.vct_out, r.vn_out);
  r.rebound_angle_centre = std::atan2(r.vt_out, r.vn_out);
  return r;
}

}  // namespace granwave::impact
