// The registry's kernel half: the model of a case's law (its description's model() through
// crystal::law_model: the contact kernel's instantiations for every form of the law) and the
// polydisperse relaxation with the law's frictionless, undamped form. With config/contact_laws.cpp,
// the only translation units that dispatch on config::ContactLaw.
//
// 256-bit vectors for the contact loop, as in crystal/dynamics.cpp (whose comment gives the
// measurements): the passes of a law without a unit of its own are instantiated here.
#pragma GCC target("prefer-vector-width=256")
#include <algorithm>
#include <memory>
#include <type_traits>

#include "contact/case_laws.hpp"
#include "crystal/dynamics.hpp"
#include "crystal/law_model.hpp"

namespace granwave::crystal {

// Compiled in law_model_<law>.cpp (256-bit vectors) and law_model_<law>_wide.cpp (512).
#define GRANWAVE_LAW_UNITS(D)                                                                               \
  extern template std::shared_ptr<const ContactModel> law_model<D, Forms::narrow>(const D::Params&, double); \
  extern template std::shared_ptr<const ContactModel> law_model<D, Forms::wide>(const D::Params&, double);
GRANWAVE_LAW_UNITS(contact::LinearLudingCase)
GRANWAVE_LAW_UNITS(contact::HertzMindlinCase)
#undef GRANWAVE_LAW_UNITS

namespace {
// The laws whose two kinds of forms have units of their own.
template <class D>
constexpr bool has_units = std::is_same_v<D, contact::LinearLudingCase> || std::is_same_v<D, contact::HertzMindlinCase>;
}  // namespace

std::shared_ptr<const ContactModel> case_model(const contact::LawParams& cp, double density) {
  return contact::visit_law(cp.law(), [&]<class D>(D) {
    const auto& params = cp.get<typename D::Params>();
    if constexpr (has_units<D>) {
      std::shared_ptr<const ContactModel> m = law_model<D, Forms::wide>(params, density);
      return m ? m : law_model<D, Forms::narrow>(params, density);
    } else {
      return law_model<D>(params, density);
    }
  });
}

RelaxResult relax(Packing& packing, const contact::LawParams& contact, double density, double tolerance,
                  long max_steps) {
  const double a_max = *std::max_element(packing.radius.begin(), packing.radius.end());
  const double m_min = *std::min_element(packing.mass.begin(), packing.mass.end());
  double overlap_max = 2.0 * a_max - packing.d_prime;
  if (packing.from_file()) {  // no lattice: the largest overlap there is
    overlap_max = 0.0;
    for (const PackingContact& c : list_contacts(packing, false)) overlap_max = std::max(overlap_max, c.overlap);
  }
  const contact::Relaxation r = contact::visit_law(contact.law(), [&]<class D>(D) {
    return D::relaxation(contact.get<typename D::Params>(), density, a_max, m_min, overlap_max);
  });
  return relax_with(packing, case_model(r.params, density), r.t_c, tolerance, max_steps);
}

}  // namespace granwave::crystal
