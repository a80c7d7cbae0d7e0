// The gathered contact passes of the Hertz-Mindlin law's forms with torques (each tangential history,
// with and without rolling and torsion): law_model<HertzMindlinCase, Forms::gathered>
// (crystal/law_model.hpp).
//
// 512-bit vectors where the machine has them (docs/benchmarks.md, session 30).
#pragma GCC target("prefer-vector-width=512")
#include "contact/hertz_mindlin_case.hpp"
#include "crystal/law_model.hpp"

namespace granwave::crystal {

template std::shared_ptr<const ContactModel> law_model<contact::HertzMindlinCase, Forms::gathered>(
    const contact::HertzMindlinCase::Params& params, double density);

}  // namespace granwave::crystal
