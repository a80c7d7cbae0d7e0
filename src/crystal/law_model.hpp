// The kernel's forms of one case law: law_model<D> makes crystal::model_of of the form that the
// description D's parameters select (D::model), and so instantiates the contact passes of every
// form. A non-inline template: each real law's instantiation is compiled in a unit of its own
// (law_model_linear.cpp, law_model_hertz_mindlin.cpp, declared extern in law_models.cpp), so that
// a parallel build compiles the laws' passes at once; a law without such a unit (the test law) is
// instantiated in law_models.cpp, where the registry dispatches.
#pragma once
#include <memory>

#include "crystal/dynamics.hpp"
#include "crystal/kernel.hpp"

namespace granwave::crystal {

template <class D>
std::shared_ptr<const ContactModel> law_model(const typename D::Params& params, double density) {
  return D::model(params, density, [](const auto& law) -> std::shared_ptr<const ContactModel> { return model_of(law); });
}

}  // namespace granwave::crystal
