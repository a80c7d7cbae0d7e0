// Guards of a chain case (chain/guards.hpp).
#include "chain/guards.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>

#include "core/error.hpp"
#include "core/format.hpp"
#include "theory/hertz.hpp"

namespace granwave::chain {
namespace {

// Measured costs (granwave run on oriented20 and on 10x its t_end, /usr/bin/time maxrss): 21.8 MB
// at 6001 samples, +0.675 kB per sample of 82 stored columns (8 bytes each, reserved up front).
// Rounded up: 20 MB fixed (15.3 MB for `granwave check` alone), 400 bytes per bead (system,
// stepper, RK4 stages), and the stored series half again for the analysis of the written trace
// (it reads the contact forces back after the run's series are freed).
constexpr double kFixedBytes = 20e6, kBytesPerBead = 400.0, kAnalysisFactor = 1.5;

std::string contact_label(const ChainSystem& sys, std::size_t j) {
  const bool wall = j + 1 >= sys.nbeads();
  return "contact " + std::to_string(j) + " (" + sys.material_names[sys.material[j]] + "-" +
         (wall ? "wall " + sys.wall : sys.material_names[sys.material[j + 1]]) + ")";
}

}  // namespace

void assess_physics(const ChainSystem& sys, double dt, Assessment& a, const std::string& keys_dt) {
  const std::size_t n = sys.nbeads(), nc = sys.ncontacts();
  const std::size_t before = a.refusals.size();
  for (std::size_t b = 0; b < n; ++b) {
    const std::string m = sys.material_names[sys.material[b]];
    a.require_finite("the mass of bead " + std::to_string(b), sys.mass[b], "materials." + m);
    a.require_finite("the radius of bead " + std::to_string(b), sys.radius[b], "materials." + m);
    if (a.refusals.size() > before) return;
  }
  for (std::size_t j = 0; j < nc; ++j) {
    a.require_finite("the Hertz constant A of " + contact_label(sys, j), sys.hertz_constant[j],
                     "the materials' youngs_modulus, poisson_ratio, radius");
    a.require_finite("the static overlap delta_0 of " + contact_label(sys, j), sys.initial_overlap[j], "chain.precompression",
                     false);
    if (a.refusals.size() > before) return;
  }
  const std::string v_key = "chain.striker.velocity (v0 = " + fmt("%.4g", sys.striker_velocity) + " m/s)";
  for (const auto& k : contact_kinds(sys)) {
    const std::string keys = "the materials of " + k.label + " or " + v_key;
    a.require_finite("the two-body contact time t_c of " + k.label, k.contact_time, keys);
    a.require_finite("the two-body peak force of " + k.label, k.peak_force, keys);
  }
  const double dt_max = stable_dt(sys);
  a.require_finite("the stability limit 2/omega_max", dt_max, "the materials or " + v_key);
  a.require_finite("integrator.dt (resolved)", dt, keys_dt);
  if (a.refusals.size() > before) return;

  // An overlap that reaches the radius: Hertz's law (eq. 13) is a small-overlap law.
  double worst = 0.0, worst_delta = 0.0, worst_r = 0.0;
  std::size_t wj = 0;
  for (std::size_t j = 0; j < nc; ++j) {
    const double delta = theory::hertz_impact(sys.hertz_constant[j], sys.mass[0], theory::kWallMass, sys.striker_velocity)
                             .max_overlap +
                         sys.initial_overlap[j];
    const double r = j + 1 < n ? std::min(sys.radius[j], sys.radius[j + 1]) : sys.radius[j];
    if (!(delta / r <= worst)) worst = delta / r, worst_delta = delta, worst_r = r, wj = j;
  }
  const std::string overlap = "the largest overlap the striker's energy allows, in " + contact_label(sys, wj) + ", is " +
                              fmt("%.4g", worst_delta) + " m = " + fmt("%.3g", 100.0 * worst) + " % of the radius " +
                              fmt("%.4g", worst_r) + " m";
  const std::string lower = "lower " + v_key + (sys.precompression > 0.0 ? " or chain.precompression" : "");
  if (!(worst < 1.0))
    a.refusals.push_back(overlap + ": Hertz contacts (eq. 13) mean nothing there; " + lower);
  else if (worst > kOverlapWarnFraction)
    a.warnings.push_back(overlap + ", above the " + fmt("%.0f", 100.0 * kOverlapWarnFraction) +
                         " % within which Hertz's small-overlap law holds; " + lower + " for a valid model");

  if (dt > dt_max)
    a.refusals.push_back("integrator.dt = " + fmt("%.4g", dt) + " s is above the stability limit 2/omega_max = " +
                         fmt("%.4g", dt_max) + " s of this chain (Gershgorin bound, stiffness at the overlap bound); use dt <= " +
                         fmt("%.3g", dt_max / 100.0) + " s for accuracy (" + keys_dt + ")");
  const double tc = shortest_contact_time(sys);
  if (dt > tc / 50.0)
    a.warnings.push_back("dt = " + fmt("%.4g", dt) + " s is above t_c/50 = " + fmt("%.4g", tc / 50.0) +
                         " s (t_c = shortest two-body contact time at v0), the accuracy criterion of seed 002 sec. 2.2");
  else if (dt > tc / 100.0)
    a.warnings.push_back("dt = " + fmt("%.4g", dt) + " s is above 1/100 of the shortest contact time (" +
                         fmt("%.4g", tc / 100.0) + " s); peak forces will be off by more than about 1e-3");
}

namespace {

// Steps, samples, memory and output of a run at time step dt (NaN: not known yet, the system only).
void estimate(const config::Case& c, double nb, double nc, double dt, ResourceEstimate& e) {
  e.memory = kFixedBytes + kBytesPerBead * nb;
  e.output = 100.0 * nb;
  if (!(std::isfinite(dt) && dt > 0.0)) return;
  const double t_stop = c.stop.enabled ? c.stop.max_time.value_or(c.integrator.t_end) : c.integrator.t_end;
  e.steps = std::round(t_stop / dt);
  const double stride = c.output.interval > 0.0 ? std::max(1.0, std::round(c.output.interval / dt)) : 1.0;
  e.samples = std::floor(e.steps / stride) + 1.0;
  bool cf = true, bf = true, en = true;
  if (!c.output.fields.empty()) {
    cf = bf = en = false;
    for (const auto& f : c.output.fields) {
      cf = cf || f == "contact_force";
      bf = bf || f == "bead_force";
      en = en || f == "energy";
    }
  }
  const double columns = (cf ? nc : 0.0) + (bf ? nb : 0.0) + (en ? 3.0 : 0.0) + 1.0;
  const double series = (e.samples + 1.0) * columns * 8.0;
  const double sensors = static_cast<double>(c.output.full_rate_beads.size());
  const double full_rate = sensors > 0.0 ? (e.steps + 1.0) * (sensors + 1.0) * 8.0 : 0.0;
  e.memory += kAnalysisFactor * series + full_rate;
  e.output += series + full_rate;
}

}  // namespace

Assessment assess(const config::Case& c, const ResourceLimits& limits, ChainSystem* built) {
  if (!c.chain) throw InputError(c.path + ": [chain] is missing");
  const config::ChainCase& ch = *c.chain;
  Assessment a;
  ResourceEstimate& e = a.estimate;
  // Beads and contacts from the case, before anything is built; with a given dt the whole
  // estimate, else (dt_over_tc needs the contact times) the system's memory first.
  double nb = 1.0;  // the striker
  for (const auto& s : ch.segments)
    nb += s.kind == config::ChainSegment::Kind::cells ? static_cast<double>(s.count) * static_cast<double>(ch.cell.size())
                                                      : static_cast<double>(s.repeat) * static_cast<double>(s.beads.size());
  const bool wall = ch.wall != "free";
  const double nc = nb - 1.0 + (wall ? 1.0 : 0.0);
  e.size = fmt("%.0f beads", nb);
  e.steps_keys = std::string("integrator.t_end or integrator.dt") + (c.stop.enabled ? " (or stop.max_time)" : "");
  e.memory_keys = "integrator.t_end, output.interval or output.fields, or the chain's length (chain.segment)";
  if (!c.output.full_rate_beads.empty()) e.memory_keys += ", output.full_rate_beads (stored at every step)";
  estimate(c, nb, nc, c.integrator.dt.value_or(NAN), e);
  check_resources(a, limits);
  if (!a.refusals.empty()) return a;

  ChainSystem sys = build_chain(c);
  const std::string keys_dt = c.integrator.dt ? "integrator.dt" : "integrator.dt_over_tc";
  const double dt = c.integrator.dt ? *c.integrator.dt : c.integrator.dt_over_tc.value_or(NAN) * shortest_contact_time(sys);
  assess_physics(sys, dt, a, keys_dt);
  if (!c.integrator.dt) {
    estimate(c, nb, nc, dt, e);
    check_resources(a, limits);
  }
  if (built) *built = std::move(sys);
  return a;
}

}  // namespace granwave::chain
