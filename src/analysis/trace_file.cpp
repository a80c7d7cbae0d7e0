// Reading any code's trace file into memory (analysis/trace_file.hpp).
#include "analysis/trace_file.hpp"

#include <algorithm>
#include <cmath>
#include <string>
#include <tuple>
#include <utility>

#include "config/case.hpp"
#include "core/error.hpp"
#include "crystal/observables.hpp"
#include "io/h5.hpp"

namespace granwave::analysis {
namespace {

// A trace from elsewhere may hold NaN or infinities (a run that blew up, a damaged copy): refused,
// naming the dataset, the sample and the column, rather than measured.
void require_finite(const io::H5Reader& r, const std::string& path, const std::vector<double>& v, std::size_t ncols) {
  for (std::size_t i = 0; i < v.size(); ++i)
    if (!std::isfinite(v[i]))
      throw InputError(r.path() + ": " + path + " holds " + std::to_string(v[i]) + " at sample " +
                       std::to_string(ncols ? i / ncols : i) + (ncols > 1 ? ", column " + std::to_string(i % ncols) : "") +
                       ": only finite values can be measured");
}

// An observable's dataset, [nt, nlayers] or [nt] as the table says.
std::vector<double> read_series(const io::H5Reader& r, const crystal::Observable& o, std::size_t nt, std::size_t nlayers) {
  const std::string path = o.path();
  std::vector<std::size_t> dims;
  auto v = r.read_double(path, &dims);
  if (o.shape == crystal::Shape::per_layer) {
    if (dims.size() != 2 || dims[0] != nt || dims[1] != nlayers)
      throw InputError(r.path() + ": " + path + " must have shape [nt, nlayers] = [" + std::to_string(nt) + ", " +
                       std::to_string(nlayers) + "]");
  } else if (dims.size() != 1 || dims[0] != nt) {
    throw InputError(r.path() + ": " + path + " must have shape [nt] = [" + std::to_string(nt) + "]");
  }
  require_finite(r, path, v, o.shape == crystal::Shape::per_layer ? nlayers : 1);
  return v;
}

// Provenance text is informative: an unreadable attribute must not stop the measurement.
std::string root_attr(const io::H5Reader& r, const std::string& name) {
  if (!r.has_attr("/", name)) return {};
  try {
    return r.attr_string("/", name);
  } catch (const InputError&) {
    return "(unreadable)";
  }
}

double median_spacing(const std::vector<double>& x) {
  std::vector<double> d;
  for (std::size_t i = 1; i < x.size(); ++i) d.push_back(x[i] - x[i - 1]);
  if (d.empty()) return 0.0;
  std::nth_element(d.begin(), d.begin() + d.size() / 2, d.end());
  return d[d.size() / 2];
}

double max_abs_change(const std::vector<double>& f, std::size_t nt, std::size_t n) {
  double m = 0.0;
  for (std::size_t i = 0; i < nt; ++i)
    for (std::size_t p = 0; p < n; ++p) m = std::max(m, std::abs(f[i * n + p] - f[p]));
  return m;
}

// A packing's free bins: after the last bin holding a source particle (role 1), before the first holding
// one held at the top (role 2) (data/SCHEMA.md §2: /system/role, /system/layer, one per particle).
std::pair<int, int> free_bins(const io::H5Reader& r, const std::string& path, std::size_t nlayers) {
  const auto role = r.read_int("/system/role"), layer = r.read_int("/system/layer");
  if (role.size() != layer.size())
    throw InputError(path + ": /system/role has " + std::to_string(role.size()) + " entries and /system/layer " +
                     std::to_string(layer.size()) + " (allowed: one each per particle)");
  for (std::size_t q = 0; q < role.size(); ++q)
    if (role[q] < 0 || role[q] > 2 || layer[q] < 0 || layer[q] >= static_cast<std::int64_t>(nlayers))
      throw InputError(path + ": /system/role or /system/layer of particle " + std::to_string(q) +
                       " is out of range (allowed: role 0, 1 or 2; layer 0 .. " + std::to_string(nlayers - 1) + ")");
  const auto [first, last] = packing_free_bins(role, layer, nlayers);
  if (last - first < 2)
    throw InputError(path + ": the packing's free bins (/system/role, /system/layer) are " +
                     std::to_string(last - first + 1) + " between the source and the top slab (allowed: >= 3)");
  return {first, last};
}

}  // namespace

std::vector<double>& CrystalTrace::series(const std::string& name) {
  // What the measures read, by the table's names (as crystal::analysis_trace fills them).
  static const std::pair<const char*, std::vector<double> CrystalTrace::*> measured[] = {
      {"layer_stress_zz", &CrystalTrace::stress_zz},           {"layer_stress_zx", &CrystalTrace::stress_zx},
      {"layer_displacement_z", &CrystalTrace::displacement_z}, {"layer_displacement_x", &CrystalTrace::displacement_x},
      {"layer_velocity_z", &CrystalTrace::velocity_z},         {"layer_velocity_x", &CrystalTrace::velocity_x},
      {"coordination", &CrystalTrace::coordination}};
  for (const auto& [n, member] : measured)
    if (name == n) return this->*member;
  return other[name];
}

const std::vector<crystal::Observable>& no_observables() {
  static const std::vector<crystal::Observable> none;
  return none;
}

TraceFile read_trace(const std::string& path, const std::vector<crystal::Observable>& observables) {
  return read_trace(io::H5Reader(path), observables);
}

TraceFile read_trace(const io::H5Reader& r, const std::vector<crystal::Observable>& observables) {
  const std::string& path = r.path();
  TraceFile f;
  f.path = path;
  f.code = root_attr(r, "code");
  f.code_version = root_attr(r, "code_version");
  f.case_name = root_attr(r, "case_name");
  f.time_convention = root_attr(r, "time_convention");
  f.case_toml = root_attr(r, "case_toml");
  if (!r.has("/time")) throw InputError(path + ": no /time dataset (not a granwave trace file, SCHEMA.md §3)");
  const auto time = r.read_double("/time");
  const std::size_t nt = time.size();
  if (nt < 3) throw InputError(path + ": /time has fewer than 3 samples");
  require_finite(r, "/time", time, 1);
  for (std::size_t i = 1; i < nt; ++i)
    if (!(time[i] > time[i - 1]))
      throw InputError(path + ": /time is not strictly increasing (sample " + std::to_string(i) + ")");

  if (r.has("/crystal/layer_z")) {
    f.model = "crystal";
    auto& c = f.crystal;
    c.time = time;
    c.nt = nt;
    c.layer_z = r.read_double("/crystal/layer_z");
    c.nlayers = c.layer_z.size();
    if (c.nlayers < 4) throw InputError(path + ": /crystal/layer_z has fewer than 4 layers");
    require_finite(r, "/crystal/layer_z", c.layer_z, 1);
    // The layer series: every /crystal observable of the table the file holds (/energy is not measured).
    for (const crystal::Observable& o : observables)
      if (o.group == "/crystal" && r.has(o.path())) c.series(o.name) = read_series(r, o, nt, c.nlayers);
    c.l0 = r.has_attr("/system", "l0") ? r.attr_double("/system", "l0") : median_spacing(c.layer_z);
    if (!(c.l0 > 0.0 && std::isfinite(c.l0)))
      throw InputError(path + ": the layer spacing l0 = " + std::to_string(c.l0) +
                       " (/system attribute l0, or the median spacing of /crystal/layer_z) is not a positive number");
    // A file's packing has slabs, not fixed layers: its source bins are the layers below layer_z = 0.
    const bool from_file = r.has_attr("/system", "generator") && r.attr_string("/system", "generator") != "fcc";
    c.packing_bins = from_file;
    if (r.has_attr("/system", "fixed_layers") && !from_file) {
      const double fl = r.attr_double("/system", "fixed_layers");
      if (!(std::abs(fl) < 1e9))
        throw InputError(path + ": /system attribute fixed_layers = " + std::to_string(fl) + " is not a layer count");
      c.fixed_layers = static_cast<int>(std::lround(fl));
    } else {  // layer_z = 0 is the innermost driven layer: the ones below it are driven too
      int below = 0;
      for (double z : c.layer_z) below += z < -0.5 * c.l0;
      c.fixed_layers = below + 1;
    }
    // A packing's top slab is its own thickness: the bins from the lowest one holding a top particle.
    if (from_file && r.has("/system/role") && r.has("/system/layer"))
      std::tie(c.first_free_bin, c.last_free_bin) = free_bins(r, path, c.nlayers);
    // Driven layers at each end; the measured ones, from the innermost driven layer at the source
    // to the last free one (at least 2), must be layers.
    if (c.fixed_layers < 1 || 2 * static_cast<std::size_t>(c.fixed_layers) + 1 > c.nlayers)
      throw InputError(path + ": " + std::to_string(c.fixed_layers) + " fixed layers at each end of " +
                       std::to_string(c.nlayers) + " layers (/system attribute fixed_layers, or layer_z below 0) "
                       "leave fewer than 2 layers to measure");
    // Excitation mode: from the case text every trace carries; else from which field moved.
    const std::string& toml = f.case_toml;
    bool known = false;
    if (!toml.empty()) {
      try {
        const auto cs = config::parse_case(toml, path + ":/case_toml", config::CaseParse::keys_only);
        c.mode = cs.excitation.mode == config::Excitation::Mode::S ? 'S' : 'P';
        c.mode_source = "case_toml";
        if (!cs.analysis.period.empty()) c.period = parse_period_reading(cs.analysis.period);
        if (!cs.analysis.wavenumber_speed.empty()) c.wavenumber_speed = parse_wavenumber_speed(cs.analysis.wavenumber_speed);
        known = true;
      } catch (const std::exception&) {
      }
    }
    if (!known) {
      auto pick = [&](const std::vector<double>& zf, const std::vector<double>& xf) {
        if (zf.empty() || xf.empty()) return 0;
        return max_abs_change(xf, nt, c.nlayers) > max_abs_change(zf, nt, c.nlayers) ? 2 : 1;
      };
      int v = pick(c.displacement_z, c.displacement_x);
      if (!v) v = pick(c.velocity_z, c.velocity_x);
      if (!v) v = pick(c.stress_zz, c.stress_zx);
      c.mode = v == 2 ? 'S' : 'P';
      c.mode_source = "inferred";
    }
  } else if (r.has("/chain/contact_force")) {
    f.model = "chain";
    auto& c = f.chain;
    c.time = time;
    c.nt = nt;
    std::vector<std::size_t> dims;
    c.contact_force = r.read_double("/chain/contact_force", &dims);
    if (dims.size() != 2 || dims[0] != nt || dims[1] == 0)
      throw InputError(path + ": /chain/contact_force must be [nt, ncontacts] with nt = " + std::to_string(nt) +
                       " (the samples of /time) and ncontacts > 0");
    require_finite(r, "/chain/contact_force", c.contact_force, dims[1]);
    c.ncontacts = dims[1];
    c.contact_position.assign(c.ncontacts, kNaN);
    if (r.has("/system/position")) {
      std::vector<std::size_t> pd;
      const auto pos = r.read_double("/system/position", &pd);
      std::vector<double> rad;
      if (r.has("/system/radius")) rad = r.read_double("/system/radius");
      const std::size_t nb = pd.size() == 2 && pd[1] == 3 ? pd[0] : 0;  // [n, 3], else not used
      // Contact j touches bead j on its far side: x_j + a_j (the wall contact too).
      for (std::size_t j = 0; j < c.ncontacts && j < nb; ++j)
        c.contact_position[j] = pos[j * 3] + (rad.size() == nb ? rad[j] : 0.0);
    }
  } else {
    throw InputError(path + ": neither /crystal/layer_z nor /chain/contact_force (SCHEMA.md §3)");
  }
  return f;
}

}  // namespace granwave::analysis
