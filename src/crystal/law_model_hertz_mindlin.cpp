// The Hertz-Mindlin law's forms whose contact passes run at 256-bit vectors: the direct passes (no
// tangential force) and, unless GRANWAVE_COUPLES_512, the forms with rolling and torsion,
// law_model<HertzMindlinCase, Forms::narrow> (crystal/law_model.hpp); the tangential forms are in
// law_model_hertz_mindlin_wide.cpp.
//
// 256-bit vectors, as in crystal/dynamics.cpp (whose comment gives the measurements).
#pragma GCC target("prefer-vector-width=256")
#include "contact/hertz_mindlin_case.hpp"
#include "crystal/law_model.hpp"

namespace granwave::crystal {

template std::shared_ptr<const ContactModel> law_model<contact::HertzMindlinCase, Forms::narrow>(
    const contact::HertzMindlinCase::Params& params, double density);

}  // namespace granwave::crystal
