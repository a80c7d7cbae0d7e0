// The contact passes of the Hertz-Mindlin law's forms (each tangential history, with and without
// rolling and torsion): law_model<HertzMindlinCase>, apart from the other laws' (crystal/law_model.hpp).
//
// 256-bit vectors for the contact loop, as in crystal/dynamics.cpp (whose comment gives the
// measurements).
#pragma GCC target("prefer-vector-width=256")
#include "contact/hertz_mindlin_case.hpp"
#include "crystal/law_model.hpp"

namespace granwave::crystal {

template std::shared_ptr<const ContactModel> law_model<contact::HertzMindlinCase>(
    const contact::HertzMindlinCase::Params& params, double density);

}  // namespace granwave::crystal
