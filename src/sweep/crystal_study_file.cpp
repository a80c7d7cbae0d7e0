// The crystal study file (data/SCHEMA.md §6), from the finished study.
#include <string>
#include <utility>

#include "io/h5.hpp"
#include "sweep/crystal_study.hpp"

namespace granwave::sweep {

void write_crystal_study(io::H5Writer& w, const CrystalStudy& s, const CrystalStudyResult& r) {
  io::write_provenance(w);
  w.attr("/", "kind", std::string("crystal_study"));
  w.attr("/", "study_name", s.name);
  w.attr("/", "vary", std::string(to_string(s.vary)));
  w.attr("/", "study_toml", s.text);
  w.attr("/", "case_toml", s.base.toml_text);
  w.attr("/", "fingerprint", crystal_study_fingerprint(s));
  write_members(w, "/members", r.members, crystal_value_names(s));
  w.write("/study/positions", s.positions);
  if (const auto& d = r.damping) {
    w.write("/damping/gamma_star", d->gamma_star);
    w.write("/damping/t_gamma_star", d->t_gamma_star);
    w.write("/damping/ratio_t_gamma_t_c", d->ratio_t_gamma_t_c);
    w.attr("/damping", "t_c", d->t_c);
  }
  if (const auto& ps = r.pressure)
    for (std::size_t q = 0; q < ps->modes.size(); ++q) {
      const std::string g = std::string("/pressure/") + ps->modes[q];
      w.group(g);
      const std::pair<const char*, const PowerLaw*> laws[] = {{"exponent_delta", &ps->v_delta[q]},
                                                              {"exponent_pressure", &ps->v_pressure[q]},
                                                              {"theory_exponent_delta", &ps->theory_v_delta[q]},
                                                              {"theory_exponent_pressure", &ps->theory_v_pressure[q]}};
      for (const auto& [name, law] : laws) {
        w.attr(g, name, law->exponent);
        w.attr(g, std::string(name) + "_error", law->error);
      }
    }
}

}  // namespace granwave::sweep
