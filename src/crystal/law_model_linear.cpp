// The contact passes of the linear law's forms (Luding's spring-dashpot with friction, rolling and
// torsion; Hooke without): law_model<LinearLudingCase>, apart from the other laws' (crystal/law_model.hpp).
//
// 256-bit vectors for the contact loop, as in crystal/dynamics.cpp (whose comment gives the
// measurements).
#pragma GCC target("prefer-vector-width=256")
#include "contact/linear_luding_case.hpp"
#include "crystal/law_model.hpp"

namespace granwave::crystal {

template std::shared_ptr<const ContactModel> law_model<contact::LinearLudingCase>(
    const contact::LinearLudingCase::Params& params, double density);

}  // namespace granwave::crystal
