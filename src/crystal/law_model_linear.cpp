// The linear law's forms whose contact passes run at 256-bit vectors: Hooke's direct passes (with and
// without its dashpot) and, unless GRANWAVE_COUPLES_512, the forms with rolling and torsion,
// law_model<LinearLudingCase, Forms::narrow> (crystal/law_model.hpp); the friction forms are in
// law_model_linear_wide.cpp.
//
// 256-bit vectors, as in crystal/dynamics.cpp (whose comment gives the measurements).
#pragma GCC target("prefer-vector-width=256")
#include "contact/linear_luding_case.hpp"
#include "crystal/law_model.hpp"

namespace granwave::crystal {

template std::shared_ptr<const ContactModel> law_model<contact::LinearLudingCase, Forms::narrow>(
    const contact::LinearLudingCase::Params& params, double density);

}  // namespace granwave::crystal
