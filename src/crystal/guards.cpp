// Guards of a crystal case (crystal/guards.hpp).
#include "crystal/guards.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <limits>
#include <numbers>

#include "config/contact_laws.hpp"
#include "core/error.hpp"
#include "core/format.hpp"
#include "crystal/observables.hpp"
#include "crystal/simulation.hpp"

namespace granwave::crystal {
namespace {

// Measured costs (granwave run, /usr/bin/time maxrss): 18.6 MB with 3200 particles, 72.0 MB with
// 51200, 245 MB with 204800 (1125 bytes per particle: state, contact list with history, packing;
// with friction the contact pass's particle rows add 96, crystal/kernel.hpp), and 9.4 kB per stored sample of the 200-layer crystal (6 layer fields x 8 bytes, in vectors that
// grow by doubling). Rounded up: 20 MB fixed, 1300 bytes per particle, 2.5 x the stored series (a
// vector's growth, and the analysis of the written trace, which reads it back and transforms one
// field), 400 bytes per particle for a VTK snapshot (ASCII). Since the sample's per-layer lists and
// lever-arm scratch (crystal/layer_sums.hpp; 4x4xL crystal with friction, 100 steps, a sample every
// 10): 23.6 MB with 3200 particles, 95.3 MB with 51200, 324 MB with 204800, 1456 bytes per particle
// between the last two (1334 before them): 1500 bytes per particle.
constexpr double kFixedBytes = 20e6, kBytesPerParticle = 1500.0, kSeriesFactor = 2.5, kVtkBytesPerParticle = 400.0;

}  // namespace

Assessment assess(const config::Case& c, const ResourceLimits& limits, std::optional<Derived>* derived) {
  if (!c.crystal) throw InputError(c.path + ": [crystal] is missing");
  check_output_fields(c);  // the table's names (crystal/observables.hpp)
  const config::CrystalCase& k = *c.crystal;
  Assessment a;
  {  // what derive() divides by, so that its refusals name the right keys
    const double m = k.density * 4.0 / 3.0 * std::numbers::pi * k.radius * k.radius * k.radius;
    a.require_finite("the particle mass m = density 4/3 pi a^3", m, "crystal.radius, crystal.density");
    const contact::ScaleCheck scale = config::law_of(c.contact).scale(c.contact, k, m);  // the law's stiffness/m
    a.require_finite(scale.what, scale.value, scale.keys);
    const double a_min = k.radius - k.polydispersity * k.overlap * 2.0 * k.radius;
    a.require_finite("the smallest radius a - polydispersity delta", a_min, "crystal.polydispersity, crystal.overlap");
    if (!a.refusals.empty()) return a;
  }
  const Derived d = derive(c);  // refuses bad contact parameters (overdamped, negative, ...)
  if (derived) *derived = d;
  ResourceEstimate& e = a.estimate;
  // The particles and the layers (z-bins) the run stores: the FCC's cells, or the file's packing.
  double layers = k.cells[2];
  double n = static_cast<double>(k.cells[0]) * k.cells[1] * layers;
  if (k.from_file()) {
    n = static_cast<double>(k.imported->particles.size());
    layers = std::max(1.0, std::ceil(k.imported->box.length(2) / k.packing_file->bin_width - 1e-9));
  }
  e.size = fmt("%.6g particles", n);
  e.steps_keys = "integrator.t_end or integrator.dt";
  e.memory_keys = k.random        ? "random.count, random.bin_width, integrator.t_end or output.interval"
                  : k.from_file() ? "packing.file, packing.bin_width, integrator.t_end or output.interval"
                                  : "crystal.cells, integrator.t_end or output.interval";
  const std::string keys_dt = c.integrator.dt ? "integrator.dt" : "integrator.dt_over_tc";

  const std::string material = "crystal.radius, crystal.density";
  const config::ContactLawInfo& law = config::law_of(c.contact);
  const contact::GuardKeys keys = law.guard_keys();
  a.require_finite("the particle mass m", d.mass, material);
  a.require_finite("the contact frequency omega", d.omega, keys.stiffness + ", " + keys.damping + ", " + material);
  a.require_finite("the contact time t_c", d.t_c, keys.stiffness + ", " + keys.damping + ", " + material);
  a.require_finite("the stability limit of velocity Verlet", d.dt_stable, keys.stability + ", " + material);
  a.require_finite("integrator.dt (resolved)", d.dt, keys_dt);
  a.require_finite("the prestress sigma_0", d.sigma_0, keys.prestress, false);
  a.require_finite("the P-wave speed V_p (eq. 10)", d.v_p, keys.wave_speed + ", " + material);
  if (!a.refusals.empty()) return a;

  if (d.dt > d.dt_stable)
    a.refusals.push_back("integrator.dt = " + fmt("%.4g", d.dt) + " s is above the stability limit " + fmt("%.4g", d.dt_stable) +
                         " s of velocity Verlet for this crystal (2/omega_max, omega_max^2 <= 2 z (k + 3.5 k_t)/m_min, z = " +
                         std::to_string(d.max_coordination) +
                         law.stability_note(d.delta_max) +
                         "); change " + keys_dt);
  {  // The rolling and torsion springs turn the spheres: per contact an angular spring (k_r + k_o) a'^2
     // against I = 2/5 m a^2; the same Gershgorin bound omega^2 <= 2 z K/I_min, with a' <= a_max/2.
    const contact::RollingTorsionKeys& p = c.contact.rolling();
    const double spring = p.kr + p.ko, dashpot = p.gamma_r + p.gamma_o;
    if (spring > 0.0 || dashpot > 0.0) {
      const double delta0 = k.overlap * 2.0 * k.radius;
      const double a_lo = k.radius - k.polydispersity * delta0;
      double a_hi = k.radius + k.polydispersity * delta0, z = 12.0;
      double inertia = 0.4 * k.density * 4.0 / 3.0 * std::numbers::pi * std::pow(a_lo, 5);
      if (k.from_file() && k.imported) {  // the packing's own radii, masses and largest coordination
        a_hi = 0.0;
        inertia = std::numeric_limits<double>::infinity();
        for (const auto& q : k.imported->particles) {
          a_hi = std::max(a_hi, q.radius);
          inertia = std::min(inertia, 0.4 * q.mass * q.radius * q.radius);
        }
        z = d.max_coordination;
      }
      const double arm2 = 0.25 * a_hi * a_hi;
      const double omega = std::sqrt(2.0 * z * spring * arm2 / inertia), eta = z * dashpot * arm2 / (2.0 * inertia);
      const double dt_turn = omega > 0.0 ? 2.0 / omega * (std::sqrt(1.0 + (eta / omega) * (eta / omega)) - eta / omega)
                                         : 1.0 / eta;
      if (d.dt > dt_turn)
        a.refusals.push_back("integrator.dt = " + fmt("%.4g", d.dt) + " s is above the stability limit " +
                             fmt("%.4g", dt_turn) + " s of the rolling and torsion springs (2/omega, omega^2 <= 2 z (k_r + k_o) a'^2/I_min, " +
                             "a' = a/2, I = 2/5 m a^2, z = " + fmt("%.0f", z) + ", with their dashpots); change " + keys_dt +
                             " or contact.kr, contact.ko");
    }
  }
  if (d.dt > d.t_c / 50.0 * (1.0 + 1e-12))  // dt_over_tc = 0.02 gives t_c/50 up to a rounding
    a.warnings.push_back("dt = " + fmt("%.4g", d.dt) + " s exceeds t_c/50 = " + fmt("%.4g", d.t_c / 50.0) +
                         " s, the accuracy rule of seed 002 sec. 2.2");

  // The largest overlap: the initial one plus what the source puts into one contact.
  const double diameter = 2.0 * k.radius, delta0 = k.overlap * diameter;
  double a_min = k.radius - k.polydispersity * delta0;
  if (k.from_file())
    for (const auto& q : k.imported->particles) a_min = std::min(a_min, q.radius);
  const bool velocity = c.excitation.drive == config::Excitation::Drive::velocity;
  const double added = velocity ? std::abs(c.excitation.amplitude) * std::sqrt(d.mass / d.kn)
                                : std::abs(c.excitation.amplitude) * diameter;
  const double delta = delta0 + added, ratio = delta / a_min;
  const std::string source = velocity ? "velocity drive, |v| sqrt(m/k)" : "displacement step, |amplitude| d";
  const std::string overlap = "the overlap bound (initial " + fmt("%.4g", delta0) + " m + " + fmt("%.4g", added) +
                              " m from the " + source + ") is " + fmt("%.4g", delta) + " m = " + fmt("%.3g", 100.0 * ratio) +
                              " % of the smallest radius " + fmt("%.4g", a_min) + " m";
  const std::string lower = "lower excitation.amplitude or crystal.overlap";
  if (!(ratio < 1.0))
    a.refusals.push_back(overlap + ": contacts (eq. 1) mean nothing there; " + lower);
  else if (ratio > kOverlapWarnFraction)
    a.warnings.push_back(overlap + ", above the " + fmt("%.0f", 100.0 * kOverlapWarnFraction) +
                         " % within which the small-overlap contact law holds; " + lower + " for a valid model");

  e.steps = std::round(c.integrator.t_end / d.dt);
  const double every = c.output.interval > 0.0 ? std::max(1.0, std::round(c.output.interval / d.dt)) : 1.0;
  e.samples = std::floor(e.steps / every) + 1.0;
  // Stored in memory: every observable of the table per sample (a layer's row or one value); in
  // the file, only those of the [output] fields.
  double all = 0.0, chosen = 0.0;
  for (const Observable& o : observables()) {
    const double values = o.shape == Shape::per_layer ? layers : 1.0;
    all += values;
    if (selected(c, o)) chosen += values;
  }
  const double in_memory = e.samples * all * 8.0;
  const double columns = c.output.fields.empty() ? all : chosen + 1.0;  // + time
  const double snapshots = c.output.vtk_every > 0 ? std::floor(e.samples / c.output.vtk_every) + 1.0 : 0.0;
  e.memory = kFixedBytes + kBytesPerParticle * n + kSeriesFactor * in_memory + (snapshots > 0 ? kVtkBytesPerParticle * n : 0.0);
  e.output = e.samples * columns * 8.0 + 120.0 * n + snapshots * kVtkBytesPerParticle * n;
  if (snapshots > 0) e.memory_keys += ", output.vtk_every";
  check_resources(a, limits);
  return a;
}

}  // namespace granwave::crystal
