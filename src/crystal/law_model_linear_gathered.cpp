// The gathered contact passes of the linear law's forms with torques (Luding's spring-dashpot with
// friction, rolling and torsion): law_model<LinearLudingCase, Forms::gathered> (crystal/law_model.hpp).
//
// 512-bit vectors where the machine has them (docs/benchmarks.md, session 30).
#pragma GCC target("prefer-vector-width=512")
#include "contact/linear_luding_case.hpp"
#include "crystal/law_model.hpp"

namespace granwave::crystal {

template std::shared_ptr<const ContactModel> law_model<contact::LinearLudingCase, Forms::gathered>(
    const contact::LinearLudingCase::Params& params, double density);

}  // namespace granwave::crystal
