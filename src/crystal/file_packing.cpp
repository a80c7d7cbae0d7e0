// The generator of crystal.lattice = "file" (crystal/packing.hpp): a packing imported by src/packing
// made a run's: z cut open, roles by slab, z-bins, relaxed under the case's law before the wave.
// lattice = "random" takes the same road: its prepared periodic packing is the case's `imported`.
#include <algorithm>
#include <cmath>
#include <numeric>
#include <numbers>
#include <sstream>

#include "core/error.hpp"
#include "crystal/derive.hpp"
#include "crystal/dynamics.hpp"
#include "crystal/packing.hpp"

namespace granwave::crystal {

namespace {

// Each particle's bin from its centre now (clamped into the box's bins), then the particles
// stored bin by bin, in their order within a bin (a stable sort).
void sort_into_bins(Packing& p) {
  const std::size_t n = p.size();
  for (std::size_t q = 0; q < n; ++q) {
    const double b = std::floor((p.z[q] - p.bin_origin) / p.bin_width);
    p.layer[q] = static_cast<int>(std::clamp(b, 0.0, static_cast<double>(p.layers - 1)));
  }
  std::vector<std::size_t> order(n);
  std::iota(order.begin(), order.end(), std::size_t{0});
  std::stable_sort(order.begin(), order.end(), [&](std::size_t a, std::size_t b) { return p.layer[a] < p.layer[b]; });
  const auto permute = [&](auto& v) {
    auto old = v;
    for (std::size_t q = 0; q < n; ++q) v[q] = old[order[q]];
  };
  permute(p.x), permute(p.y), permute(p.z), permute(p.radius), permute(p.mass), permute(p.inertia);
  permute(p.layer), permute(p.fixed), permute(p.role);
  // The springs follow their particles: (i, j) renamed, the pair's i < j again (the spring reversed), sorted.
  std::vector<std::uint32_t> now(n);
  for (std::size_t q = 0; q < n; ++q) now[order[q]] = static_cast<std::uint32_t>(q);
  for (packing::SpringHistory& s : p.springs) {
    s.i = now[s.i], s.j = now[s.j];
    if (s.i > s.j) {
      std::swap(s.i, s.j);
      for (double& x : s.xi) x = -x;
    }
  }
  std::sort(p.springs.begin(), p.springs.end(), [](const auto& a, const auto& b) { return a.i != b.i ? a.i < b.i : a.j < b.j; });
}

// The largest net contact force on a free particle over the mean contact force, under the case's
// normal law (the static check of the relaxation).
double unbalanced_force(const config::Case& c, const Packing& p) {
  std::vector<double> f(3 * p.size(), 0.0);
  double sum = 0.0;
  std::size_t count = 0;
  for (const PackingContact& k : list_contacts(p, true)) {
    const double fn = static_normal_force(c, p.radius[k.i], p.radius[k.j], k.overlap);
    const double b = std::sqrt(k.bx * k.bx + k.by * k.by + k.bz * k.bz);
    const double u[3] = {k.bx / b, k.by / b, k.bz / b};  // from i towards j: j pushes i back
    for (int a = 0; a < 3; ++a) {
      f[3 * k.i + a] -= fn * u[a];
      f[3 * k.j + a] += fn * u[a];
    }
    sum += std::abs(fn);
    ++count;
  }
  double worst = 0.0;
  for (std::size_t q = 0; q < p.size(); ++q)
    if (!p.fixed[q]) worst = std::max(worst, std::hypot(f[3 * q], f[3 * q + 1], f[3 * q + 2]));
  return count && sum > 0.0 ? worst / (sum / static_cast<double>(count)) : 0.0;
}

double solid_fraction(const Packing& p, double height) {
  double v = 0.0;
  for (double r : p.radius) v += 4.0 / 3.0 * std::numbers::pi * r * r * r;
  return v / (p.box_x * p.box_y * height);
}

}  // namespace

Packing imported_packing(const config::Case& c) {
  const config::CrystalCase& k = *c.crystal;
  if (!k.from_file() || !k.imported || !k.packing_file)
    throw InputError(c.path + ": crystal.lattice = \"" + k.lattice + "\" needs its packing (not imported or prepared)");
  const packing::Packing& src = *k.imported;
  const config::PackingKeys& keys = *k.packing_file;
  Packing p;
  p.generator = k.lattice;  // "file" or "random"
  if (k.preparation) p.preparation = *k.preparation;
  if (k.random) p.seed = k.random->seed, p.preparation_friction = k.random->friction;
  p.preparation.springs.clear();  // kept once, as the packing's springs below
  p.source_file = keys.file;
  p.source_format = keys.format;
  p.source_thickness = keys.source_thickness;
  p.box_x = src.box.length(0);
  p.box_y = src.box.length(1);
  const double z_lo = src.box.lo[2], z_hi = src.box.hi[2];
  p.bin_origin = z_lo;
  p.bin_width = keys.bin_width;
  p.l0 = keys.bin_width;
  p.layers = std::max(1, static_cast<int>(std::ceil((z_hi - z_lo) / keys.bin_width - 1e-9)));
  double d_sum = 0.0;
  for (const packing::Particle& q : src.particles) {
    // x and y in [0, box) as the cell list wants them (the importer wrapped them into [lo, hi)).
    double x = q.centre.x() - src.box.lo[0], y = q.centre.y() - src.box.lo[1];
    x = x >= p.box_x ? x - p.box_x : x < 0.0 ? x + p.box_x : x;
    y = y >= p.box_y ? y - p.box_y : y < 0.0 ? y + p.box_y : y;
    const double z = q.centre.z();
    p.x.push_back(x);
    p.y.push_back(y);
    p.z.push_back(z);
    p.radius.push_back(q.radius);
    p.mass.push_back(q.mass);  // the density rule's (config/packing_loader.cpp)
    p.inertia.push_back(0.4 * q.mass * q.radius * q.radius);
    // A periodic z is cut open here: contacts across it are gone, the slabs hold what is left.
    const std::uint8_t role = z < z_lo + keys.source_thickness ? role_source
                              : z >= z_hi - keys.fixed_thickness ? role_fixed_top
                                                                 : role_free;
    p.role.push_back(role);
    p.fixed.push_back(role != role_free);
    p.layer.push_back(0);
    d_sum += 2.0 * q.radius;
  }
  p.d = p.d_prime = d_sum / static_cast<double>(p.size());
  p.delta = 0.0;
  if (k.preparation) {  // the springs of the pairs that the cut in z leaves (the nearest image inside the box)
    const double lz = z_hi - z_lo;
    for (const packing::SpringHistory& s : k.preparation->springs)
      if (std::abs(p.z[s.j] - p.z[s.i]) < 0.5 * lz) p.springs.push_back(s);
  }
  sort_into_bins(p);
  return p;
}

Packing relaxed_imported_packing(const config::Case& c) {
  Packing p = imported_packing(c);
  // A frictional preparation ended static, held by its springs: no frictionless relaxation (it would
  // let the packing collapse); its residuals are the preparation's (prepare_unbalanced, _torque).
  if (p.preparation_friction > 0.0) return p;
  RelaxResult r;
  try {
    r = relax(p, c.contact, c.crystal->density, c.crystal->packing_file->relax_tolerance);
  } catch (const NotStanding& e) {
    // An imported packing is relaxed frictionless and carries no tangential history (data/SCHEMA.md §1).
    const config::PackingKeys& keys = *c.crystal->packing_file;
    std::ostringstream why;
    const std::string source = keys.file.empty() ? "the prepared packing" : "packing.file " + keys.file;
    why << c.path << ": " << source << ": " << e.what() << " (solid fraction "
        << solid_fraction(p, c.crystal->imported->box.length(2))
        << "): a loose or friction-prepared packing. granwave relaxes an imported packing under the case's normal law "
           "without friction and carries no tangential history (allowed: a packing that stands without friction, "
           "e.g. compressed past frictionless jamming)";
    throw InputError(why.str());
  }
  p.relaxed = true;
  p.relax_steps = r.steps;
  p.relax_ratio = r.ratio;
  sort_into_bins(p);  // bins from the relaxed centres (the slabs did not move)
  p.relax_unbalanced = unbalanced_force(c, p);
  return p;
}

}  // namespace granwave::crystal
