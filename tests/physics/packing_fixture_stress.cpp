// The fixtures' contacts against the codes that made them: the Love-Weber stress of the pairs the
// importer finds, with each code's contact stiffness, equals the stress that code reported when it
// wrote the file (LAMMPS' thermo pressure, YADE's PeriTriaxController stress). This checks the
// import (units, wrapping, periodic images), the contact search and the overlaps at once.
#include <catch2/catch.hpp>
#include <array>
#include <cmath>
#include <functional>
#include <string>

#include "packing/contacts.hpp"
#include "packing/importers.hpp"
#include "../packing_fixtures.hpp"

using namespace granwave::packing;

namespace {
// Diagonal of (1/V) sum over contacts of f_n n (x) l, with f_n = kn(a_i, a_j) overlap and
// l = |x_j - x_i| n the branch vector (normal forces only: both preparations were frictionless).
std::array<double, 3> love_stress(const Packing& p, const std::function<double(double, double)>& kn) {
  std::array<double, 3> s{};
  for (const Touch& t : touching_pairs(p)) {
    const Particle& a = p.particles[t.i];
    const Particle& b = p.particles[t.j];
    Vec3 d = b.centre - a.centre;
    double* dc[3] = {&d.vx, &d.vy, &d.vz};
    for (int k = 0; k < 3; ++k) *dc[k] -= std::round(*dc[k] / p.box.length(k)) * p.box.length(k);
    const double dist = d.norm();
    const double f = kn(a.radius, b.radius) * t.overlap;
    for (int k = 0; k < 3; ++k) s[k] += f * (*dc[k]) * (*dc[k]) / dist;
  }
  for (double& v : s) v /= p.box.volume();
  return s;
}
}  // namespace

TEST_CASE("lammps_periodic: the contacts give LAMMPS' pressure", "[packing][fixture]") {
  const Packing p = read_lammps_data(fixtures::path("lammps_periodic/packing.data"), "si", "p p p");
  // make.lmp: pair_style gran/hooke with kn = 1000 N/m for every pair. log.lammps, step 125000
  // (write_data's): Press 5190.9151 Pa, with the kinetic part (KE 1.8e-9 J: 5e-4 Pa) and the
  // dashpots of moving rattlers, both far below the tolerance.
  const auto s = love_stress(p, [](double, double) { return 1000.0; });
  CHECK((s[0] + s[1] + s[2]) / 3.0 == Approx(5190.9151).epsilon(1e-4));
}

TEST_CASE("yade_periodic: the contacts give YADE's cell stress on each axis", "[packing][fixture]") {
  const Packing p = fixtures::yade_periodic();
  // make.py: FrictMat E = 1e8 Pa, so Ip2_FrictMat_FrictMat_FrictPhys gives kn = 2 E a_i a_j / (a_i + a_j).
  // log.txt, "goal reached": stress (-99940.45, -100006.91, -100077.02) Pa (compression negative),
  // one step before the export.
  // The text keeps 6 digits of each centre (1e-7 m of overlaps near 2e-6 m): 1e-3 relative.
  const auto s = love_stress(p, [](double a, double b) { return 2e8 * a * b / (a + b); });
  CHECK(s[0] == Approx(99940.45).epsilon(1e-3));
  CHECK(s[1] == Approx(100006.91).epsilon(1e-3));
  CHECK(s[2] == Approx(100077.02).epsilon(1e-3));
}
