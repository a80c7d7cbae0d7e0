// The direct contact passes of the Hertz-Mindlin law's forms without torques (no tangential force):
// law_model<HertzMindlinCase, Forms::direct> (crystal/law_model.hpp); the forms with a tangential
// history, with and without rolling and torsion, are in law_model_hertz_mindlin_gathered.cpp.
//
// 256-bit vectors for the contact loop, as in crystal/dynamics.cpp (whose comment gives the
// measurements).
#pragma GCC target("prefer-vector-width=256")
#include "contact/hertz_mindlin_case.hpp"
#include "crystal/law_model.hpp"

namespace granwave::crystal {

template std::shared_ptr<const ContactModel> law_model<contact::HertzMindlinCase, Forms::direct>(
    const contact::HertzMindlinCase::Params& params, double density);

}  // namespace granwave::crystal
