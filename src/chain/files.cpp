// The chain parts of the system and trace files (data/SCHEMA.md §2, §3).
#include <cmath>

#include "chain/chain.hpp"
#include "core/error.hpp"
#include "io/h5.hpp"

namespace granwave::chain {
namespace {

std::vector<std::int64_t> to_i64(const std::vector<int>& v) { return {v.begin(), v.end()}; }
std::vector<int> to_int(const std::vector<std::int64_t>& v) { return {v.begin(), v.end()}; }

std::string join(const std::string& group, const std::string& name) {
  return (group == "/" || group.empty()) ? "/" + name : group + "/" + name;
}

// Chain beads lie along x: [n, 3] with y = z = 0.
std::vector<double> along_x(const std::vector<double>& x) {
  std::vector<double> out(3 * x.size(), 0.0);
  for (std::size_t i = 0; i < x.size(); ++i) out[3 * i] = x[i];
  return out;
}

}  // namespace

void write_system(io::H5Writer& w, const ChainSystem& sys, const std::string& group) {
  const std::string g = group.empty() ? "/" : group;
  if (g != "/") w.group(g);
  const std::size_t n = sys.nbeads();
  w.attr(g, "model", std::string("chain"));
  w.attr(g, "schema_version", std::int64_t{1});
  w.attr(g, "case_name", sys.case_name);
  w.write(join(g, "material_names"), sys.material_names);
  w.write(join(g, "material_index"), to_i64(sys.material));
  w.write(join(g, "mass"), sys.mass);
  w.write(join(g, "radius"), sys.radius);
  std::vector<double> inertia(n);
  for (std::size_t i = 0; i < n; ++i) inertia[i] = 0.4 * sys.mass[i] * sys.radius[i] * sys.radius[i];
  w.write(join(g, "inertia"), inertia);
  w.write(join(g, "youngs_modulus"), sys.youngs_modulus);
  w.write(join(g, "poisson_ratio"), sys.poisson_ratio);
  w.write(join(g, "fixed"), std::vector<std::int64_t>(n, 0));
  w.write(join(g, "position"), along_x(sys.position), {n, 3});
  w.write(join(g, "velocity"), along_x(sys.velocity), {n, 3});
  w.write(join(g, "cell"), to_i64(sys.cell));
  w.write(join(g, "spin"), to_i64(sys.spin));
  w.write(join(g, "flippable"), to_i64(sys.flippable));
  w.write(join(g, "counts_for_m"), to_i64(sys.counts_for_m));
  w.write(join(g, "cell_materials"), to_i64(sys.cell_materials));
  w.write(join(g, "hertz_constant"), sys.hertz_constant);
  w.write(join(g, "initial_overlap"), sys.initial_overlap);
  w.attr(g, "magnetisation", sys.magnetisation);
  w.attr(g, "wall", sys.wall);
  w.attr(g, "wall_youngs_modulus", sys.wall_youngs_modulus);
  w.attr(g, "wall_poisson_ratio", sys.wall_poisson_ratio);
  w.attr(g, "wall_position", sys.wall_position);
  w.attr(g, "precompression", sys.precompression);
  w.attr(g, "striker_velocity", sys.striker_velocity);
}

ChainSystem read_system(const io::H5Reader& r, const std::string& group) {
  const std::string g = group.empty() ? "/" : group;
  if (!r.has_attr(g, "model") || r.attr_string(g, "model") != "chain")
    throw InputError(r.path() + ": not a chain system (attribute 'model' is not \"chain\")");
  ChainSystem s;
  s.case_name = r.attr_string(g, "case_name");
  s.material_names = r.read_strings(join(g, "material_names"));
  s.material = to_int(r.read_int(join(g, "material_index")));
  s.mass = r.read_double(join(g, "mass"));
  s.radius = r.read_double(join(g, "radius"));
  s.youngs_modulus = r.read_double(join(g, "youngs_modulus"));
  s.poisson_ratio = r.read_double(join(g, "poisson_ratio"));
  const auto pos = r.read_double(join(g, "position"));
  const auto vel = r.read_double(join(g, "velocity"));
  const std::size_t n = s.mass.size();
  if (pos.size() != 3 * n || vel.size() != 3 * n) throw InputError(r.path() + ": position/velocity are not [n, 3]");
  for (std::size_t i = 0; i < n; ++i) {
    s.position.push_back(pos[3 * i]);
    s.velocity.push_back(vel[3 * i]);
  }
  s.cell = to_int(r.read_int(join(g, "cell")));
  s.spin = to_int(r.read_int(join(g, "spin")));
  s.counts_for_m = to_int(r.read_int(join(g, "counts_for_m")));
  s.flippable = r.has(join(g, "flippable")) ? to_int(r.read_int(join(g, "flippable"))) : std::vector<int>(s.spin.size(), 0);
  if (r.has(join(g, "cell_materials"))) s.cell_materials = to_int(r.read_int(join(g, "cell_materials")));
  // A file from elsewhere (or damaged) is checked before any of its numbers is used as an index.
  const auto refuse = [&](const std::string& what) { throw InputError(r.path() + ": " + g + ": " + what); };
  if (n == 0) refuse("no beads");
  for (const auto* v : {&s.radius, &s.youngs_modulus, &s.poisson_ratio})
    if (v->size() != n) refuse("mass, radius, youngs_modulus and poisson_ratio must have one value per bead");
  if (s.material.size() != n || s.cell.size() != n) refuse("material_index and cell must have one value per bead");
  if (s.counts_for_m.size() != s.spin.size() || s.flippable.size() != s.spin.size())
    refuse("spin, flippable and counts_for_m must have one value per cell");
  for (std::size_t b = 0; b < n; ++b) {
    if (s.material[b] < 0 || static_cast<std::size_t>(s.material[b]) >= s.material_names.size())
      refuse("material_index of bead " + std::to_string(b) + " is not an index of material_names");
    if (s.cell[b] < -1 || s.cell[b] >= static_cast<int>(s.spin.size()))
      refuse("cell of bead " + std::to_string(b) + " is neither -1 nor a cell index");
    if (!(std::isfinite(s.mass[b]) && s.mass[b] > 0 && std::isfinite(s.radius[b]) && s.radius[b] > 0 &&
          std::isfinite(s.youngs_modulus[b]) && s.youngs_modulus[b] > 0 && std::isfinite(s.poisson_ratio[b]) &&
          std::isfinite(s.position[b]) && std::isfinite(s.velocity[b])))
      refuse("bead " + std::to_string(b) + " has a mass, radius, modulus, position or velocity that is not a finite "
             "(positive) number");
  }
  for (int m : s.cell_materials)
    if (m < 0 || static_cast<std::size_t>(m) >= s.material_names.size()) refuse("cell_materials holds a bad material index");
  s.cell_first_bead.assign(s.spin.size(), -1);
  for (std::size_t b = n; b-- > 0;)
    if (s.cell[b] >= 0) s.cell_first_bead[s.cell[b]] = static_cast<int>(b);
  s.hertz_constant = r.read_double(join(g, "hertz_constant"));
  s.initial_overlap = r.read_double(join(g, "initial_overlap"));
  s.magnetisation = r.attr_double(g, "magnetisation");
  s.wall = r.attr_string(g, "wall");
  s.has_wall = s.wall != "free";
  s.wall_youngs_modulus = r.attr_double(g, "wall_youngs_modulus");
  s.wall_poisson_ratio = r.attr_double(g, "wall_poisson_ratio");
  s.wall_position = r.attr_double(g, "wall_position");
  s.precompression = r.has_attr(g, "precompression") ? r.attr_double(g, "precompression") : 0.0;
  s.striker_velocity = n > 0 ? s.velocity[0] : 0.0;
  // The material table's per-material values are not stored; take them from the beads.
  const std::size_t nm = s.material_names.size();
  const double nan = std::nan("");
  for (const auto& [bead, table] : s.material_columns()) {
    table->assign(nm, nan);
    for (std::size_t b = 0; b < n; ++b) (*table)[s.material[b]] = (*bead)[b];
  }
  if (s.hertz_constant.size() != n - 1 + (s.has_wall ? 1 : 0) || s.initial_overlap.size() != s.hertz_constant.size())
    throw InputError(r.path() + ": hertz_constant/initial_overlap do not match the beads and the wall");
  for (std::size_t k = 0; k < s.hertz_constant.size(); ++k)
    if (!(std::isfinite(s.hertz_constant[k]) && s.hertz_constant[k] >= 0 && std::isfinite(s.initial_overlap[k])))
      refuse("contact " + std::to_string(k) + " has a hertz_constant or initial_overlap that is not a finite number");
  for (double x : {s.wall_youngs_modulus, s.wall_poisson_ratio, s.wall_position, s.precompression})
    if (s.has_wall && !std::isfinite(x)) refuse("a wall attribute is not a finite number");
  return s;
}

namespace {
// A dataset of the trace: a series of the run, or values made for the file (the conservative
// model's zero dissipation, the sensors' bead indices as int64).
struct TraceItem {
  std::string path;
  std::vector<std::size_t> shape;
  std::vector<double> ChainTrace::*series = nullptr;
  std::vector<double> values;
  std::vector<std::int64_t> counts;
};

// The trace's datasets but /system, in the file's order.
std::vector<TraceItem> trace_items(const ChainTrace& tr) {
  const std::size_t nt = tr.nt(), nft = tr.full_rate_time.size(), ns = tr.full_rate_beads.size();
  std::vector<TraceItem> out;
  auto series = [&](const char* path, std::vector<double> ChainTrace::*s, std::vector<std::size_t> shape = {}) {
    if (shape.empty()) shape = {(tr.*s).size()};
    out.push_back({path, std::move(shape), s, {}, {}});
  };
  series("/time", &ChainTrace::time);
  if (!tr.bead_force.empty()) series("/chain/bead_force", &ChainTrace::bead_force, {nt, tr.nbeads});
  if (!tr.contact_force.empty()) series("/chain/contact_force", &ChainTrace::contact_force, {nt, tr.ncontacts});
  if (ns) {
    series("/chain/full_rate/time", &ChainTrace::full_rate_time);
    series("/chain/full_rate/bead_force", &ChainTrace::full_rate_bead_force, {nft, ns});
    out.push_back({"/chain/full_rate/beads", {ns}, nullptr, {}, to_i64(tr.full_rate_beads)});
  }
  if (!tr.kinetic.empty()) {
    series("/energy/kinetic", &ChainTrace::kinetic);
    series("/energy/potential", &ChainTrace::potential);
    // Conservative model: nothing dissipated; work_in is the static load's work (precompression).
    out.push_back({"/energy/dissipated", {nt}, nullptr, std::vector<double>(nt, 0.0), {}});
    series("/energy/work_in", &ChainTrace::work_in);
  }
  return out;
}
}  // namespace

void write_trace(io::H5Writer& w, const ChainTrace& tr) {
  for (const auto& d : trace_items(tr)) {
    if (!d.counts.empty()) w.write(d.path, d.counts, d.shape);
    else w.write(d.path, d.series ? tr.*d.series : d.values, d.shape);
  }
  w.attr("/", "time_convention", std::string("synchronous"));
  w.attr("/", "dt", tr.dt);
  w.attr("/", "steps", static_cast<std::int64_t>(tr.steps));
  w.attr("/", "stopped_early", static_cast<std::int64_t>(tr.stopped_early));
}

TraceSeries take_series(ChainTrace&& tr) {
  TraceSeries out;
  for (auto& d : trace_items(tr))
    out.datasets.push_back({d.path, d.shape, d.series ? std::move(tr.*d.series) : std::move(d.values), std::move(d.counts)});
  return out;
}

}  // namespace granwave::chain
