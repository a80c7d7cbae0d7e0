// The packing study's results (see packing_study.hpp): per-pressure means and spreads over the
// seeds, the power laws in p, the markdown table and the study file (data/SCHEMA.md §6b).
#include <algorithm>
#include <cmath>
#include <sstream>

#include "core/format.hpp"
#include "core/numbers.hpp"
#include "io/h5.hpp"
#include "sweep/crystal_study.hpp"
#include "sweep/packing_study.hpp"

namespace granwave::sweep {

std::vector<PackingRow> packing_rows(const PackingStudy& s, const std::vector<MemberResult>& members) {
  std::vector<PackingRow> rows;
  const std::size_t nv = packing_value_names().size();
  const std::vector<double> widths = s.widths.empty() ? std::vector<double>{0.0} : s.widths;
  for (double p : s.pressures)
    for (double w : widths) {
      PackingRow row;
      row.pressure = p;
      row.width = w;
      row.mean.assign(nv, kNaN);
      row.sd.assign(nv, kNaN);
      std::vector<const MemberResult*> of;
      for (const auto& m : members)
        if (m.values.size() == nv && m.values[pv_pressure_target] == p && m.values[pv_width] == w) of.push_back(&m);
      row.seeds = of.size();
      for (std::size_t k = 0; k < nv; ++k) {
        double sum = 0.0, sq = 0.0;
        std::size_t n = 0;
        for (const auto* m : of)
          if (std::isfinite(m->values[k])) sum += m->values[k], ++n;
        if (n == 0) continue;
        row.mean[k] = sum / n;
        for (const auto* m : of)
          if (std::isfinite(m->values[k])) sq += (m->values[k] - row.mean[k]) * (m->values[k] - row.mean[k]);
        row.sd[k] = n > 1 ? std::sqrt(sq / (n - 1)) : kNaN;
      }
      rows.push_back(std::move(row));
    }
  return rows;
}

PackingSlopes packing_slopes(const std::vector<MemberResult>& members) {
  // Against the pressure reached (the preparation's), every member of the first width a point.
  const auto slope = [&](std::size_t k) {
    std::vector<double> x, y;
    for (const auto& m : members)
      if (m.values[pv_width] == members.front().values[pv_width] && m.values[k] > 0.0 && m.values[pv_pressure] > 0.0) x.push_back(m.values[pv_pressure]), y.push_back(m.values[k]);
    bool spread = false;
    for (double p : x) spread = spread || std::abs(p / x.front() - 1.0) > 0.1;
    return spread ? power_law(x, y).exponent : kNaN;
  };
  PackingSlopes sl;
  sl.K_relaxed = slope(pv_K_relaxed);
  sl.G_relaxed = slope(pv_G_relaxed);
  sl.K_affine = slope(pv_K_affine);
  sl.G_affine = slope(pv_G_affine);
  sl.K_walton = slope(pv_K_walton);
  sl.coordination = slope(pv_coordination_backbone);
  sl.V_p = slope(pv_V_p_first_peak);
  sl.V_s = slope(pv_V_s_first_peak);
  return sl;
}

std::string packing_markdown(const PackingStudy& s, const std::vector<MemberResult>& members) {
  std::ostringstream o;
  const auto rows = packing_rows(s, members);
  const auto ms = [](const PackingRow& r, std::size_t k, const char* f) {
    std::string t = fmt(f, r.mean[k]);
    if (std::isfinite(r.sd[k])) t += " +- " + fmt(f, r.sd[k]);
    return t;
  };
  o << "Means +- sample standard deviations over the seeds. K, G in MPa (isotropic parts of the triply periodic "
       "packing's elastic moduli: affine, relaxed, Walton's effective medium); speeds in m/s: first peaks of the P and S "
       "pulses beside the relaxed bulk's Christoffel speeds along z.\n\n";
  o << "| p (Pa) | width | seeds | N | Phi | Z | z* | rattlers (%) | K affine | K relaxed | K Walton | G affine | G relaxed | G Walton "
       "| V_p pulse | V_p relaxed | V_s pulse | V_s relaxed |\n";
  o << "|---|---|---|---|---|---|---|---|---|---|---|---|---|---|---|---|---|---|\n";
  for (const auto& r : rows) {
    const auto mpa = [&](std::size_t k) {
      PackingRow q = r;
      q.mean[k] *= 1e-6, q.sd[k] *= 1e-6;
      return ms(q, k, "%.4g");
    };
    const double ratt = 100.0 * r.mean[pv_rattlers] / r.mean[pv_count];
    o << "| " << fmt("%g", r.pressure) << " | " << fmt("%g", r.width) << " | " << r.seeds << " | " << fmt("%.0f", r.mean[pv_count]) << " | "
      << ms(r, pv_solid_fraction, "%.4f") << " | " << ms(r, pv_coordination, "%.3f") << " | "
      << ms(r, pv_coordination_backbone, "%.3f") << " | " << fmt("%.2f", ratt) << " | " << mpa(pv_K_affine) << " | "
      << mpa(pv_K_relaxed) << " | " << mpa(pv_K_walton) << " | " << mpa(pv_G_affine) << " | " << mpa(pv_G_relaxed)
      << " | " << mpa(pv_G_walton) << " | " << ms(r, pv_V_p_first_peak, "%.2f") << " | " << ms(r, pv_V_pz_relaxed, "%.2f")
      << " | " << ms(r, pv_V_s_first_peak, "%.2f") << " | " << ms(r, pv_V_sz_relaxed, "%.2f") << " |\n";
  }
  std::vector<double> pressures;
  for (const auto& r : rows)
    if (std::find(pressures.begin(), pressures.end(), r.pressure) == pressures.end()) pressures.push_back(r.pressure);
  if (pressures.size() < 2) {  // a study over the width alone (random_poly.toml): no line through one pressure
    o << "\nNo slopes against p: the study has one pressure.\n";
    return o.str();
  }
  const PackingSlopes sl = packing_slopes(members);
  o << "\nSlopes d ln / d ln p over every packing (Makse et al. 2004: above 1/3 for K and G, since Z grows with p; "
       "Walton's at fixed Z is 1/3): K relaxed "
    << fmt("%.3f", sl.K_relaxed) << ", G relaxed " << fmt("%.3f", sl.G_relaxed) << ", K affine " << fmt("%.3f", sl.K_affine)
    << ", G affine " << fmt("%.3f", sl.G_affine) << ", K Walton " << fmt("%.3f", sl.K_walton) << "; z* "
    << fmt("%.3f", sl.coordination) << "; V_p " << fmt("%.3f", sl.V_p) << ", V_s " << fmt("%.3f", sl.V_s) << "\n";
  return o.str();
}

std::string packing_study_fingerprint(const PackingStudy& s) {
  std::string columns;
  for (const auto& n : packing_value_names()) columns += n + ",";
  return fingerprint({s.text, s.case_text, columns});
}

void write_packing_study(io::H5Writer& w, const PackingStudy& s, const std::vector<MemberResult>& members) {
  io::write_provenance(w);
  w.attr("/", "kind", std::string("packing_study"));
  w.attr("/", "study_name", s.name);
  w.attr("/", "study_toml", s.text);
  w.attr("/", "case_toml", s.case_text);
  w.attr("/", "fingerprint", packing_study_fingerprint(s));
  write_members(w, "/members", members, packing_value_names());
  // Per pressure: <value> and <value>_sd over the seeds.
  const auto rows = packing_rows(s, members);
  Columns cols;
  std::vector<double> p, wd, n;
  for (const auto& r : rows) p.push_back(r.pressure), wd.push_back(r.width), n.push_back(static_cast<double>(r.seeds));
  cols.emplace_back("pressure_target", p);
  cols.emplace_back("width", wd);
  cols.emplace_back("seeds", n);
  const auto& names = packing_value_names();
  for (std::size_t k = pv_count; k < names.size(); ++k) {
    std::vector<double> mean, sd;
    for (const auto& r : rows) mean.push_back(r.mean[k]), sd.push_back(r.sd[k]);
    cols.emplace_back(names[k], mean);
    cols.emplace_back(names[k] + "_sd", sd);
  }
  write_columns(w, "/table", cols);
  const PackingSlopes sl = packing_slopes(members);
  const std::pair<const char*, double> slopes[] = {{"K_relaxed", sl.K_relaxed}, {"G_relaxed", sl.G_relaxed},
                                                   {"K_affine", sl.K_affine},   {"G_affine", sl.G_affine},
                                                   {"K_walton", sl.K_walton},   {"coordination_backbone", sl.coordination},
                                                   {"V_p", sl.V_p},             {"V_s", sl.V_s}};
  w.group("/slopes");
  for (const auto& [name, value] : slopes) w.attr("/slopes", name, value);
}

}  // namespace granwave::sweep
