// The relaxed theory's inputs from a case (crystal/relaxed_inputs.hpp): the slab's options, the
// triply periodic relaxation of a file's packing for the bulk.
#include "crystal/relaxed_inputs.hpp"

#include <algorithm>
#include <cmath>
#include <numbers>
#include <string>

#include "core/error.hpp"
#include "crystal/derive.hpp"
#include "crystal/fire.hpp"
#include "crystal/packing.hpp"
#include "packing/packing.hpp"

namespace granwave::crystal {
namespace {

struct State {
  std::vector<Eigen::Vector3d> x;
  std::vector<double> a, m;
  Eigen::Vector3d box;
  std::vector<std::pair<int, int>> pairs;  // within a_i + a_j + skin at the last build
  std::vector<Eigen::Vector3d> x_build;
  double skin = 0.0;

  Eigen::Vector3d branch(int i, int j) const {  // minimum image, i to j
    Eigen::Vector3d d = x[j] - x[i];
    for (int k = 0; k < 3; ++k) d[k] -= box[k] * std::round(d[k] / box[k]);
    return d;
  }
  void build() {  // all pairs: called rarely (moves beyond skin/2)
    pairs.clear();
    const int n = static_cast<int>(x.size());
    for (int i = 0; i < n; ++i)
      for (int j = i + 1; j < n; ++j)
        if (branch(i, j).norm() < a[i] + a[j] + skin) pairs.emplace_back(i, j);
    x_build = x;
  }
  bool far() const {
    for (std::size_t p = 0; p < x.size(); ++p)
      if ((x[p] - x_build[p]).norm() > 0.5 * skin) return true;
    return false;
  }
};

// Net normal forces; returns the mean contact force.
double forces(const config::Case& c, const State& s, std::vector<Eigen::Vector3d>& f) {
  std::fill(f.begin(), f.end(), Eigen::Vector3d::Zero());
  double sum = 0.0;
  int count = 0;
  for (const auto& [i, j] : s.pairs) {
    const Eigen::Vector3d b = s.branch(i, j);
    const double l = b.norm(), overlap = s.a[i] + s.a[j] - l;
    if (!(overlap > 0.0)) continue;
    const double fn = static_normal_force(c, s.a[i], s.a[j], overlap);
    const Eigen::Vector3d u = b / l;  // j pushes i back along -u
    f[i] -= fn * u;
    f[j] += fn * u;
    sum += std::abs(fn);
    ++count;
  }
  return count ? sum / count : 0.0;
}

}  // namespace

theory::RelaxedOptions relaxed_slab_options(const config::Case& c, const Packing& pk) {
  theory::RelaxedOptions slab;
  slab.contact = lattice_options(c, 1e-6);
  slab.affine_layers = std::max(1, pk.fixed_layers);
  slab.mu = c.contact.friction().mu_static;
  slab.unstressed = false;
  if (pk.from_file()) {
    slab.prescribed.resize(pk.size());
    for (std::size_t p = 0; p < pk.size(); ++p) slab.prescribed[p] = pk.role_of(p) != role_free;
    slab.slab_volume = pk.box_x * pk.box_y * c.crystal->imported->box.length(2);
  }
  return slab;
}

PeriodicBulk periodic_bulk(const config::Case& c, double tolerance, long max_steps) {
  const config::CrystalCase& k = *c.crystal;
  if (!k.from_file() || !k.imported) throw InputError(c.path + ": the periodic bulk needs a packing from a file");
  const packing::Packing& src = *k.imported;
  if (src.box.z_walls()) throw InputError(src.source + ": the packing lies between z walls, not periodic in z");
  const Packing pk = imported_packing(c);  // the file's centres, radii and masses (density rule)
  State s;
  s.box = {pk.box_x, pk.box_y, src.box.length(2)};
  double a_mean = 0.0;
  for (std::size_t p = 0; p < pk.size(); ++p) {
    s.x.emplace_back(pk.x[p], pk.y[p], pk.z[p]);
    s.a.push_back(pk.radius[p]);
    s.m.push_back(pk.mass[p]);
    a_mean += pk.radius[p] / static_cast<double>(pk.size());
  }
  s.skin = 0.2 * a_mean;
  s.build();
  // The stiffest contact's time (a Hertz contact softens as its overlap relaxes: taken again every
  // 2000 steps; a linear law's never changes).
  const double m_min = *std::min_element(s.m.begin(), s.m.end());
  auto contact_time = [&] {
    double k_max = 0.0;
    for (const auto& [i, j] : s.pairs) {
      const double overlap = s.a[i] + s.a[j] - s.branch(i, j).norm();
      if (overlap > 0.0) k_max = std::max(k_max, contact_between(c, s.a[i], s.a[j], overlap).kn);
    }
    if (!(k_max > 0.0)) throw InputError(c.path + ": the file's packing has no touching contacts");
    return std::numbers::pi * std::sqrt(0.5 * m_min / k_max);
  };
  const double t_c = contact_time();
  // FIRE (crystal/fire.hpp) with velocity Verlet, as crystal/relax.cpp.
  const std::size_t n = s.x.size();
  std::vector<Eigen::Vector3d> v(n, Eigen::Vector3d::Zero()), f(n);
  Fire fire(t_c);
  double mean = forces(c, s, f);
  PeriodicBulk out;
  for (long step = 0;; ++step) {
    double worst = 0.0;
    for (const auto& q : f) worst = std::max(worst, q.norm());
    if (worst <= tolerance * mean) {
      out.steps = step;
      out.unbalanced = worst / mean;
      break;
    }
    if (step >= max_steps)
      throw RunError(c.path + ": the periodic bulk's relaxation did not reach a net force below " +
                     std::to_string(tolerance) + " of the mean contact force within " + std::to_string(max_steps) +
                     " steps (largest " + std::to_string(worst / mean) + ")");
    if (step > 0 && step % 2000 == 0) fire.dt_max = 0.1 * contact_time();
    double power = 0.0, v2 = 0.0, f2 = 0.0;
    for (std::size_t p = 0; p < n; ++p) power += f[p].dot(v[p]), v2 += v[p].squaredNorm(), f2 += f[p].squaredNorm();
    const Fire::Mix mix = fire.next(power, v2, f2);
    if (mix.moving)
      for (std::size_t p = 0; p < n; ++p) v[p] = mix.keep * v[p] + mix.scale * f[p];
    else
      for (auto& q : v) q.setZero();
    const double dt = fire.dt;
    for (std::size_t p = 0; p < n; ++p) {
      v[p] += 0.5 * dt * f[p] / s.m[p];
      s.x[p] += dt * v[p];
    }
    if (s.far()) s.build();
    mean = forces(c, s, f);
    for (std::size_t p = 0; p < n; ++p) v[p] += 0.5 * dt * f[p] / s.m[p];
  }
  // The network of the relaxed state.
  theory::ContactNetwork& net = out.net;
  net.box_x = s.box[0], net.box_y = s.box[1];
  const ContactAt k0 = contact_at(c, linearisation_overlap(c, pk));  // the fallback k, kt (each contact has its own)
  net.k = k0.kn, net.kt = k0.kt;
  for (std::size_t p = 0; p < n; ++p) net.particles.push_back({s.m[p], 0, s.x[p].z(), s.a[p], pk.inertia[p]});
  for (const auto& [i, j] : s.pairs) {
    const Eigen::Vector3d b = s.branch(i, j);
    const double overlap = s.a[i] + s.a[j] - b.norm();
    if (!(overlap > 0.0)) continue;
    const ContactAt kc = contact_between(c, s.a[i], s.a[j], overlap);
    theory::NetworkContact nc{i, j, theory::Vec3(b.x(), b.y(), b.z()), kc.f_n};
    nc.k = kc.kn, nc.kt = kc.kt;
    net.contacts.push_back(nc);
  }
  out.box_z = s.box[2];
  return out;
}

}  // namespace granwave::crystal
