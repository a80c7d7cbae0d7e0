// The checks of a packing before a run (see checks.hpp for the list and their order).
#include "packing/checks.hpp"

#include <algorithm>
#include <cmath>
#include <sstream>
#include <unordered_map>

#include "core/error.hpp"
#include "packing/contacts.hpp"

namespace granwave::packing {

namespace {
const char* axis_name(int a) { return a == 0 ? "x" : a == 1 ? "y" : "z"; }
double coord(const Vec3& v, int a) { return a == 0 ? v.x() : a == 1 ? v.y() : v.z(); }
std::string num(double v) {
  std::ostringstream s;
  s.precision(9);
  s << v;
  return s.str();
}
}  // namespace

std::string where(const Packing& packing, const Particle& p) {
  std::string s = packing.source;  // appended piecewise: GCC 12 warns falsely (-Wrestrict) on "x" + string&&
  if (p.line > 0) {
    s += ':';
    s += std::to_string(p.line);
  }
  s += ", particle id ";
  s += std::to_string(p.id);
  return s;
}

void wrap_into_box(Packing& packing) {
  for (auto& p : packing.particles) p.centre = wrap(packing.box, p.centre);
}

void check_packing(const Packing& packing, const Limits& limits) {
  const Box& box = packing.box;
  const auto& ps = packing.particles;
  for (int a = 0; a < 3; ++a)
    if (!(box.hi[a] > box.lo[a]) || !std::isfinite(box.length(a)))
      throw InputError(packing.source + ": the box's " + axis_name(a) + " bounds [" + num(box.lo[a]) + ", " +
                       num(box.hi[a]) + "] are not a finite interval with hi > lo");
  for (int a = 0; a < 2; ++a)
    if (!box.periodic[a])
      throw InputError(packing.source + ": the box is not periodic in " + axis_name(a) +
                       ": lateral walls are not supported (allowed: periodic x and y, z periodic or between "
                       "flat walls, as LAMMPS' boundary p p p or p p f)");
  if (ps.empty()) throw InputError(packing.source + ": the packing has no particles");

  double a_max = 0.0;
  for (const auto& p : ps) a_max = std::max(a_max, p.radius);
  for (const auto& p : ps) {
    for (int a = 0; a < 3; ++a) {
      const double c = coord(p.centre, a);
      if (box.periodic[a]) continue;
      if (c < box.lo[a] || c > box.hi[a])
        throw InputError(where(packing, p) + ": centre " + axis_name(a) + " = " + num(c) +
                         " is outside the non-periodic box [" + num(box.lo[a]) + ", " + num(box.hi[a]) +
                         "] (allowed: inside; only a periodic axis wraps)");
      const double through = p.radius - std::min(c - box.lo[a], box.hi[a] - c);
      if (through > limits.max_overlap * p.radius)
        throw InputError(where(packing, p) + ": the sphere reaches " + num(through) + " m through the " +
                         axis_name(a) + " wall, more than max_overlap = " + num(limits.max_overlap) +
                         " of its radius " + num(p.radius));
    }
  }
  std::unordered_map<std::int64_t, const Particle*> seen;
  for (const auto& p : ps) {
    auto [it, fresh] = seen.emplace(p.id, &p);
    if (!fresh)
      throw InputError(where(packing, p) + ": duplicate id, already on line " + std::to_string(it->second->line) +
                       " (allowed: each id once)");
  }
  const double reach = limits.contact_reach > 0.0 ? limits.contact_reach : 2.0 * a_max;
  for (int a = 0; a < 3; ++a) {
    if (!box.periodic[a]) continue;
    const double L = box.length(a);
    if (L < 2.0 * reach)
      throw InputError(packing.source + ": periodic " + axis_name(a) + " length " + num(L) +
                       " is less than twice the largest contact reach " + num(reach) +
                       " (a pair would touch through two images; allowed: >= " + num(2.0 * reach) + ")");
    if (L < 6.0 * a_max)
      throw InputError(packing.source + ": periodic " + axis_name(a) + " length " + num(L) +
                       " is less than three largest diameters " + num(6.0 * a_max) +
                       " (YADE's periodic cell needs them; allowed: >= " + num(6.0 * a_max) + ")");
  }
  std::vector<Touch> touches = touching_pairs(packing);
  for (const auto& t : touches) {
    const double smaller = std::min(ps[t.i].radius, ps[t.j].radius);
    if (t.overlap > limits.max_overlap * smaller)
      throw InputError(where(packing, ps[t.i]) + " and particle id " + std::to_string(ps[t.j].id) +
                       (ps[t.j].line ? " (line " + std::to_string(ps[t.j].line) + ")" : std::string()) +
                       " overlap by " + num(t.overlap) + ", " + num(t.overlap / smaller) +
                       " of the smaller radius (allowed: <= max_overlap = " + num(limits.max_overlap) + ")");
  }
  if (limits.touching) *limits.touching = std::move(touches);
}

}  // namespace granwave::packing
