// Issue 39 item 1 for packings from files: the bulk of a file's packing is its own triply periodic
// packing relaxed under the case's law (crystal/relaxed_inputs.hpp), not the cut one closed again.
// An FCC crystal written as an x y z r table with its periodic box and imported must give the bulk
// relaxed tensor of the crystal granwave builds (closed across z), whose identity with the lattice
// dynamics' long waves tests/physics/theory_relaxed_packings.cpp checks to 1e-6: the same tensor
// through the importer, the z-periodic relaxation (at rest already: no step) and its network.
#include <catch2/catch.hpp>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>

#include "config/case.hpp"
#include "crystal/derive.hpp"
#include "crystal/packing.hpp"
#include "crystal/relaxed_inputs.hpp"
#include "theory/relaxed_moduli.hpp"

using namespace granwave;

TEST_CASE("FCC from a file: periodic bulk relaxed moduli = the built crystal's", "[theory][relaxed]") {
  std::ifstream in(std::string(GRANWAVE_SOURCE_DIR) + "/data/cases/crystal_kt10.toml");
  std::stringstream text;
  text << in.rdbuf();
  std::string fcc_text = text.str();
  const std::string from = "cells = [4, 4, 200]";
  fcc_text.replace(fcc_text.find(from), from.size(), "cells = [4, 4, 12]");
  const config::Case fcc = config::parse_case(fcc_text, "crystal_kt10_small");
  const crystal::Packing pk = crystal::make_packing(fcc);

  // The built crystal's bulk, closed across z (layers one spacing apart: an even count closes ABAB).
  const theory::ContactNetwork net = crystal::contact_network(fcc, pk);
  std::vector<theory::Vec3> centres;
  for (std::size_t p = 0; p < pk.size(); ++p) centres.emplace_back(pk.x[p], pk.y[p], pk.z[p]);
  const double box_z = pk.layers * pk.l0;
  theory::RelaxedOptions bulk;
  bulk.contact = crystal::lattice_options(fcc, 1e-6);
  bulk.boundary = theory::RelaxedBoundary::bulk;
  bulk.box_z = box_z;
  const auto closed = theory::periodic_in_z(net, centres, box_z, [&](int i, int j, const theory::Vec3&, double overlap) {
    const auto k = crystal::contact_between(fcc, pk.radius[i], pk.radius[j], overlap);
    theory::NetworkContact nc;
    nc.normal_force = k.f_n, nc.k = k.kn, nc.kt = k.kt;
    return nc;
  });
  const auto built = theory::relaxed_moduli(closed, bulk);

  // The same crystal as a file: x y z r, the box from the lattice, z from half a spacing below layer 0.
  const auto dir = std::filesystem::temp_directory_path() / "granwave_theory_file_bulk";
  std::filesystem::create_directories(dir);
  const auto table = dir / "fcc.xyzr";
  {
    std::ofstream out(table);
    out.precision(17);
    for (std::size_t p = 0; p < pk.size(); ++p) out << pk.x[p] << ' ' << pk.y[p] << ' ' << pk.z[p] << ' ' << pk.radius[p] << '\n';
  }
  const double z_lo = pk.z[0] - 0.5 * pk.l0;
  std::ostringstream file_case;
  file_case.precision(17);
  const auto contact = fcc_text.substr(fcc_text.find("[contact]"), fcc_text.find("[excitation]") - fcc_text.find("[contact]"));
  file_case << "[case]\nname = \"fcc_file\"\nmodel = \"crystal\"\n[crystal]\nlattice = \"file\"\ndensity = 2000\n[packing]\n"
            << "file = \"" << table.string() << "\"\nformat = \"xyzr\"\nbox = [[0.0, " << pk.box_x << "], [0.0, " << pk.box_y
            << "], [" << z_lo << ", " << z_lo + box_z << "]]\nsource_thickness = " << 2.5 * pk.l0 << "\n"
            << contact << "[excitation]\nmode = \"P\"\n[integrator]\ndt = 2e-7\nt_end = 1e-5\n";
  const config::Case c = config::parse_case(file_case.str(), (dir / "fcc_file.toml").string());
  const crystal::PeriodicBulk pb = crystal::periodic_bulk(c);
  std::printf("file FCC: %zu contacts, %ld FIRE steps, unbalanced %.1e; built: %zu contacts\n", pb.net.contacts.size(),
              pb.steps, pb.unbalanced, closed.contacts.size());
  CHECK(pb.steps == 0);  // an FCC at its overlap is at rest
  CHECK(pb.box_z == Approx(box_z).epsilon(1e-14));
  CHECK(pb.net.contacts.size() == closed.contacts.size());
  theory::RelaxedOptions fb = bulk;
  fb.box_z = pb.box_z;
  const auto file = theory::relaxed_moduli(pb.net, fb);
  CHECK(file.rattlers == 0);
  CHECK(file.unstable_modes == 0);
  double diff = 0.0, scale = 0.0;
  for (int i = 0; i < 81; ++i) {
    diff = std::max(diff, std::abs(file.relaxed.data()[i] - built.relaxed.data()[i]));
    scale = std::max(scale, std::abs(built.relaxed.data()[i]));
  }
  std::printf("file FCC bulk: V_pz %.9f V_sz %.9f (built %.9f %.9f), tensor difference %.2e\n", file.V_pz, file.V_sz,
              built.V_pz, built.V_sz, diff / scale);
  CHECK(diff / scale < 1e-9);
  CHECK(file.V_sz < file.V_sz_affine);  // the rotations relax S
  std::filesystem::remove_all(dir);
}
