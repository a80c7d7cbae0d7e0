// Entry points of the crystal model (src/models.hpp): check, build, run.
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <iomanip>
#include <iostream>
#include <limits>
#include <memory>
#include <optional>
#include <ostream>

#include "analysis/report.hpp"
#include "analysis/trace_analysis.hpp"
#include "config/contact_laws.hpp"
#include "core/error.hpp"
#include "core/json.hpp"
#include "crystal/case_lattice.hpp"
#include "crystal/guards.hpp"
#include "crystal/observables.hpp"
#include "crystal/packing.hpp"
#include "crystal/simulation.hpp"
#include "crystal/trace_writer.hpp"
#include "crystal/vtk.hpp"
#include "io/h5.hpp"
#include "models.hpp"
#include "packing/prepared_state.hpp"
#include "theory/crystal_theory.hpp"
#include "theory/lattice_dynamics.hpp"

namespace granwave::crystal {

namespace {

// A packing given as a system file must be the case's crystal.
void check_system_matches(const config::Case& c, const Packing& p, const std::string& path) {
  const auto& k = *c.crystal;
  if (k.from_file() || p.from_file()) {
    if (!k.from_file() || !p.from_file() || p.size() != k.imported->particles.size() ||
        std::abs(p.bin_width - k.packing_file->bin_width) > 1e-12 * p.bin_width)
      throw InputError(path + ": the system's packing (generator, particle count, bin width) is not the one of " + c.path);
    return;
  }
  if (p.nx != k.cells[0] || p.ny != k.cells[1] || p.layers != k.cells[2] || p.fixed_layers != k.fixed_layers ||
      std::abs(p.d - 2.0 * k.radius) > 1e-12 * p.d)
    throw InputError(path + ": the system's packing (cells, fixed layers, radius) is not the one of " + c.path);
}

// The time loop's phases (RunResult::phases) as a JSON object {name: seconds}.
Json phases_json(const PhaseTimes& t) {
  Json o = Json::object();
  for (std::size_t k = 0; k < t.seconds.size(); ++k) o[t.names[k]] = t.seconds[k];
  return o;
}

// The same as one line: "phases: kick+drift 0.41 s (18%), ...".
std::string phases_line(const PhaseTimes& t) {
  const double total = std::max(t.total(), 1e-300);
  std::ostringstream o;
  o << "phases:";
  for (std::size_t k = 0; k < t.seconds.size(); ++k) {
    std::string name = t.names[k];
    for (char& ch : name) ch = ch == '_' ? ' ' : ch;
    if (name == "kick drift") name = "kick+drift";
    o << (k ? ", " : " ") << name << " " << std::setprecision(3) << t.seconds[k] << " s (" << std::setprecision(2)
      << 100.0 * t.seconds[k] / total << "%)";
  }
  return o.str();
}

// `granwave check`'s lines for a packing from a file: where from, slabs, bins, the network.
void describe_file_packing(const config::Case& c, const Packing& p, std::ostream& out) {
  const config::PackingKeys& keys = *c.crystal->packing_file;
  std::size_t source = 0, top = 0;
  for (std::uint8_t r : p.role) source += r == role_source, top += r == role_fixed_top;
  const auto contacts = list_contacts(p, true);
  if (c.crystal->random) {
    const packing::Preparation& q = *c.crystal->preparation;
    out << "crystal case " << c.name << ": " << p.size() << " particles, random (seed " << c.crystal->random->seed
        << "), prepared at " << c.crystal->random->pressure << " Pa: box " << p.box_x << " x " << p.box_y << " x "
        << c.crystal->imported->box.length(2) << " m, z cut open\n";
    out << "  preparation: " << q.steps << " steps of " << q.time_step << " s; pressure " << q.pressure
        << " Pa, E_kin/E_pot " << q.kinetic_ratio << ", unbalanced force " << q.unbalanced_force
        << " of the mean contact force; solid fraction " << q.solid_fraction << ", coordination " << q.coordination
        << " (" << q.coordination_backbone << " without the " << q.rattlers << " rattlers)\n";
    if (c.crystal->random->friction > 0.0)
      out << "  with friction mu = " << c.crystal->random->friction << ": unbalanced torque " << q.unbalanced_torque
          << " of the mean contact force x mean radius, " << q.sliding << " contacts sliding, " << p.springs.size()
          << " tangential springs (not relaxed: it stands on them)\n";
  } else {
    out << "crystal case " << c.name << ": " << p.size() << " particles from " << keys.file << " (" << keys.format
        << "), box " << p.box_x << " x " << p.box_y << " x " << c.crystal->imported->box.length(2) << " m, z cut open\n";
  }
  out << "  mean diameter " << p.d << " m; " << contacts.size() << " contacts (" << 2.0 * contacts.size() / p.size()
      << " per particle), mean overlap " << c.crystal->overlap << " of the mean diameter\n";
  out << "  source slab " << keys.source_thickness << " m (" << source << " particles), top slab " << keys.fixed_thickness
      << " m (" << top << " particles), " << p.layers << " z-bins of " << p.bin_width << " m from z = " << p.bin_origin
      << " m\n";
  std::size_t differ = 0;
  for (const auto& q : c.crystal->imported->particles) differ += std::isfinite(q.density) &&
                                                                  std::abs(q.density - c.crystal->density) > 1e-9 * c.crystal->density;
  if (!c.crystal->random)
    out << "  masses: " << (keys.density_from_file ? "the file's" : "crystal.density x 4/3 pi r^3 (the case's density wins)");
  if (!c.crystal->random && !keys.density_from_file) out << "; " << differ << " particles' file densities differ from the case's";
  out << (c.crystal->random ? "" : "\n") << "  relaxed before the wave until E_kin/E_pot < " << keys.relax_tolerance
      << " (frictionless, the case's normal law, slabs held)\n";
}

std::string trace_path_for(const config::Case& c, const RunRequest& req) {
  return req.trace_path.empty() ? c.name + ".h5" : req.trace_path;
}

}  // namespace

void check(const config::Case& c, std::ostream& out, const ResourceLimits& limits) {
  std::optional<Derived> derived;
  const Assessment a = assess(c, limits, &derived);  // before anything is allocated (crystal/guards.hpp)
  enforce(a, c.path);
  const Derived& d = *derived;
  const Packing p = initial_packing(c);  // refuses a packing that does not fit its box
  const auto& k = *c.crystal;
  out << std::setprecision(6);
  if (k.from_file()) {
    describe_file_packing(c, p, out);
  } else {
    out << "crystal case " << c.name << ": " << p.size() << " particles (" << k.cells[0] << " x " << k.cells[1] << " x "
        << k.cells[2] << " layers, " << k.fixed_layers << " fixed at each end)\n";
    out << "  d = " << p.d << " m, d' = d(1 - overlap) = " << p.d_prime << " m, l0 = d'/sqrt(2) = " << p.l0
        << " m, delta = " << p.delta << " m, box " << p.box_x << " x " << p.box_y << " m\n";
  }
  out << "  mass m = " << d.mass << " kg, m_ij = " << d.m_ij << " kg\n";
  const config::ContactLawInfo& law = config::law_of(c.contact);
  out << (law.stiffness_of_overlap ? "  contact linearised at delta_0" : "  contact") << ": omega = sqrt(k/m_ij - eta_0^2) = " << d.omega << " 1/s, t_c = pi/omega = " << d.t_c
      << " s, restitution exp(-eta_0 t_c) = " << d.restitution
      << (c.contact.friction().clip() ? " (\"allow\" value; \"clip\" ends earlier)" : "")
      << "\n";
  out << "  dt = " << d.dt << " s = t_c/" << d.t_c / d.dt << "; stability limit (conservative"
      << (k.from_file() ? ", z = " + std::to_string(d.max_coordination) + " contacts, the network's largest" : std::string()) << ") "
      << d.dt_stable << " s; " << d.steps << " steps, a sample every " << d.sample_every << " steps\n";
  out << law.check_line(c.contact, {d.f0, d.kn, d.kt, d.gamma_n, 0.0});  // at delta_0
  if (k.from_file()) {
    out << "  prestress sigma_0 = Love-Weber sigma_zz of the imported network under the case's law = " << d.sigma_0 << " Pa\n";
    out << "  predicted speeds along z (eq. 10 over the packing's contact network, affine): V_p = " << d.v_p
        << " m/s, V_s = " << d.v_s << " m/s (frictionless)\n";
  } else {
    out << "  prestress sigma_0 = " << law.prestress_formula << " = " << d.sigma_0 << " Pa\n";
    out << "  predicted speeds along z (eq. 10, branch d'): V_p = " << d.v_p << " m/s"
        << (d.kt > 0.0 ? " (affine, sqrt(1 + kt/k))" : "") << ", V_s = " << d.v_s << " m/s (frictionless)\n";
  }
  out << law.tangential_line(c.contact);
  if (k.polydispersity > 0.0)
    out << "  polydisperse: radii a +- " << k.polydispersity * p.delta << " m (seed " << k.seed
        << "); relaxed until E_kin/E_pot < " << k.relax_tolerance << "\n";
  out << "  resources: " << describe(a.estimate, limits) << "\n";
  for (const auto& w : a.warnings) out << "warning: " << w << "\n";
}

void build(const config::Case& c, const std::string& system_path) {
  ResourceLimits no_step_limit;  // build does not run: only the packing's memory and meaning count
  no_step_limit.max_steps = std::numeric_limits<double>::infinity();
  std::optional<Derived> derived;
  enforce(assess(c, no_step_limit, &derived), c.path);
  const Packing p = make_packing(c);
  io::H5Writer w(system_path);
  io::write_provenance(w);
  write_system(w, p, c.name);
  const config::CrystalCase& k = *c.crystal;
  if (k.random && k.imported && k.preparation) {  // what a run from this file takes instead of preparing it again
    packing::PreparedState st;
    st.packing = *k.imported;
    st.preparation = *k.preparation;
    st.pressure_target = k.random->pressure;
    st.seed = k.random->seed;
    st.friction = k.random->friction;
    packing::write_prepared_group(w, st);
  }
  // The resolved time step, so that the other codes' drivers need not linearise the law for dt_over_tc.
  w.attr("/", "dt", derived->dt);
  w.commit();
}

int run(const config::Case& c, const RunRequest& req, std::ostream& out_all) {
  const std::string trace_path = trace_path_for(c, req);
  // Under mpirun with R > 1: this rank's slab of the run (crystal/slab.hpp). Every rank runs
  // the same code on the same case; rank 0 alone writes the trace and prints.
  const std::shared_ptr<SlabComm> comm = world_slab_comm();
  const int ranks = comm ? comm->ranks() : 1;
  const bool root = !comm || comm->rank() == 0;
  std::ostream none(nullptr);
  std::ostream& out = root ? out_all : none;
  std::ostream& err = root ? std::cerr : none;
  if (ranks > 1 && c.crystal->from_file())
    throw InputError(c.path + ": crystal.lattice = \"" + c.crystal->lattice + "\": a packing that is not a lattice runs on one MPI rank only (the slabs "
                     "of an MPI run are whole FCC layers); run without mpirun");
  if (ranks > 1) {
    const int nl = c.crystal->cells[2];
    if (ranks > max_slab_ranks(nl))
      throw InputError(c.path + ": crystal.cells[2] = " + std::to_string(nl) + " layers cannot be split over " +
                       std::to_string(ranks) + " MPI ranks: each rank owns whole layers, so at most " +
                       std::to_string(max_slab_ranks(nl)) + " ranks");
    if (c.output.vtk_every > 0)
      throw InputError(c.path + ": output.vtk_every = " + std::to_string(c.output.vtk_every) +
                       ": VTK snapshots are not written by a run split over MPI ranks (set 0, or run without mpirun)");
  }
  std::optional<Derived> derived;  // the case derived once, for the guards, the run and the summary
  Assessment a = assess(c, req.limits, &derived);  // the refusals of `granwave check`, before anything is allocated
  if (!req.in_memory) check_output_space(a, trace_path);
  enforce(a, c.path);
  const Derived& d = *derived;
  for (const auto& w : a.warnings) err << "granwave run: warning: " << w << "\n";
  Packing packing;
  if (req.system_path.empty()) {
    packing = make_packing(c);
  } else {
    packing = read_system(req.system_path);
    check_system_matches(c, packing, req.system_path);
  }
  std::unique_ptr<VtkSeries> vtk;
  SampleHook hook;
  if (c.output.vtk_every > 0 && !req.in_memory) {
    const auto dot = trace_path.rfind(".h5");
    vtk = std::make_unique<VtkSeries>(dot == std::string::npos ? trace_path : trace_path.substr(0, dot));
    hook = [&](const Dynamics& dyn, std::size_t sample) {
      if (sample % static_cast<std::size_t>(c.output.vtk_every) == 0) vtk->write(dyn);
    };
  }
  // What the summary needs from the run; its series are freed before the analysis reads them back.
  double work_in = 0.0, dissipated = 0.0, residual = 0.0, shadow_residual = 0.0, seconds = 0.0;
  double coordination0 = 0.0, coordination_end = 0.0;
  long steps = 0, rebuilds = 0, relists = 0;
  std::size_t samples = 0;
  std::vector<double> rank_seconds, rank_message_seconds, rank_cpu_seconds, rank_message_cpu_seconds;
  PhaseTimes phases;
  std::unique_ptr<io::H5Reader> kept_trace;  // the trace, when it lives in memory only
  {
    RunResult r = simulate(c, d, packing, hook, comm, root ? ProgressHook(req.progress) : ProgressHook());
    if (vtk) vtk->finish();
    if (root) {
      io::H5Writer w(trace_path, req.in_memory ? io::H5Writer::Storage::memory : io::H5Writer::Storage::disk);
      write_trace(c, packing, r, w);
      if (req.in_memory) kept_trace = std::make_unique<io::H5Reader>(w);
      w.commit();
    }
    if (r.failed)  // on every rank
      throw RunError(r.error + (req.in_memory ? std::string() : " (samples so far kept in " + trace_path + ")"));
    const Traces& t = r.traces;
    const std::size_t last = t.samples() - 1;
    auto total = [&](std::size_t k) { return t["kinetic"][k] + t["potential"][k] + t["dissipated"][k] - t["work_in"][k]; };
    residual = total(last) - total(0);
    shadow_residual = residual - (t["verlet_correction"][last] - t["verlet_correction"][0]);
    work_in = t["work_in"][last];
    dissipated = t["dissipated"][last];
    coordination0 = t["coordination"][0];
    coordination_end = t["coordination"][last];
    steps = r.steps;
    rebuilds = r.rebuilds;
    relists = r.relists;
    seconds = r.seconds;
    samples = t.samples();
    rank_seconds = r.rank_seconds;
    rank_message_seconds = r.rank_message_seconds;
    rank_cpu_seconds = r.rank_cpu_seconds;
    rank_message_cpu_seconds = r.rank_message_cpu_seconds;
    phases = r.phases;
    if (root && req.keep) req.keep(take_series(c, std::move(r.traces)));
  }
  if (!root) return 0;

  // The measures: `granwave analyze` of the trace just written (one ruler, src/analysis).
  // The case's lattice, solved once: the analysis's branches (when the wave turns the particles)
  // and the long-wave speed of the summary.
  analysis::CrystalAnalysisOptions measure;
  double v_lattice = 0.0;
  add_case_lattice(measure, c, d, LatticeNeed::when_not_sine, &v_lattice);
  // (a packing's bins: the analysis takes its slabs, fit range and pulse field from the trace's roles)
  // Read back only what the measures read: the file was written whole just now, and the other
  // series would cost their reads, checksums and memory for nothing (`analyze` reads them all).
  const bool shear = c.excitation.mode == config::Excitation::Mode::S;
  const std::vector<std::string> measured = analysis::measured_series(shear ? 'S' : 'P');
  std::vector<Observable> read_back;
  for (const Observable& o : observables())
    if (std::find(measured.begin(), measured.end(), o.name) != measured.end()) read_back.push_back(o);
  const analysis::FileReport rep = kept_trace ? analysis::report_file(*kept_trace, read_back, measure)
                                                 : analysis::report_file(trace_path, read_back, measure);
  const double pss = static_cast<double>(packing.size()) * steps / std::max(seconds, 1e-12);
  if (req.json) {
    Json j = {{"schema", "granwave-run/1"},
              {"case", c.name},
              {"model", "crystal"},
              {"trace", trace_path},
              {"particles", packing.size()},
              {"steps", steps},
              {"samples", samples},
              {"mpi_ranks", ranks},
              {"mpi_rank_seconds", rank_seconds},
              {"mpi_rank_message_seconds", rank_message_seconds},
              {"mpi_rank_cpu_seconds", rank_cpu_seconds},
              {"mpi_rank_message_cpu_seconds", rank_message_cpu_seconds},
              {"wall_seconds", seconds},
              {"phases", phases_json(phases)},
              {"particle_steps_per_second", pss},
              {"mode", shear ? "S" : "P"},
              {"speed_theory", shear ? d.v_s : d.v_p},
              {"speed_theory_lattice", v_lattice},
              {"coordination", coordination0},
              {"coordination_end", coordination_end},
              {"contact_list_builds", rebuilds},  // the construction's build included
              {"contact_list_relists", relists},
              {"work_in", work_in},
              {"dissipated", dissipated},
              {"energy_residual", residual},
              {"energy_residual_shadow", shadow_residual},
              {"warnings", a.warnings}};
    j["analysis_error"] = rep.error.empty() ? Json(nullptr) : Json(rep.error);
    j["analysis"] = rep.json;
    out << json_text(j);
  } else {
    out << std::setprecision(5);
    out << "crystal " << c.name << ": " << packing.size() << " particles, " << steps << " steps in " << seconds << " s (" << pss
        << " particle-steps/s), " << rebuilds << " contact-list builds, " << relists
        << " relists of the close pairs\n";
    out << "  " << phases_line(phases) << (ranks > 1 ? " (rank 0)" : "") << "\n";
    if (ranks > 1) {
      out << "  split over " << ranks << " MPI ranks (slabs of whole layers, docs/design.md §2.8); per rank, time loop"
          << " wall / of it in MPI calls, CPU / of it in MPI calls (s):";
      for (int q = 0; q < ranks; ++q)
        out << (q ? "," : "") << " " << rank_seconds[q] << " / " << rank_message_seconds[q] << ", " << rank_cpu_seconds[q]
            << " / " << rank_message_cpu_seconds[q];
      out << "\n";
    }
    out << "  coordination " << coordination0 << " -> " << coordination_end << "\n";
    const bool kt = d.kt > 0.0;  // Hertz-Mindlin: k_t linearised at delta_0
    out << "  theory: " << (shear ? "V_s = " : "V_p = ") << (shear ? d.v_s : d.v_p) << " m/s ("
        << (shear && kt ? "eq. 10 without its kt term" : "eq. 10")
        << (packing.from_file() ? " over the packing's contact network, affine" : ", branch d'")
        << (!shear && kt ? ", affine kt" : "") << "), ";
    if (std::isfinite(v_lattice))
      out << v_lattice << " m/s (lattice dynamics with rotations and prestress"
          << (shear && kt ? ", the prediction with kt > 0" : "") << ")\n";
    else
      out << "lattice dynamics: none (not a Bravais lattice)\n";
    out << "  energy: work_in " << work_in << " J, dissipated " << dissipated << " J, balance residual " << residual
        << " J (" << shadow_residual << " J after the Verlet correction)\n";
    out << "  trace: " << trace_path << "\n";
    if (vtk) out << "  snapshots: " << vtk->collection_path() << " (" << vtk->files().size() << " files)\n";
    out << rep.text;
  }
  return 0;
}

}  // namespace granwave::crystal
