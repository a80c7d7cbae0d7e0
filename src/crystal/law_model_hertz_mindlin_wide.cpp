// The Hertz-Mindlin law's tangential forms (each tangential history; with GRANWAVE_COUPLES_512 also
// those with rolling and torsion), whose gathered passes 512-bit vectors make faster:
// law_model<HertzMindlinCase, Forms::wide> (crystal/law_model.hpp).
//
// 512-bit vectors where the machine has them (docs/benchmarks.md, session 30).
#pragma GCC target("prefer-vector-width=512")
#include "contact/hertz_mindlin_case.hpp"
#include "crystal/law_model.hpp"

namespace granwave::crystal {

template std::shared_ptr<const ContactModel> law_model<contact::HertzMindlinCase, Forms::wide>(
    const contact::HertzMindlinCase::Params& params, double density);

}  // namespace granwave::crystal
