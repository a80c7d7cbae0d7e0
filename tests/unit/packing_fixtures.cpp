// The packings of data/packings, made by LAMMPS, LIGGGHTS and YADE (each with its script and log),
// read back by the importers: count, box, radii, a particle named in the file, and that each is
// jammed (touching pairs and a solid fraction near random close packing).
#include <catch2/catch.hpp>
#include <cmath>
#include <map>
#include <string>

#include "packing/contacts.hpp"
#include "packing/importers.hpp"
#include "../packing_fixtures.hpp"

using namespace granwave::packing;

namespace {
// Radii made uniform in r0 (1 +- 0.15) with r0 = 0.5 mm, all three scripts.
void check_radii_and_jamming(const Packing& p, double phi_lo, double phi_hi) {
  const PackingStats s = measure(p);
  CHECK(s.r_min >= 0.85 * 5e-4 * (1 - 1e-9));
  CHECK(s.r_max <= 1.15 * 5e-4 * (1 + 1e-9));
  CHECK(s.r_min < 0.87 * 5e-4);  // the whole range is drawn
  CHECK(s.r_max > 1.13 * 5e-4);
  CHECK(s.solid_fraction > phi_lo);
  CHECK(s.solid_fraction < phi_hi);
  // Jammed frictionless spheres: isostatic at 6 contacts per non-rattler, more when compressed.
  CHECK(s.mean_coordination_nonrattler > 5.5);
  CHECK(s.rattlers < s.particles / 5);
  CHECK(s.max_overlap < 0.05);
}
}  // namespace

TEST_CASE("fixture lammps_periodic: data file and custom dump of the same packing", "[packing][fixture]") {
  const Packing data = read_lammps_data(fixtures::path("lammps_periodic/packing.data"), "si", "p p p");
  REQUIRE(data.particles.size() == 3000);
  for (int a = 0; a < 3; ++a) {
    CHECK(data.box.lo[a] == 0.0);
    CHECK(data.box.hi[a] == 0.0134848865771451);
    CHECK(data.box.periodic[a]);
  }
  const Particle& first = data.particles[0];  // the first Atoms row
  CHECK(first.id == 1826);
  CHECK(first.radius == 0.5 * 0.0010002068340778352);
  CHECK(first.density == 2500.0);
  CHECK(first.centre.x() == 0.00023954042278858894);
  CHECK(first.centre.z() == 0.0005369899327610281);
  REQUIRE(first.velocity);
  CHECK(first.velocity->y() == 0.00316322428493666);
  check_radii_and_jamming(data, 0.64, 0.67);

  const Packing dump = read_lammps_dump(fixtures::path("lammps_periodic/packing.dump"), "si");
  REQUIRE(dump.particles.size() == 3000);
  CHECK(dump.box.hi[1] == Approx(0.0134848865771451).epsilon(1e-15));
  std::map<std::int64_t, const Particle*> by_id;
  for (const auto& p : data.particles) by_id[p.id] = &p;
  for (const auto& p : dump.particles) {  // 12 significant digits of the scaled coordinates
    const Particle& q = *by_id.at(p.id);
    REQUIRE((p.centre - q.centre).norm() < 1e-11 * 0.0135 * 3);
    REQUIRE(p.radius == Approx(q.radius).epsilon(1e-11));
  }
}

TEST_CASE("fixture liggghts_periodic: custom dump", "[packing][fixture]") {
  const Packing p = read_lammps_dump(fixtures::path("liggghts_periodic/packing.dump"), "si");
  REQUIRE(p.particles.size() == 2000);
  CHECK(p.box.periodic == std::array<bool, 3>{true, true, true});
  // LIGGGHTS writes the bounds with 6 digits: the deck's box edge was 0.0118639681699891 m.
  CHECK(p.box.lo[0] == 0.0);
  CHECK(p.box.hi[2] == 0.011864);
  const Particle& first = p.particles[0];  // "1892 1 0.000483905853647 0.000131271228764 ..."
  CHECK(first.id == 1892);
  CHECK(first.radius == 0.000483905853647);
  CHECK(first.centre.x() == 0.000131271228764);
  CHECK(first.centre.z() == 0.000580215111537);
  CHECK(std::isnan(first.density));  // the dump has no density column
  check_radii_and_jamming(p, 0.63, 0.66);
}

TEST_CASE("fixture yade_periodic: yade.export.text with the cell the script wrote", "[packing][fixture]") {
  const Packing p = fixtures::yade_periodic();
  REQUIRE(p.particles.size() == 2000);
  const Particle& first = p.particles[0];  // "0.000712096	0.00798192	0.00244498	0.000574963"
  CHECK(first.id == 0);
  CHECK(first.centre.y() == 0.00798192);
  CHECK(first.radius == 0.000574963);
  check_radii_and_jamming(p, 0.63, 0.66);
  // YADE's own avgNumInteractions at export (log.txt): 6.231. The text keeps 6 digits, so a
  // few pairs at the edge of contact may go either way.
  CHECK(measure(p).mean_coordination == Approx(6.231).margin(0.01));
}

TEST_CASE("fixture lammps_tall: the two columns' custom dumps", "[packing][fixture]") {
  // 100 mean diameters tall, 5 and 7 wide (data/packings/README.md: its table's numbers, by the same rule).
  const Packing w5 = read_lammps_dump(fixtures::path("lammps_tall/packing_w5.dump"), "si");
  REQUIRE(w5.particles.size() == 3060);
  CHECK(w5.box.periodic == std::array<bool, 3>{true, true, true});
  CHECK(w5.box.hi[0] == 5.0007754817862904e-03);
  CHECK(w5.box.hi[2] == 1.0001550963572600e-01);
  const Particle& first = w5.particles[0];  // "1085 1 0.00112447752953 0.242876685174 ..."
  CHECK(first.id == 1085);
  CHECK(first.radius == 0.5 * 0.00112447752953);
  CHECK(first.centre.x() == Approx(0.242876685174 * 5.0007754817862904e-03).epsilon(1e-14));
  check_radii_and_jamming(w5, 0.64, 0.67);
  const PackingStats s5 = measure(w5);
  CHECK(s5.solid_fraction == Approx(0.6544).margin(5e-5));
  CHECK(s5.mean_coordination == Approx(6.910).margin(5e-4));
  CHECK(s5.rattlers == 13);

  const Packing w7 = read_lammps_dump(fixtures::path("lammps_tall/packing_w7.dump"), "si");
  REQUIRE(w7.particles.size() == 6000);
  CHECK(w7.box.hi[1] == 7.0020194015957002e-03);
  CHECK(w7.particles[0].id == 747);
  check_radii_and_jamming(w7, 0.64, 0.67);
  const PackingStats s7 = measure(w7);
  CHECK(s7.solid_fraction == Approx(0.6541).margin(5e-5));
  CHECK(s7.mean_coordination == Approx(6.907).margin(5e-4));
  CHECK(s7.rattlers == 27);
}
