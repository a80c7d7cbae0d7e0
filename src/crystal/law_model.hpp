// The kernel's forms of one case law: law_model<D, F> makes crystal::model_of of the form that the
// description D's parameters select (D::model), and so instantiates the contact passes of its
// forms: all of them (Forms::all), or only the wide ones (Forms::wide: the gathered passes, friction,
// which 512-bit vectors make faster; with rolling and torsion only where couples_wide is set, below)
// or only the others (Forms::narrow: the direct passes, which 512 bits make 27 % slower, and
// otherwise the forms with rolling and torsion); nullptr when the selected form is not of that kind.
// A non-inline template: each real law's two kinds are compiled in units of their own
// (law_model_<law>.cpp at 256-bit vectors, law_model_<law>_wide.cpp at 512 where the machine has
// them; declared extern in law_models.cpp), so that a parallel build compiles them at once; a law
// without such units (the test law) is instantiated in law_models.cpp, where the registry dispatches.
#pragma once
#include <memory>
#include <type_traits>

#include "contact/law.hpp"
#include "crystal/dynamics.hpp"
#include "crystal/kernel.hpp"

namespace granwave::crystal {

enum class Forms { all, wide, narrow };

// The forms with couples join the wide units where the cores run 512-bit operations whole (CMake's
// GRANWAVE_COUPLES_512: Intel cores with AVX-512, the rolling pass 9 % faster; Zen 5, 14 %); Zen 4
// runs them as two halves, and there they lost 10 % at 320 000 particles (docs/benchmarks.md,
// sessions 30, 32 and 36).
#ifdef GRANWAVE_COUPLES_512
inline constexpr bool couples_wide = true;
#else
inline constexpr bool couples_wide = false;
#endif

template <class Law>
inline constexpr bool wide_form = Law::torques && (couples_wide || !contact::HasCouples<Law>);

template <class D, Forms F = Forms::all>
std::shared_ptr<const ContactModel> law_model(const typename D::Params& params, double density) {
  return D::model(params, density, [](const auto& law) -> std::shared_ptr<const ContactModel> {
    if constexpr (F == Forms::all || (F == Forms::wide) == wide_form<std::decay_t<decltype(law)>>)
      return model_of(law);
    else
      return nullptr;
  });
}

}  // namespace granwave::crystal
