// The crystal's trace file (data/SCHEMA.md §3) from a run's series, and the same series in memory
// (take_series, analysis_trace).
#include "crystal/trace_writer.hpp"

#include <string>
#include <tuple>
#include <vector>
#include <utility>

#include "config/contact_laws.hpp"
#include "crystal/observables.hpp"
#include "io/h5.hpp"

namespace granwave::crystal {

analysis::CrystalTrace analysis_trace(const config::Case& c, const Packing& packing, const Traces& tr) {
  analysis::CrystalTrace t;
  t.time = tr.time;
  t.layer_z = tr.layer_z;
  t.nt = tr.samples();
  t.nlayers = tr.nlayers;
  t.l0 = packing.l0;
  t.fixed_layers = packing.source_bins();  // FCC: fixed_layers; a file: the bins of its source slab
  t.mode = c.excitation.mode == config::Excitation::Mode::S ? 'S' : 'P';
  t.mode_source = "case_toml";
  // What the analysis measures (analysis/trace_file.hpp), by the table's names.
  t.stress_zz = tr["layer_stress_zz"];
  t.stress_zx = tr["layer_stress_zx"];
  t.displacement_z = tr["layer_displacement_z"];
  t.displacement_x = tr["layer_displacement_x"];
  t.velocity_z = tr["layer_velocity_z"];
  t.velocity_x = tr["layer_velocity_x"];
  t.coordination = tr["coordination"];
  // A packing's free bins by role, by the trace file reader's rule (analysis::packing_free_bins), so that
  // a run measured in memory gets the fit range `analyze` gives its file.
  if (packing.from_file()) {
    t.packing_bins = true;
    std::tie(t.first_free_bin, t.last_free_bin) = analysis::packing_free_bins(packing.role, packing.layer, t.nlayers);
  }
  return t;
}

namespace {
// A dataset of the trace: its path, its values (/time, /crystal/layer_z, or observable k's
// series), [nt, nlayers] or one-dimensional.
struct TraceField {
  std::string path;
  enum { time, layer_z, observable } source;
  std::size_t k;
  bool per_layer;
  template <class T>  // Traces or const Traces
  auto& values(T& t) const {
    return source == time ? t.time : source == layer_z ? t.layer_z : t.series[k];
  }
};

// The datasets of the case's trace but /system, in the file's order: /time, /crystal/layer_z,
// then the observables of the table that the case's `[output] fields` select.
std::vector<TraceField> trace_fields(const config::Case& c) {
  std::vector<TraceField> out = {{"/time", TraceField::time, 0, false}, {"/crystal/layer_z", TraceField::layer_z, 0, false}};
  const std::vector<Observable>& all = observables();
  for (std::size_t k = 0; k < all.size(); ++k)
    if (selected(c, all[k])) out.push_back({all[k].path(), TraceField::observable, k, all[k].shape == Shape::per_layer});
  return out;
}

std::vector<std::size_t> shape_of(const TraceField& f, const Traces& t) {
  return f.per_layer ? std::vector<std::size_t>{t.samples(), t.nlayers} : std::vector<std::size_t>{f.values(t).size()};
}
}  // namespace

void write_trace(const config::Case& c, const Packing& p, const RunResult& r, io::H5Writer& w) {
  io::write_provenance(w);
  w.attr("/", "case_name", c.name);
  w.attr("/", "case_toml", c.toml_text);
  w.attr("/", "time_convention", std::string("synchronous"));
  // The contact-law conventions the crosscheck compares (data/SCHEMA.md §3).
  w.attr("/", "lever_arm", std::string(contact::lever_arm_name(c.contact.friction().lever_arm)));
  w.attr("/", "normal_tension", std::string(c.contact.friction().clip() ? "clip" : "allow"));
  w.attr("/", "coulomb_normal",
         std::string(c.contact.friction().magnitude() ? "magnitude" : "compressive"));
  w.attr("/", "contact_law", contact_law_name(c.contact));
  w.attr("/", "tangential_history", tangential_history_name(c.contact));
  w.attr("/", "rolling_lever", std::string(contact::rolling_lever_name(c.contact.rolling().rolling_lever)));
  w.attr("/", "rolling_history", std::string(contact::rolling_history_name(c.contact.rolling().rolling_history)));
  w.attr("/", "status", r.failed ? "failed: " + r.error : std::string("complete"));
  write_system(w, p, c.name, "/system");
  for (const auto& f : trace_fields(c)) w.write(f.path, f.values(r.traces), shape_of(f, r.traces));
}

TraceSeries take_series(const config::Case& c, Traces&& t) {
  TraceSeries out;
  const auto fields = trace_fields(c);
  for (const auto& f : fields) out.datasets.push_back({f.path, shape_of(f, t), {}, {}});  // before /time moves
  for (std::size_t k = 0; k < fields.size(); ++k) out.datasets[k].values = std::move(fields[k].values(t));
  return out;
}


}  // namespace granwave::crystal
