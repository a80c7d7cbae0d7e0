// The linear law's friction forms (Luding's spring-dashpot, each lever arm; with GRANWAVE_COUPLES_512
// also those with rolling and torsion), whose gathered passes 512-bit vectors make faster:
// law_model<LinearLudingCase, Forms::wide> (crystal/law_model.hpp).
//
// 512-bit vectors where the machine has them (docs/benchmarks.md, session 30).
#pragma GCC target("prefer-vector-width=512")
#include "contact/linear_luding_case.hpp"
#include "crystal/law_model.hpp"

namespace granwave::crystal {

template std::shared_ptr<const ContactModel> law_model<contact::LinearLudingCase, Forms::wide>(
    const contact::LinearLudingCase::Params& params, double density);

}  // namespace granwave::crystal
