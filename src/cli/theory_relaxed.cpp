// `granwave theory`'s relaxed moduli and effective-medium estimate (theory_relaxed.hpp).
#include "cli/theory_relaxed.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <limits>
#include <numbers>

#include "cli/theory_json.hpp"
#include "config/contact_laws.hpp"
#include "core/error.hpp"
#include "crystal/relaxed_inputs.hpp"
#include "crystal/simulation.hpp"
#include "packing/packing.hpp"

namespace granwave::cli {
namespace {

Json moduli_json(const theory::RelaxedModuli& r) {
  return {{"boundary", theory::boundary_name(r.boundary)},
          {"V_pz", quantity(r.V_pz, "m/s")},
          {"V_sz", quantity(r.V_sz, "m/s")},
          {"V_sy", quantity(r.V_sy, "m/s")},
          {"V_pz_affine", quantity(r.V_pz_affine, "m/s")},
          {"V_sz_affine", quantity(r.V_sz_affine, "m/s")},
          {"rho", quantity(r.rho, "kg/m^3")},
          {"volume", quantity(r.volume, "m^3")},
          {"pressure", quantity(r.pressure, "Pa")},
          {"coordination", quantity(r.coordination, "1")},
          {"particles", r.particles},
          {"free_particles", r.free_particles},
          {"rattlers", r.rattlers},
          {"contacts", r.contacts},
          {"contacts_used", r.contacts_used},
          {"dof", r.dof},
          {"zero_modes",
           {{"free_rotations", r.free_rotation_modes},
            {"translations", r.translation_modes},
            {"mechanisms", r.mechanisms}}},
          {"unstable_modes", r.unstable_modes},
          {"sliding_contacts", r.sliding_contacts},
          {"forcing_on_zero_modes", r.forcing_on_zero_modes},
          {"unbalanced", r.unbalanced},
          {"residual", r.residual},
          {"A_relaxed", tensor_json(r.relaxed, "A[a][b][g][f]: a,g gradient, b,f displacement")}};
}

}  // namespace

RelaxedPart relaxed_part(const config::Case& c, const crystal::Packing& pk, const theory::ContactNetwork& net) {
  RelaxedPart R;
  theory::RelaxedOptions slab = crystal::relaxed_slab_options(c, pk);
  R.slab = theory::relaxed_moduli(net, slab);
  auto contact_of = [&](int i, int j, const theory::Vec3&, double overlap) {
    const auto k = crystal::contact_between(c, pk.radius[i], pk.radius[j], overlap);
    theory::NetworkContact nc;
    nc.normal_force = k.f_n, nc.k = k.kn, nc.kt = k.kt;
    return nc;
  };
  std::vector<theory::Vec3> centres;
  for (std::size_t p = 0; p < pk.size(); ++p) centres.emplace_back(pk.x[p], pk.y[p], pk.z[p]);

  if (pk.from_file()) {
    // The file's packing is triply periodic before crystal/file_packing.cpp cuts it: relaxed as such
    // under the case's normal law (crystal/periodic_bulk.hpp), every particle free.
    if (c.crystal->imported->box.z_walls()) {
      R.bulk_note = "omitted: the file's packing lies between z walls (not periodic in z)";
    } else if (pk.preparation_friction > 0.0) {
      // The bulk's relaxation is frictionless: it would let a packing that stands on its springs collapse.
      R.bulk_note = "omitted: the packing was prepared with friction and stands on its tangential springs; the "
                    "periodic bulk's relaxation is frictionless";
    } else try {
      const crystal::PeriodicBulk pb = crystal::periodic_bulk(c, 1e-10, 200000);
      theory::RelaxedOptions bulk = slab;
      bulk.prescribed.clear();
      bulk.boundary = theory::RelaxedBoundary::bulk;
      bulk.box_z = pb.box_z;
      R.bulk = theory::relaxed_moduli(pb.net, bulk);
      R.bulk_available = true;
      R.bulk_note = "the file's triply periodic packing (before the cut into slabs) relaxed by FIRE under the case's "
                    "normal law, every particle free, in " + std::to_string(pb.steps) + " steps";
    } catch (const RunError& e) {
      R.bulk_available = false;
      R.bulk_note = std::string("omitted: ") + e.what();
    }
  } else if (pk.layers % 2 != 0) {
    // The bulk: the network closed across z, the end layers' centres one mean layer spacing apart;
    // an ABAB stack closes only with an even number of layers.
    R.bulk_note = "omitted: an odd number of layers does not close the ABAB stack across z";
  } else {
    double zlo = 0.0, zhi = 0.0;
    int nlo = 0, nhi = 0;
    for (std::size_t p = 0; p < pk.size(); ++p) {
      if (pk.layer[p] == 0) zlo += pk.z[p], ++nlo;
      if (pk.layer[p] == pk.layers - 1) zhi += pk.z[p], ++nhi;
    }
    theory::RelaxedOptions bulk = slab;
    bulk.boundary = theory::RelaxedBoundary::bulk;
    bulk.box_z = (zhi / nhi - zlo / nlo) * pk.layers / (pk.layers - 1);
    const auto periodic = theory::periodic_in_z(net, centres, bulk.box_z, contact_of);
    R.bulk = theory::relaxed_moduli(periodic, bulk);
    R.bulk_available = true;
    R.bulk_note = pk.relaxed ? "closed across z through the fixed end layers, which were not relaxed against each other"
                             : "the crystal closed across z (its fixed layers are lattice layers)";
  }

  // The bulk unless its closure left no load-bearing network (every particle a rattler).
  const theory::RelaxedModuli& ref = R.bulk_available && R.bulk.contacts_used > 0 ? R.bulk : R.slab;
  R.Z = ref.coordination;
  R.phi = ref.rho / c.crystal->density;  // overlaps neglected
  if (pk.from_file()) {  // the file's masses may follow its own densities: the spheres' volume instead
    double v = 0.0;
    for (double a : pk.radius) v += 4.0 / 3.0 * std::numbers::pi * a * a * a;
    R.phi = v / ref.volume;
  }
  R.p = ref.pressure;
  const config::ContactLawInfo& law = config::law_of(c.contact);
  if (!(R.Z > 0.0)) {
    R.medium_model = "none: no load-bearing contacts";
    const double nan = std::numeric_limits<double>::quiet_NaN();
    R.medium = {nan, nan, nan, nan, nan};
  } else if (law.hertz_normal) {
    R.medium_model = "walton_hertz_mindlin";
    const double E = c.contact.number("youngs_modulus").value(), nu = c.contact.number("poisson_ratio").value();
    const double G_g = E / (2.0 * (1.0 + nu));
    R.medium = theory::walton_hertz_mindlin(R.Z, R.phi, G_g, nu, R.p, ref.rho);
  } else {
    R.medium_model = "linear_springs";
    R.medium = theory::affine_linear(R.Z, R.phi, c.crystal->radius, net.k, net.kt, ref.rho);
  }
  return R;
}

void add_relaxed_json(Json& o, const RelaxedPart& r) {
  Json rel = {{"note", "non-affine: free particles' translations and rotations relaxed under a homogeneous strain; "
                       "A_relaxed = A_affine - Xi^T H^+ Xi / V with the initial-stress term (rho V^2 = eigenvalues of "
                       "A_abgf m_a m_g); slab: fixed layers (a file's packing: its source and top slabs, every contact weighted 1, V = box_x box_y "
                       "L_z of the file) moved affinely; rattlers and zero modes removed, never "
                       "divided by; every contact treated as sticking"},
              {"slab", moduli_json(r.slab)}};
  if (r.bulk_available) {
    rel["bulk"] = moduli_json(r.bulk);
    rel["bulk"]["note"] = r.bulk_note;
  } else {
    rel["bulk"] = {{"available", false}, {"note", r.bulk_note}};
  }
  o["relaxed"] = rel;
  o["effective_medium"] = {
      {"label", "affine estimate"},
      {"model", r.medium_model},
      {"note", r.medium_model == "walton_hertz_mindlin"
                   ? "Walton 1987 / Digby 1981: K = [Z^2 phi^2 G^2 p/(18 pi^2 (1-nu)^2)]^(1/3), G = (3/5) K (5-4nu)/(2-nu) "
                     "(rough), G_smooth = (3/5) K; isotropic contacts, every contact strained affinely"
                   : "linear springs, isotropic contacts strained affinely: K = Z phi k_n/(6 pi R), G = Z phi (2 k_n + 3 "
                     "k_t)/(20 pi R), G_smooth = Z phi k_n/(10 pi R)"},
      {"Z", quantity(r.Z, "1")},
      {"phi", quantity(r.phi, "1")},
      {"p", quantity(r.p, "Pa")},
      {"K", quantity(r.medium.K, "Pa")},
      {"G", quantity(r.medium.G, "Pa")},
      {"G_smooth", quantity(r.medium.G_smooth, "Pa")},
      {"V_p", quantity(r.medium.V_p, "m/s")},
      {"V_s", quantity(r.medium.V_s, "m/s")}};
}

void print_relaxed(const RelaxedPart& r) {
  auto line = [](const theory::RelaxedModuli& m) {
    std::printf("relaxed (%s, non-affine): V_pz = %.4f m/s, V_sz = %.4f m/s, V_sy = %.4f m/s (affine %.4f, %.4f); "
                "p = %.6g Pa, Z = %.4f\n",
                theory::boundary_name(m.boundary), m.V_pz, m.V_sz, m.V_sy, m.V_pz_affine, m.V_sz_affine, m.pressure,
                m.coordination);
    std::printf("  rattlers %d, zero modes: %d free rotations, %d translations, %d mechanisms; unstable %d; sliding "
                "contacts %d (treated as sticking); unbalanced %.2e\n",
                m.rattlers, m.free_rotation_modes, m.translation_modes, m.mechanisms, m.unstable_modes, m.sliding_contacts,
                m.unbalanced);
  };
  line(r.slab);
  if (r.bulk_available)
    line(r.bulk);
  else
    std::printf("relaxed (bulk): %s\n", r.bulk_note.c_str());
  std::printf("effective medium (affine estimate, %s, Z = %.4f, phi = %.4f, p = %.6g Pa): K = %.6g Pa, G = %.6g Pa "
              "(smooth %.6g), V_p = %.4f m/s, V_s = %.4f m/s\n",
              r.medium_model.c_str(), r.Z, r.phi, r.p, r.medium.K, r.medium.G, r.medium.G_smooth, r.medium.V_p, r.medium.V_s);
}

}  // namespace granwave::cli
