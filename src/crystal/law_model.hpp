// The kernel's forms of one case law: law_model<D, F> makes crystal::model_of of the form that the
// description D's parameters select (D::model), and so instantiates the contact passes of its
// forms: all of them (Forms::all), or only those whose pass gathers columns (laws with torques,
// Forms::gathered) or only the others (Forms::direct), nullptr when the selected form is not of
// that kind. A non-inline template: each real law's two kinds are compiled in units of their own
// (law_model_<law>.cpp, the direct passes at 256-bit vectors, and law_model_<law>_gathered.cpp,
// declared extern in law_models.cpp), so that a parallel build compiles them at once and each kind
// takes its own vector width; a law without such units (the test law) is instantiated in
// law_models.cpp, where the registry dispatches.
#pragma once
#include <memory>
#include <type_traits>

#include "crystal/dynamics.hpp"
#include "crystal/kernel.hpp"

namespace granwave::crystal {

enum class Forms { all, gathered, direct };

template <class D, Forms F = Forms::all>
std::shared_ptr<const ContactModel> law_model(const typename D::Params& params, double density) {
  return D::model(params, density, [](const auto& law) -> std::shared_ptr<const ContactModel> {
    if constexpr (F == Forms::all || (F == Forms::gathered) == std::decay_t<decltype(law)>::torques)
      return model_of(law);
    else
      return nullptr;
  });
}

}  // namespace granwave::crystal
