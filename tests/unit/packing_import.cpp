// The importers of other codes' packing files (src/packing): what each format gives, and one test
// per defect that must stop a run with an InputError naming the file, the line and the particle.
#include <catch2/catch.hpp>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <string>

#include "core/error.hpp"
#include "packing/importers.hpp"

using namespace granwave;
using namespace granwave::packing;
using Catch::Contains;

namespace {
std::string write(const std::string& name, const std::string& text) {
  const auto path = (std::filesystem::temp_directory_path() / ("granwave_packing_" + name)).string();
  std::ofstream(path) << text;
  return path;
}

// Eight spheres of radius 0.5 on a cubic grid of spacing 1.0 in a 4 x 4 x 4 box: touching nobody.
std::string dump_text(const std::string& flags, const std::string& columns, const std::string& rows) {
  return "ITEM: TIMESTEP\n100\nITEM: NUMBER OF ATOMS\n" +
         std::to_string(std::count(rows.begin(), rows.end(), '\n')) + "\nITEM: BOX BOUNDS " + flags +
         "\n0 4\n0 4\n0 4\nITEM: ATOMS " + columns + "\n" + rows;
}

Box cube(double L, bool z_periodic = true) {
  Box b;
  b.hi = {L, L, L};
  b.periodic = {true, true, z_periodic};
  return b;
}

std::string data_text(const std::string& atoms, int n, const std::string& extra_header = "") {
  return "LAMMPS data file via write_data\n\n" + std::to_string(n) + " atoms\n1 atom types\n\n0 4 xlo xhi\n0 4 ylo yhi\n"
         "0 4 zlo zhi\n" + extra_header + "\nAtoms # sphere\n\n" + atoms;
}
}  // namespace

TEST_CASE("LAMMPS data file: sphere rows, units to SI, velocities, image flags", "[packing][import]") {
  const std::string atoms = "7 2 1.0 2.5 0.5 0.5 0.5 0 0 0\n3 1 0.9 2.5 1.5 2.5 3.5 1 0 -1\n";
  const auto path = write("data_cgs.data", data_text(atoms, 2) + "\nVelocities\n\n3 1 2 3 0 0 0\n7 0 0 -4 0 0 0\n");
  const Packing p = read_lammps_data(path, "cgs", "p p f");
  REQUIRE(p.particles.size() == 2);
  CHECK(p.box.hi[2] == Approx(0.04));
  CHECK(p.box.periodic[0]);
  CHECK(!p.box.periodic[2]);
  const Particle& a = p.particles[0];
  CHECK(a.id == 7);
  CHECK(a.type == 2);
  CHECK(a.radius == Approx(0.005));                  // 1.0 cm diameter
  CHECK(a.density == Approx(2500.0));                // 2.5 g/cm^3
  CHECK(std::isnan(a.mass));
  CHECK(a.centre.z() == Approx(0.005));
  REQUIRE(a.velocity);
  CHECK(a.velocity->z() == Approx(-0.04));          // cm/s
  CHECK(p.particles[1].velocity->x() == Approx(0.01));
  CHECK(p.particles[1].line == 13);
}

TEST_CASE("LAMMPS dump: the last snapshot, scaled and unwrapped coordinates, wrapped into a periodic box",
          "[packing][import]") {
  const std::string first = dump_text("pp pp pp", "id radius x y z", "1 0.5 9 9 9\n");
  const std::string last = dump_text("pp pp ff", "id type diameter xu yu zu vx vy vz",
                                     "1 1 1.0 -0.5 4.5 0.5 1 2 3\n2 1 1.0 2.0 2.0 2.0 0 0 0\n");
  const Packing p = read_lammps_dump(write("dump_unwrapped.dump", first + last), "si");
  REQUIRE(p.particles.size() == 2);
  CHECK(p.particles[0].centre.x() == Approx(3.5));   // -0.5 wrapped
  CHECK(p.particles[0].centre.y() == Approx(0.5));   // 4.5 wrapped
  CHECK(p.particles[0].radius == Approx(0.5));
  CHECK(p.particles[0].velocity->y() == Approx(2.0));
  CHECK(p.box.z_walls());
  CHECK(p.particles[0].line == 20);

  const Packing s = read_lammps_dump(
      write("dump_scaled.dump", dump_text("pp pp pp", "id radius xs ys zs", "5 0.5 0.125 1.1 -0.25\n")), "micro");
  CHECK(s.particles[0].centre.x() == Approx(0.5e-6));
  CHECK(s.particles[0].centre.y() == Approx(0.4e-6));  // 1.1 of the box, wrapped
  CHECK(s.particles[0].centre.z() == Approx(3.0e-6));
  CHECK(s.particles[0].radius == Approx(0.5e-6));
}

TEST_CASE("LAMMPS dump: ITEM: UNITS and ITEM: TIME of dump_modify, units checked", "[packing][import]") {
  const std::string body = "ITEM: TIME\n0.5\nITEM: TIMESTEP\n100\nITEM: NUMBER OF ATOMS\n1\nITEM: BOX BOUNDS pp pp pp\n"
                           "0 4\n0 4\n0 4\nITEM: ATOMS id radius x y z\n1 0.5 1 1 1\n";
  const auto path = write("dump_units.dump", "ITEM: UNITS\ncgs\n" + body);
  CHECK(read_lammps_dump(path, "cgs").box.hi[0] == Approx(0.04));
  REQUIRE_THROWS_WITH(read_lammps_dump(path, "si"), Contains(path + ":2: the dump says units \"cgs\", the caller \"si\""));
}

TEST_CASE("YADE text export: the format line, comments, ids by order or from the file", "[packing][import]") {
  const Packing p = read_yade_text(write("yade.txt", "#format x_y_z_r\n# a comment\n0.5\t0.5\t0.5\t0.5\n"
                                                     "4.5\t2.5\t2.5\t0.4\n"), cube(4.0));
  REQUIRE(p.particles.size() == 2);
  CHECK(p.particles[0].id == 0);  // YADE's body ids start at 0
  CHECK(p.particles[1].centre.x() == Approx(0.5));
  CHECK(p.particles[1].radius == Approx(0.4));
  const Packing q =
      read_yade_text(write("yade_ids.txt", "#format id_x_y_z_r_matId\n12\t1\t1\t1\t0.5\t3\n"), cube(4.0));
  CHECK(q.particles[0].id == 12);
  CHECK(q.particles[0].type == 3);
}

TEST_CASE("x y z r table: the box from the caller, 1-based ids", "[packing][import]") {
  const Packing p = read_xyzr_table(write("table.txt", "# x y z r\n1 1 1 0.5\n3 3 3.4 0.5\n"), cube(4.0, false));
  REQUIRE(p.particles.size() == 2);
  CHECK(p.particles[1].id == 2);
  CHECK(p.particles[1].centre.z() == Approx(3.4));
}

TEST_CASE("defect: a particle outside a non-periodic box", "[packing][import][defect]") {
  const auto path = write("outside.dump", dump_text("pp pp ff", "id radius x y z", "1 0.5 1 1 1\n2 0.5 2 2 4.2\n"));
  REQUIRE_THROWS_MATCHES(read_lammps_dump(path, "si"), InputError,
                         Catch::Matchers::Message(path + ":11, particle id 2: centre z = 4.2 is outside the "
                                                  "non-periodic box [0, 4] (allowed: inside; only a periodic axis wraps)"));
  // A sphere through a z wall by more than the overlap bound.
  const auto deep = write("through_wall.txt", "1 1 0.2 0.5\n");
  REQUIRE_THROWS_WITH(read_xyzr_table(deep, cube(4.0, false)),
                      Contains(deep + ":1, particle id 1") && Contains("through the z wall"));
}

TEST_CASE("defect: NaN or infinite numbers", "[packing][import][defect]") {
  const auto path = write("nan.txt", "1 1 1 0.5\n2 nan 2 0.5\n");
  REQUIRE_THROWS_WITH(read_xyzr_table(path, cube(4.0)),
                      Contains(path + ":2") && Contains("\"nan\" is not a finite number"));
  const auto inf = write("inf.data", data_text("1 1 1.0 2500 inf 1 1\n", 1));
  REQUIRE_THROWS_WITH(read_lammps_data(inf, "si", "p p p"), Contains(inf + ":12") && Contains("x \"inf\""));
}

TEST_CASE("defect: a negative or zero radius", "[packing][import][defect]") {
  const auto neg = write("negative.txt", "#format x_y_z_r\n1 1 1 -0.5\n");
  REQUIRE_THROWS_WITH(read_yade_text(neg, cube(4.0)),
                      Contains(neg + ":2, particle id 0: radius") && Contains("allowed: radius > 0"));
  const auto zero = write("zero.dump", dump_text("pp pp pp", "id diameter x y z", "4 0 1 1 1\n"));
  REQUIRE_THROWS_WITH(read_lammps_dump(zero, "si"), Contains(zero + ":10, particle id 4: radius"));
}

TEST_CASE("defect: duplicate ids", "[packing][import][defect]") {
  const auto path = write("duplicate.data", data_text("5 1 1.0 2500 1 1 1\n5 1 1.0 2500 3 3 3\n", 2));
  REQUIRE_THROWS_WITH(read_lammps_data(path, "si", "p p p"),
                      Contains(path + ":13, particle id 5: duplicate id, already on line 12"));
}

TEST_CASE("defect: an overlap above the bound", "[packing][import][defect]") {
  // Centres 0.9 apart, radii 0.5 and 0.6: overlap 0.2 = 0.4 of the smaller radius.
  const auto path = write("overlap.txt", "1 1 1 0.5\n1.9 1 1 0.6\n");
  REQUIRE_THROWS_WITH(read_xyzr_table(path, cube(4.0)),
                      Contains(path + ":1, particle id 1 and particle id 2 (line 2) overlap by 0.2") &&
                          Contains("0.4 of the smaller radius"));
  // The same pair across the periodic face, and accepted under a looser bound.
  const auto across = write("overlap_across.txt", "0.1 1 1 0.5\n3.2 1 1 0.6\n");
  REQUIRE_THROWS_WITH(read_xyzr_table(across, cube(4.0)), Contains("overlap by 0.2"));
  Limits loose;
  loose.max_overlap = 0.5;
  CHECK(read_xyzr_table(across, cube(4.0), loose).particles.size() == 2);
}

TEST_CASE("defect: a periodic box too short for the cell list", "[packing][import][defect]") {
  // 3.5 diameters pass YADE's three but not twice a contact reach of two diameters.
  const auto path = write("short_reach.txt", "1 1 1 0.5\n");
  Limits long_reach;
  long_reach.contact_reach = 2.0;
  REQUIRE_THROWS_WITH(read_xyzr_table(path, cube(3.5), long_reach),
                      Contains(path + ": periodic x length 3.5 is less than twice the largest contact reach 2"));
  CHECK_NOTHROW(read_xyzr_table(path, cube(4.0), long_reach));
}

TEST_CASE("defect: a periodic box shorter than YADE's three diameters", "[packing][import][defect]") {
  const auto path = write("short_yade.txt", "1 1 1 0.5\n");
  REQUIRE_THROWS_WITH(read_xyzr_table(path, cube(2.5)),
                      Contains("periodic x length 2.5 is less than three largest diameters 3"));
  CHECK_NOTHROW(read_xyzr_table(path, cube(3.0)));
}

TEST_CASE("defect: an unreadable format", "[packing][import][defect]") {
  const auto text = write("garbage.txt", "hello world\n");
  REQUIRE_THROWS_WITH(read_lammps_dump(text, "si"), Contains(text + ": no \"ITEM: TIMESTEP\" line"));
  REQUIRE_THROWS_WITH(read_lammps_data(text, "si", "p p p"), Contains(text + ": no \"N atoms\" line"));
  REQUIRE_THROWS_WITH(read_yade_text(text, cube(4.0)), Contains(text + ":1: 2 values where format x_y_z_r has 4"));
  REQUIRE_THROWS_WITH(read_xyzr_table(text, cube(4.0)), Contains(text + ":1: 2 values (allowed: four"));
  REQUIRE_THROWS_WITH(read_xyzr_table(text + ".missing", cube(4.0)), Contains("cannot open the packing file"));
  const auto other_style = write("atomic.data", "LAMMPS data\n\n1 atoms\n0 4 xlo xhi\n0 4 ylo yhi\n0 4 zlo zhi\n\n"
                                                "Atoms # atomic\n\n1 1 1 1 1\n");
  REQUIRE_THROWS_WITH(read_lammps_data(other_style, "si", "p p p"), Contains("allowed: atom_style sphere"));
  const auto no_radius = write("no_radius.dump", dump_text("pp pp pp", "id x y z", "1 1 1 1\n"));
  REQUIRE_THROWS_WITH(read_lammps_dump(no_radius, "si"), Contains("neither a radius nor a diameter"));
  const auto yade_other = write("yade_attrs.txt", "#format x_y_z_r_attrs\n1 1 1 0.5 7\n");
  REQUIRE_THROWS_WITH(read_yade_text(yade_other, cube(4.0)), Contains("format x_y_z_r_attrs not supported"));
  const auto count = write("count.dump", dump_text("pp pp pp", "id radius x y z", "1 0.5 1 1 1\n") + "2 0.5 3 3 3\n");
  REQUIRE_THROWS_WITH(read_lammps_dump(count, "si"), Contains("the snapshot says 1 atoms, its ATOMS item has 2"));
}

TEST_CASE("defect: a lateral (x or y) wall", "[packing][import][defect]") {
  const auto path = write("lateral.dump", dump_text("pp ff pp", "id radius x y z", "1 0.5 1 1 1\n"));
  REQUIRE_THROWS_WITH(read_lammps_dump(path, "si"),
                      Contains(path + ": the box is not periodic in y: lateral walls are not supported"));
  const auto data = write("lateral.data", data_text("1 1 1.0 2500 1 1 1\n", 1));
  REQUIRE_THROWS_WITH(read_lammps_data(data, "si", "f p p"), Contains("not periodic in x"));
}

TEST_CASE("defect: lj and atomic units, an unknown boundary", "[packing][import][defect]") {
  const auto data = write("units.data", data_text("1 1 1.0 2500 1 1 1\n", 1));
  REQUIRE_THROWS_WITH(read_lammps_data(data, "lj", "p p p"),
                      Contains("units \"lj\" not supported (lj is reduced") && Contains("allowed: si, cgs, micro, nano"));
  REQUIRE_THROWS_WITH(read_lammps_data(data, "metal", "p p p"), Contains("an atomic unit style"));
  REQUIRE_THROWS_WITH(read_lammps_data(data, "si", "p p"), Contains("not three LAMMPS boundary words"));
  REQUIRE_THROWS_WITH(read_lammps_data(data, "si", "p p q"), Contains("not three LAMMPS boundary words"));
}

TEST_CASE("defect: a triclinic box", "[packing][import][defect]") {
  const auto dump = write("triclinic.dump", "ITEM: TIMESTEP\n0\nITEM: NUMBER OF ATOMS\n1\nITEM: BOX BOUNDS xy xz yz pp pp pp\n"
                                            "0 4 0\n0 4 0\n0 4 0\nITEM: ATOMS id radius x y z\n1 0.5 1 1 1\n");
  REQUIRE_THROWS_WITH(read_lammps_dump(dump, "si"), Contains(dump + ":5: a triclinic box"));
  const auto data = write("triclinic.data", data_text("1 1 1.0 2500 1 1 1\n", 1, "0 0 0 xy xz yz\n"));
  REQUIRE_THROWS_WITH(read_lammps_data(data, "si", "p p p"), Contains(data + ":9: a triclinic box"));
}
