// The study of sound against pressure in random packings (see packing_study.hpp): members, one
// member's preparation, moduli and pulses, and the runner. The study file and its table are
// packing_study_file.cpp.
#include "sweep/packing_study.hpp"

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <functional>
#include <iostream>
#include <mutex>
#include <sstream>

#include "analysis/trace_analysis.hpp"
#include "config/contact_laws.hpp"
#include "config/toml_reader.hpp"
#include "core/error.hpp"
#include "core/format.hpp"
#include "core/numbers.hpp"
#include "crystal/packing.hpp"
#include "crystal/relaxed_inputs.hpp"
#include "crystal/simulation.hpp"
#include "crystal/trace_writer.hpp"
#include "io/h5.hpp"
#include "packing/contacts.hpp"
#include "sweep/distributed.hpp"
#include "sweep/packing_path.hpp"
#include "theory/effective_medium.hpp"
#include "theory/relaxed_moduli.hpp"

namespace granwave::sweep {

const std::vector<std::string>& packing_value_names() {
  static const std::vector<std::string> n = {
      "pressure_target", "width", "seed", "count", "pressure", "prepare_steps", "prepare_minimise_steps", "prepare_unbalanced",
      "prepare_kinetic_ratio", "solid_fraction", "coordination", "coordination_backbone", "rattlers", "prepare_seconds",
      "bulk_pressure", "bulk_unbalanced", "bulk_coordination", "bulk_rattlers", "bulk_fire_steps", "bulk_unstable", "bulk_mechanisms", "rho",
      "K_affine", "G_affine", "K_relaxed", "G_relaxed", "K_walton", "G_walton", "G_walton_smooth", "V_pz_relaxed",
      "V_sz_relaxed", "V_pz_affine", "V_sz_affine", "height", "amplitude", "mean_overlap", "V_p_first_peak",
      "V_p_first_peak_err", "V_p_half_peak", "V_p_half_peak_err", "V_s_first_peak", "V_s_first_peak_err",
      "V_s_half_peak", "V_s_half_peak_err", "steps", "seconds"};
  return n;
}

std::vector<PackingMember> packing_members(const PackingStudy& s) {
  std::vector<PackingMember> m;
  std::vector<std::optional<double>> widths(s.widths.begin(), s.widths.end());
  if (widths.empty()) widths.push_back(std::nullopt);
  for (double p : s.pressures)
    for (const auto& w : widths)
      for (std::int64_t seed : s.seeds) m.push_back({p, w, seed});
  return m;
}

std::string member_case_text(const PackingStudy& s, const PackingMember& m, char mode, const std::string& start) {
  toml::table root = config::parse_toml(s.case_text, s.case_path);
  toml::table& random = *root["random"].as_table();
  random.insert_or_assign("pressure", m.pressure);
  random.insert_or_assign("seed", m.seed);
  if (s.count) random.insert_or_assign("count", *s.count);
  if (m.width) {
    random.insert_or_assign("distribution", std::string("uniform"));
    random.insert_or_assign("width", *m.width);
  }
  if (!start.empty()) random.insert_or_assign("start", start);
  if (!s.shape.empty()) random.insert_or_assign("shape", toml::array{s.shape[0], s.shape[1], s.shape[2]});
  if (!root["excitation"].as_table()) root.insert_or_assign("excitation", toml::table{});
  root["excitation"].as_table()->insert_or_assign("mode", std::string(1, mode));
  std::ostringstream out;
  out << root << "\n";
  return out.str();
}

IsotropicModuli isotropic_moduli(const theory::Tensor4& A, const Eigen::Matrix3d& stress) {
  // C_abgf = A_abgf + S_ag delta_bf (relaxed_moduli.hpp: A = C + sigma_ag delta_bf, sigma = -S).
  const auto C = [&](int a, int b, int g, int f) { return A(a, b, g, f) + (b == f ? stress(a, g) : 0.0); };
  double aagg = 0.0, abab = 0.0, abba = 0.0;
  for (int a = 0; a < 3; ++a)
    for (int b = 0; b < 3; ++b) {
      aagg += C(a, a, b, b);
      abab += C(a, b, a, b);
      abba += C(a, b, b, a);
    }
  return {aagg / 9.0, (0.5 * (abab + abba) - aagg / 3.0) / 10.0};
}

namespace {

// Walton's effective medium (Hertz-Mindlin laws only) at Z, phi, p.
void walton_values(const config::Case& c, double Z, double phi, double p, std::vector<double>& v) {
  if (!config::law_of(c.contact).hertz_normal) return;
  const double E = c.contact.number("youngs_modulus").value(), nu = c.contact.number("poisson_ratio").value();
  const auto w = theory::walton_hertz_mindlin(Z, phi, E / (2.0 * (1.0 + nu)), nu, p, phi * c.crystal->density);
  v[pv_K_walton] = w.K, v[pv_G_walton] = w.G, v[pv_G_walton_smooth] = w.G_smooth;
}

// The relaxed triply periodic bulk of the member's prepared packing (as `granwave theory` relaxes a
// file's packing), its isotropic moduli and the effective medium at its Z, phi and p.
void bulk_values(const config::Case& c, const crystal::Packing& pk, std::vector<double>& v) {
  theory::RelaxedOptions opt = crystal::relaxed_slab_options(c, pk);
  // 1e-6 of the mean contact force, not `granwave theory`'s 1e-10: 4000 Hertz spheres at 10 kPa did
  // not reach 1e-10 in 400 000 FIRE steps (the soft modes near jamming); the residual is recorded.
  const crystal::PeriodicBulk pb = crystal::periodic_bulk(c, 1e-6, 400000);
  v[pv_bulk_unbalanced] = pb.unbalanced;
  opt.prescribed.clear();
  opt.boundary = theory::RelaxedBoundary::bulk;
  opt.box_z = pb.box_z;
  opt.unstressed = false;
  const theory::RelaxedModuli R = theory::relaxed_moduli(pb.net, opt);
  v[pv_bulk_pressure] = R.pressure;
  v[pv_bulk_coordination] = R.coordination;
  v[pv_bulk_rattlers] = R.rattlers;
  v[pv_bulk_fire_steps] = static_cast<double>(pb.steps);
  v[pv_bulk_unstable] = R.unstable_modes;
  v[pv_bulk_mechanisms] = R.mechanisms;
  v[pv_rho] = R.rho;
  const IsotropicModuli affine = isotropic_moduli(R.affine, R.stress), relaxed = isotropic_moduli(R.relaxed, R.stress);
  v[pv_K_affine] = affine.K, v[pv_G_affine] = affine.G;
  v[pv_K_relaxed] = relaxed.K, v[pv_G_relaxed] = relaxed.G;
  v[pv_V_pz_relaxed] = R.V_pz, v[pv_V_sz_relaxed] = R.V_sz;
  v[pv_V_pz_affine] = R.V_pz_affine, v[pv_V_sz_affine] = R.V_sz_affine;
  double vs = 0.0;
  for (double a : pk.radius) vs += 4.0 / 3.0 * std::numbers::pi * a * a * a;
  if (R.coordination > 0.0) walton_values(c, R.coordination, vs / R.volume, R.pressure, v);
}


// The P and S pulses through the packing cut open in z (steps of both runs); fills the pulse values.
long pulses(const PackingStudy& s, const PackingMember& m, const config::Case& c, const crystal::Packing& pk,
            std::vector<double>& v, const StudyControl* control) {
  const packing::Packing& periodic = *c.crystal->imported;

  // The step: a fixed fraction of the mean static overlap (per mean diameter), the wave's
  // nonlinearity the same at every pressure.
  double overlap = 0.0, d_mean = 0.0;
  const auto touches = packing::touching_pairs(periodic);
  for (const auto& t : touches) overlap += t.overlap;
  for (const auto& p : periodic.particles) d_mean += 2.0 * p.radius;
  d_mean /= static_cast<double>(periodic.particles.size());
  v[pv_mean_overlap] = touches.empty() ? kNaN : overlap / touches.size() / d_mean;
  v[pv_height] = periodic.box.length(2);
  v[pv_amplitude] = s.amplitude * v[pv_mean_overlap];

  long steps = 0;
  crystal::ProgressHook stop;
  if (control) stop = [control](long, long) { stop_point(control); };
  for (char mode : s.modes) {
    config::Case cm = c;
    cm.excitation.mode = mode == 'S' ? config::Excitation::Mode::S : config::Excitation::Mode::P;
    if (cm.excitation.drive == config::Excitation::Drive::displacement) cm.excitation.amplitude = v[pv_amplitude];
    // The run covers the column run_length times at the relaxed speed (the effective medium's when
    // the bulk could not be relaxed), sampled samples_per_bin times per bin delay.
    const bool S = mode == 'S';
    double speed = S ? v[pv_V_sz_relaxed] : v[pv_V_pz_relaxed];
    if (!(speed > 0.0)) speed = std::sqrt((S ? v[pv_G_walton] : v[pv_K_walton] + 4.0 / 3.0 * v[pv_G_walton]) / v[pv_solid_fraction] / c.crystal->density);
    if (!(speed > 0.0)) throw RunError(cm.path + ": no speed to size the run by (neither a relaxed bulk nor an effective medium)");
    cm.integrator.t_end = s.run_length * v[pv_height] / speed;
    const crystal::Derived der = crystal::derive(cm);
    cm.output.interval = std::max(der.dt, pk.bin_width / speed / s.samples_per_bin);
    cm.output.vtk_every = 0;
    cm.name = s.name + "_" + fmt("%g", m.pressure) + "_" + std::to_string(m.seed) + "_" + mode;
    const crystal::RunResult run = crystal::simulate(cm, der, pk, {}, nullptr, stop);
    if (run.failed) throw RunError(cm.name + ": " + run.error);
    steps += run.steps;
    const analysis::CrystalAnalysis a = analysis::analyze_crystal(crystal::analysis_trace(cm, pk, run.traces));
    const std::size_t k = S ? pv_V_s_first_peak : pv_V_p_first_peak;
    v[k] = a.v_first_peak.speed.value;
    v[k + 1] = a.v_first_peak.speed.error;
    v[k + 2] = a.v_half_peak.speed.value;
    v[k + 3] = a.v_half_peak.speed.error;
  }
  return steps;
}

}  // namespace

MemberResult run_packing_member(const PackingStudy& s, std::size_t index, const StudyControl* control) {
  const PackingMember m = packing_members(s).at(index);
  std::vector<double> v(packing_value_names().size(), kNaN);
  v[pv_pressure_target] = m.pressure;
  v[pv_seed] = static_cast<double>(m.seed);
  v[pv_width] = m.width.value_or(0.0);
  const double t0 = wall_seconds();
  // Loading the case prepares the packing (config/random_loader.hpp), with its progress lines; on a
  // compression path from the member's saved stage (static at its pressure: no step is taken), and
  // the preparation recorded is the stage's own (from the previous pressure, or the gas).
  std::optional<packing::PreparedState> stage;
  std::string start;
  if (s.preparation_path == PackingStudy::Path::compression) {
    start = ensure_path_stages(s, m, control);
    stage = packing::load_prepared(start);
  }
  const config::Case c = config::parse_case(member_case_text(s, m, s.modes.front(), start), s.case_path);
  v[pv_prepare_seconds] = stage ? stage->seconds : wall_seconds() - t0;
  const packing::Packing& periodic = *c.crystal->imported;
  const packing::Preparation& prep = stage ? stage->preparation : *c.crystal->preparation;
  v[pv_count] = static_cast<double>(periodic.particles.size());
  v[pv_pressure] = prep.pressure;
  v[pv_prepare_steps] = static_cast<double>(prep.steps);
  v[pv_prepare_minimise_steps] = static_cast<double>(prep.minimise_steps);
  v[pv_prepare_unbalanced] = prep.unbalanced_force;
  v[pv_prepare_kinetic_ratio] = prep.kinetic_ratio;
  v[pv_solid_fraction] = prep.solid_fraction;
  v[pv_coordination] = prep.coordination;
  v[pv_coordination_backbone] = prep.coordination_backbone;
  v[pv_rattlers] = static_cast<double>(prep.rattlers);
  stop_point(control);

  // A failure after the preparation costs the member what depends on it (NaN, the label says why),
  // not the study its other members.
  std::string note;
  const auto noted = [&](const char* what, const std::function<void()>& f) {
    try {
      f();
      return true;
    } catch (const RunError& e) {
      note += std::string(" (") + what + ": " + e.what() + ")";
    } catch (const InputError& e) {
      note += std::string(" (") + what + ": " + e.what() + ")";
    }
    return false;
  };
  crystal::Packing pk;
  long steps = 0;
  if (noted("not cut open", [&] { pk = crystal::make_packing(c); })) {  // the source and top slabs, relaxed
    // Without the relaxed bulk, the effective medium at the preparation's z*, Phi and p.
    if (!noted("no relaxed bulk", [&] { bulk_values(c, pk, v); }))
      walton_values(c, prep.coordination_backbone, prep.solid_fraction, prep.pressure, v);
    stop_point(control);
    noted("no pulses", [&] { steps = pulses(s, m, c, pk, v, control); });
  }
  v[pv_steps] = static_cast<double>(steps);
  v[pv_seconds] = wall_seconds() - t0;

  MemberResult r;
  r.index = static_cast<std::int64_t>(index);
  r.values = std::move(v);
  r.label = "p=" + fmt("%g", m.pressure) + (m.width ? " width=" + fmt("%g", *m.width) : std::string()) + " seed=" + std::to_string(m.seed) + note;
  r.work = static_cast<double>(periodic.particles.size()) * static_cast<double>(prep.steps + steps);
  return r;
}


std::vector<MemberResult> run_packing_study(const PackingStudy& s, const std::string& out_path, std::ostream& out,
                                            const PackingRunOptions& opt, RunStats* stats) {
  const auto members = packing_members(s);
  RunnerOptions ro;
  ro.parts_dir = out_path + ".parts";
  ro.fingerprint = packing_study_fingerprint(s);
  ro.value_names = packing_value_names();
  ro.batch = s.batch;
  ro.threads = opt.threads;
  ro.progress = !opt.quiet;
  ro.what = "packings";
  ro.limit = opt.limit;
  ro.control = opt.control;
  // Every pressure's first seed before any second one (an interrupted study has the whole curve
  // soonest), and within a seed the low pressures first (they prepare longest).
  // On a compression path a seed's pressures come in order (each loads the previous one's packing):
  // every seed's lowest pressure first, then every seed's next.
  const bool path = s.preparation_path == PackingStudy::Path::compression;
  PackingStudy sp = s;
  if (path) sp.path_dir = std::filesystem::absolute(out_path + ".path").string();
  for (const auto& m : members) {
    const auto rank = std::find(s.seeds.begin(), s.seeds.end(), m.seed) - s.seeds.begin();
    const auto p_rank = std::find(s.pressures.begin(), s.pressures.end(), m.pressure) - s.pressures.begin();
    ro.cost.push_back(path ? static_cast<double>(s.pressures.size() - p_rank) + 0.5 / (1.0 + static_cast<double>(rank))
                           : static_cast<double>(s.seeds.size() - rank) + 0.5 / (1.0 + std::log10(m.pressure)));
  }
  std::mutex log_mutex;
  RunStats st;
  const std::vector<MemberResult> done =
      read_finished_study(out_path, ro.fingerprint, members.size(), packing_value_names().size());
  if (!done.empty()) st.total = st.resumed = done.size();
  const auto results = !done.empty() ? done : run_members(
      members.size(),
      [&](std::size_t i) {
        MemberResult r = run_packing_member(sp, i, opt.control);
        if (!opt.quiet) {
          const auto& v = r.values;
          std::lock_guard<std::mutex> lock(log_mutex);
          std::cerr << "  " << s.name << " [" << i + 1 << "/" << members.size() << "] " << r.label << ": Phi "
                    << fmt("%.4f", v[pv_solid_fraction]) << ", z* " << fmt("%.3f", v[pv_coordination_backbone])
                    << ", K/G relaxed " << fmt("%.4g", v[pv_K_relaxed]) << "/" << fmt("%.4g", v[pv_G_relaxed])
                    << " Pa, V_p " << fmt("%.2f", v[pv_V_p_first_peak]) << " (relaxed " << fmt("%.2f", v[pv_V_pz_relaxed])
                    << "), V_s " << fmt("%.2f", v[pv_V_s_first_peak]) << " (relaxed " << fmt("%.2f", v[pv_V_sz_relaxed])
                    << ") m/s, " << fmt("%.0f", v[pv_seconds]) << " s\n";
        }
        return r;
      },
      ro, &st);
  if (stats) *stats = st;
  if (opt.limit && st.resumed + st.computed < members.size()) return results;
  if (!is_root()) return results;
  io::H5Writer w(out_path);
  write_packing_study(w, s, results);
  commit_study(w, ro.parts_dir);
  out << "packing study " << s.name << ": " << results.size() << " packings, " << st.resumed << " resumed, " << st.computed
      << " computed in " << fmt("%.1f", st.seconds) << " s\n"
      << packing_markdown(s, results) << "  study file: " << out_path << "\n";
  return results;
}

std::size_t run_packing_study(const std::string& path, const std::string& out_path, const PackingRunOptions& opt,
                              std::ostream& out) {
  const PackingStudy s = load_packing_study(path);
  const std::string o = out_path.empty() ? std::filesystem::path(path).stem().string() + ".h5" : out_path;
  RunStats st;
  run_packing_study(s, o, out, opt, &st);
  const std::size_t total = packing_members(s).size();
  return total - std::min(total, st.resumed + st.computed);
}

}  // namespace granwave::sweep
