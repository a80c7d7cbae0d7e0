// Issue 39 item 2: the static probe (crystal/probe.hpp) - the simulation's own kernel strains a
// packing by +-1e-7, FIRE relaxes it under the full contact law, and the nominal stress's change must
// equal the relaxed slab tensor A_relaxed (theory/relaxed_moduli.hpp, with the initial-stress term) to
// 1e-4 relative, column by column. Two independent routes: the linearised network solved by a sparse
// LDL^T against the nonlinear law integrated and relaxed. On the FCC with tangential springs and the
// contact-point arm (the rotations relax under zx), on a relaxed polydisperse FCC (translations relax
// too), and on the YADE packing of data/packings (a disordered packing from a file, slabs by role);
// the box strains xx, yy and yx (a sheared box) with tangential springs stretched across its faces.
#include <catch2/catch.hpp>
#include <cstdio>
#include <string>
#include <vector>

#include "../case_text.hpp"
#include "config/case.hpp"
#include "crystal/derive.hpp"
#include "crystal/packing.hpp"
#include "crystal/probe.hpp"
#include "crystal/relaxed_inputs.hpp"
#include "theory/relaxed_moduli.hpp"

using namespace granwave;

namespace {

config::Case case_text(const std::string& file, const std::string& from, const std::string& to) {
  return config::parse_case(test_support::case_text(file, {{from, to}}), std::string(GRANWAVE_SOURCE_DIR) + "/" + file);
}

using S = crystal::ProbeStrain;

// The strains given; returns the largest relative error.
double probe_all(const config::Case& c, const char* label, const std::vector<S>& strains) {
  const crystal::Packing pk = crystal::make_packing(c);
  const theory::ContactNetwork net = crystal::contact_network(c, pk);
  const theory::RelaxedModuli th = theory::relaxed_moduli(net, crystal::relaxed_slab_options(c, pk));
  REQUIRE(th.unstable_modes == 0);
  crystal::ProbeOptions opt;  // amplitude 1e-7, tolerance 1e-6
  const crystal::StaticProbe probe(c, pk, net, th.volume, opt);
  double worst = 0.0;
  for (const auto s : strains) {
    const auto r = probe.run(s);
    const auto [g, f] = crystal::probe_strain_indices(s);
    Eigen::Matrix3d A;
    for (int a = 0; a < 3; ++a)
      for (int b = 0; b < 3; ++b) A(a, b) = th.relaxed(a, b, g, f);
    const double err = (r.dP - A).cwiseAbs().maxCoeff() / A.cwiseAbs().maxCoeff();
    std::printf("%s %s: dP %.9g Pa, A_relaxed %.9g Pa (affine %.9g), error %.2e, FIRE %ld/%ld, max slip %.1e, "
                "contacts changed %d\n",
                label, crystal::probe_strain_name(s), r.dP(g, f), A(g, f), th.affine(g, f, g, f), err, r.steps_plus,
                r.steps_minus, r.max_slip, r.contacts_changed);
    CHECK(err < 1e-4);
    CHECK(r.sliding == 0);  // no contact at the Coulomb limit: the linear theory's sticking holds
    CHECK(r.contacts_changed == 0);
    worst = std::max(worst, err);
  }
  return worst;
}

}  // namespace

TEST_CASE("Static probe = relaxed slab tensor: FCC with tangential springs and rotations", "[theory][probe]") {
  const config::Case c = case_text("data/cases/crystal_kt10.toml", "cells = [4, 4, 200]", "cells = [4, 4, 12]");
  probe_all(c, "crystal_kt10 4x4x12", {S::zz, S::zx, S::xx, S::yy, S::yx});
}

TEST_CASE("Static probe = relaxed slab tensor: relaxed polydisperse FCC", "[theory][probe]") {
  const config::Case c = case_text("data/cases/crystal_poly1.toml", "cells = [4, 4, 200]", "cells = [4, 4, 12]");
  probe_all(c, "crystal_poly1 4x4x12", {S::zz, S::zx, S::xx, S::yx});
}

TEST_CASE("Static probe = relaxed slab tensor: the YADE packing from a file", "[theory][probe]") {
  const config::Case c = config::load_case(std::string(GRANWAVE_SOURCE_DIR) + "/tests/crosscheck/cases/packing_yade_p.toml");
  probe_all(c, "packing_yade_p", {S::zz, S::zx, S::xx, S::yx});
}

TEST_CASE("Static probe = relaxed slab tensor: the YADE packing with tangential springs and friction", "[theory][probe]") {
  // kt = kn with the contact-point arm and mu = 0.5: rotations and tangential springs relax too.
  config::Case c = case_text("tests/crosscheck/cases/packing_yade_p.toml", "kt = 0.0\ngamma_t = 0.0\nmu_static = 0.0\nmu_dynamic = 0.0",
                             "kt = 5e4\ngamma_t = 0.0\nmu_static = 0.5\nmu_dynamic = 0.5\nlever_arm = \"contact_point\"");
  probe_all(c, "packing_yade_p with kt = kn, mu = 0.5", {S::zz, S::zx, S::xx, S::yy, S::yx});
}
