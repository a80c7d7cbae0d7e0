// Entry points of the crystal model (src/models.hpp): check, build, run.
#include <cmath>
#include <cstdio>
#include <iomanip>
#include <memory>
#include <ostream>
#include <sstream>

#include "core/error.hpp"
#include "crystal/packing.hpp"
#include "crystal/simulation.hpp"
#include "crystal/vtk.hpp"
#include "io/h5.hpp"
#include "models.hpp"

namespace granwave::crystal {

namespace {

// A packing given as a system file must be the case's crystal.
void check_system_matches(const config::Case& c, const Packing& p, const std::string& path) {
  const auto& k = *c.crystal;
  if (p.nx != k.cells[0] || p.ny != k.cells[1] || p.layers != k.cells[2] || p.fixed_layers != k.fixed_layers ||
      std::abs(p.d - 2.0 * k.radius) > 1e-12 * p.d)
    throw InputError(path + ": the system's packing (cells, fixed layers, radius) is not the one of " + c.path);
}

std::string trace_path_for(const config::Case& c, const RunRequest& req) {
  return req.trace_path.empty() ? c.name + ".h5" : req.trace_path;
}

}  // namespace

void check(const config::Case& c, std::ostream& out) {
  const Derived d = derive(c);  // refuses bad contact parameters and unstable dt
  const Packing p = lattice_packing(c);  // refuses a packing that does not fit its box
  const auto& k = *c.crystal;
  out << std::setprecision(6);
  out << "crystal case " << c.name << ": " << p.size() << " particles (" << k.cells[0] << " x " << k.cells[1] << " x "
      << k.cells[2] << " layers, " << k.fixed_layers << " fixed at each end)\n";
  out << "  d = " << p.d << " m, d' = d(1 - overlap) = " << p.d_prime << " m, l0 = d'/sqrt(2) = " << p.l0
      << " m, delta = " << p.delta << " m, box " << p.box_x << " x " << p.box_y << " m\n";
  out << "  mass m = " << d.mass << " kg, m_ij = " << d.m_ij << " kg\n";
  out << "  contact: omega = sqrt(k/m_ij - eta_0^2) = " << d.omega << " 1/s, t_c = pi/omega = " << d.t_c
      << " s, restitution exp(-eta_0 t_c) = " << d.restitution
      << (c.contact.normal_tension == config::NormalTension::clip ? " (\"allow\" value; \"clip\" ends earlier)" : "")
      << "\n";
  out << "  dt = " << d.dt << " s = t_c/" << d.t_c / d.dt << "; stability limit (conservative) " << d.dt_stable
      << " s; " << d.steps << " steps, a sample every " << d.sample_every << " steps\n";
  out << "  prestress sigma_0 = 2 sqrt(2) k delta / d'^2 = " << d.sigma_0 << " Pa\n";
  out << "  predicted speeds along z (eq. 10, branch d'): V_p = " << d.v_p << " m/s"
      << (c.contact.kt > 0.0 ? " (affine, sqrt(1 + kt/k))" : "") << ", V_s = " << d.v_s << " m/s (frictionless)\n";
  if (c.contact.kt > 0.0 || c.contact.gamma_t > 0.0)
    out << "  tangential: kt = " << c.contact.kt << " N/m, mu_s = " << c.contact.mu_static
        << ", mu_d = " << c.contact.mu_dynamic << ", lever arm "
        << (c.contact.lever_arm == config::LeverArm::contact_point ? "a - delta/2 (contact point, as YADE and LIGGGHTS)"
                                                                   : "a (seed 002 eq. (4))")
        << "\n";
  if (k.polydispersity > 0.0)
    out << "  polydisperse: radii a +- " << k.polydispersity * p.delta << " m (seed " << k.seed
        << "); relaxed until E_kin/E_pot < " << k.relax_tolerance << "\n";
  if (d.dt > d.t_c / 50.0)
    out << "warning: dt = " << d.dt << " s exceeds t_c/50 = " << d.t_c / 50.0
        << " s, the accuracy rule of seed 002 sec. 2.2\n";
  if (d.dt > d.dt_stable)
    throw InputError(c.path + ": integrator.dt = " + std::to_string(d.dt) + " s exceeds the stability limit " +
                     std::to_string(d.dt_stable) + " s of velocity Verlet for this crystal");
}

void build(const config::Case& c, const std::string& system_path) {
  const Packing p = make_packing(c);
  io::H5Writer w(system_path);
  io::write_provenance(w);
  write_system(w, p, c.name);
  w.commit();
}

int run(const config::Case& c, const RunRequest& req, std::ostream& out) {
  std::ostringstream ignored;
  check(c, ignored);  // the same refusals as `granwave check`
  Packing packing;
  if (req.system_path.empty()) {
    packing = make_packing(c);
  } else {
    packing = read_system(req.system_path);
    check_system_matches(c, packing, req.system_path);
  }
  const std::string trace_path = trace_path_for(c, req);
  std::unique_ptr<VtkSeries> vtk;
  SampleHook hook;
  if (c.output.vtk_every > 0) {
    const auto dot = trace_path.rfind(".h5");
    vtk = std::make_unique<VtkSeries>(dot == std::string::npos ? trace_path : trace_path.substr(0, dot));
    hook = [&](const Dynamics& dyn, std::size_t sample) {
      if (sample % static_cast<std::size_t>(c.output.vtk_every) == 0) vtk->write(dyn);
    };
  }
  const RunResult r = simulate(c, packing, hook);
  if (vtk) vtk->finish();
  write_trace(c, packing, r, trace_path);
  if (r.failed) throw RunError(r.error + " (samples so far kept in " + trace_path + ")");

  const Traces& t = r.traces;
  const Derived d = derive(c);
  const bool shear = c.excitation.mode == config::Excitation::Mode::S;
  const FrontSpeeds fs = front_speeds(t, packing.l0, shear);
  const std::size_t last = t.samples() - 1;
  auto total = [&](std::size_t k) { return t.kinetic[k] + t.potential[k] + t.dissipated[k] - t.work_in[k]; };
  const double residual = total(last) - total(0);
  const double shadow_residual = residual - (t.verlet_correction[last] - t.verlet_correction[0]);
  const double pss = static_cast<double>(packing.size()) * r.steps / std::max(r.seconds, 1e-12);
  if (req.json) {
    out << std::setprecision(10) << "{\"case\": \"" << c.name << "\", \"model\": \"crystal\", \"trace\": \""
        << trace_path << "\", \"particles\": " << packing.size() << ", \"steps\": " << r.steps
        << ", \"samples\": " << t.samples() << ", \"wall_seconds\": " << r.seconds
        << ", \"particle_steps_per_second\": " << pss << ", \"mode\": \"" << (shear ? "S" : "P")
        << "\", \"layers_fitted\": " << fs.layers << ", \"z_over_l0\": [" << fs.z_min << ", " << fs.z_max
        << "], \"speed_first_peak\": " << fs.first_peak.slope << ", \"speed_first_peak_error\": "
        << fs.first_peak.slope_error << ", \"speed_half_peak\": " << fs.half_peak.slope
        << ", \"speed_half_peak_error\": " << fs.half_peak.slope_error << ", \"speed_theory\": "
        << (shear ? d.v_s : d.v_p) << ", \"coordination\": " << t.coordination[0]
        << ", \"work_in\": " << t.work_in[last] << ", \"dissipated\": " << t.dissipated[last]
        << ", \"energy_residual\": " << residual << ", \"energy_residual_shadow\": " << shadow_residual << "}\n";
  } else {
    out << std::setprecision(5);
    out << "crystal " << c.name << ": " << packing.size() << " particles, " << r.steps << " steps in " << r.seconds
        << " s (" << pss << " particle-steps/s), " << r.rebuilds << " contact-list builds\n";
    out << "  coordination " << t.coordination[0] << " -> " << t.coordination[last] << "\n";
    if (fs.layers >= 2)
      out << "  " << (shear ? "S" : "P") << " front over z/l0 = " << fs.z_min << ".." << fs.z_max << " (" << fs.layers
          << " layers): first peak " << fs.first_peak.slope << " +- " << fs.first_peak.slope_error
          << " m/s, half peak " << fs.half_peak.slope << " +- " << fs.half_peak.slope_error << " m/s (theory "
          << (shear ? d.v_s : d.v_p) << " m/s)\n";
    else
      out << "  the front reaches fewer than 2 layers with z/l0 in 10..150: no speed\n";
    out << "  energy: work_in " << t.work_in[last] << " J, dissipated " << t.dissipated[last]
        << " J, balance residual " << residual << " J (" << shadow_residual << " J after the Verlet correction)\n";
    out << "  trace: " << trace_path << "\n";
    if (vtk) out << "  snapshots: " << vtk->collection_path() << " (" << vtk->files().size() << " files)\n";
  }
  return 0;
}

}  // namespace granwave::crystal
