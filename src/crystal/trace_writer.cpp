// The crystal's trace file (data/SCHEMA.md §3) from a run's series, and the same series in memory
// (take_series, analysis_trace).
#include "crystal/trace_writer.hpp"

#include <string>
#include <utility>

#include "config/contact_laws.hpp"
#include "io/h5.hpp"

namespace granwave::crystal {

analysis::CrystalTrace analysis_trace(const config::Case& c, const Packing& packing, const Traces& tr) {
  analysis::CrystalTrace t;
  t.time = tr.time;
  t.layer_z = tr.layer_z;
  t.nt = tr.samples();
  t.nlayers = tr.nlayers;
  t.l0 = packing.l0;
  t.fixed_layers = packing.fixed_layers;
  t.mode = c.excitation.mode == config::Excitation::Mode::S ? 'S' : 'P';
  t.mode_source = "case_toml";
  t.stress_zz = tr.stress_zz;
  t.stress_zx = tr.stress_zx;
  t.displacement_z = tr.displacement_z;
  t.displacement_x = tr.displacement_x;
  t.velocity_z = tr.velocity_z;
  t.velocity_x = tr.velocity_x;
  t.coordination = tr.coordination;
  return t;
}

namespace {
bool wants(const config::Case& c, const std::string& field) {
  if (c.output.fields.empty()) return true;
  for (const auto& f : c.output.fields)
    if (f == field) return true;
  return false;
}

// A dataset of the trace: its path and series, [nt, nlayers] or one-dimensional.
struct TraceField {
  std::string path;
  std::vector<double> Traces::*series;
  bool per_layer;
};

// The datasets of the case's trace but /system, in the file's order.
std::vector<TraceField> trace_fields(const config::Case& c) {
  std::vector<TraceField> out = {{"/time", &Traces::time, false}, {"/crystal/layer_z", &Traces::layer_z, false}};
  const std::pair<const char*, std::vector<double> Traces::*> fields[] = {
      {"layer_stress_zz", &Traces::stress_zz},         {"layer_stress_zx", &Traces::stress_zx},
      {"layer_displacement_z", &Traces::displacement_z}, {"layer_displacement_x", &Traces::displacement_x},
      {"layer_velocity_z", &Traces::velocity_z},       {"layer_velocity_x", &Traces::velocity_x}};
  for (const auto& [name, series] : fields)
    if (wants(c, name)) out.push_back({std::string("/crystal/") + name, series, true});
  if (wants(c, "coordination")) out.push_back({"/crystal/coordination", &Traces::coordination, false});
  if (wants(c, "energy"))
    for (const auto& [name, series] : {std::pair{"kinetic", &Traces::kinetic}, {"potential", &Traces::potential},
                                       {"dissipated", &Traces::dissipated}, {"work_in", &Traces::work_in},
                                       {"verlet_correction", &Traces::verlet_correction}})
      out.push_back({std::string("/energy/") + name, series, false});
  return out;
}

std::vector<std::size_t> shape_of(const TraceField& f, const Traces& t) {
  return f.per_layer ? std::vector<std::size_t>{t.samples(), t.nlayers} : std::vector<std::size_t>{(t.*f.series).size()};
}
}  // namespace

void write_trace(const config::Case& c, const Packing& p, const RunResult& r, io::H5Writer& w) {
  io::write_provenance(w);
  w.attr("/", "case_name", c.name);
  w.attr("/", "case_toml", c.toml_text);
  w.attr("/", "time_convention", std::string("synchronous"));
  // The contact-law conventions the crosscheck compares (data/SCHEMA.md §3).
  w.attr("/", "lever_arm", std::string(contact::lever_arm_name(c.contact.lever_arm)));
  w.attr("/", "normal_tension", std::string(c.contact.normal_tension == config::NormalTension::clip ? "clip" : "allow"));
  w.attr("/", "coulomb_normal",
         std::string(c.contact.coulomb_normal == config::CoulombNormal::magnitude ? "magnitude" : "compressive"));
  w.attr("/", "contact_law", contact_law_name(c.contact));
  w.attr("/", "tangential_history", tangential_history_name(c.contact));
  w.attr("/", "rolling_lever", std::string(contact::rolling_lever_name(c.contact.rolling_lever)));
  w.attr("/", "rolling_history", std::string(contact::rolling_history_name(c.contact.rolling_history)));
  w.attr("/", "status", r.failed ? "failed: " + r.error : std::string("complete"));
  write_system(w, p, c.name, "/system");
  for (const auto& f : trace_fields(c)) w.write(f.path, r.traces.*f.series, shape_of(f, r.traces));
}

TraceSeries take_series(const config::Case& c, Traces&& t) {
  TraceSeries out;
  const auto fields = trace_fields(c);
  for (const auto& f : fields) out.datasets.push_back({f.path, shape_of(f, t), {}, {}});  // before /time moves
  for (std::size_t k = 0; k < fields.size(); ++k) out.datasets[k].values = std::move(t.*fields[k].series);
  return out;
}


}  // namespace granwave::crystal
