// The direct contact passes of the linear law's forms without torques (Hooke, with and without its
// dashpot): law_model<LinearLudingCase, Forms::direct> (crystal/law_model.hpp); the forms with
// friction, rolling and torsion are in law_model_linear_gathered.cpp.
//
// 256-bit vectors for the contact loop, as in crystal/dynamics.cpp (whose comment gives the
// measurements: 512-bit vectors make the direct pass 27 % slower).
#pragma GCC target("prefer-vector-width=256")
#include "contact/linear_luding_case.hpp"
#include "crystal/law_model.hpp"

namespace granwave::crystal {

template std::shared_ptr<const ContactModel> law_model<contact::LinearLudingCase, Forms::direct>(
    const contact::LinearLudingCase::Params& params, double density);

}  // namespace granwave::crystal
