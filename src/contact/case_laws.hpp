// The registry of case-file contact laws: the one list of their descriptions (contact/case_law.hpp)
// and the one dispatch from contact::ContactLaw to a description. A switch without `default`,
// built with -Werror=switch: an enumerator without its case does not compile, and a case whose
// description is not in the list fails the static_assert of Described (tests/cli.cmake's
// law_registry_* tests show both, and that no ContactLaw:: comparison is left outside).
// Only the registry's translation units include this header: config/contact_laws.cpp (what code
// outside a law asks), crystal/law_models.cpp (the kernel's instantiations) and impact/simulate.cpp
// (the impact's); `granwave laws` reads the records of config/contact_laws.cpp.
#pragma once
#include <stdexcept>
#include <tuple>
#include <type_traits>

#include "contact/case_law.hpp"
#include "contact/hertz_mindlin_case.hpp"
#include "contact/linear_luding_case.hpp"
#ifdef GRANWAVE_TEST_LAW
#include "laws/test_linear_dashpot.hpp"  // tests/laws/: the test-only third law (granwave_testlaw)
#endif

namespace granwave::contact {

template <class... D>
struct LawList {};

using CaseLaws = LawList<LinearLudingCase, HertzMindlinCase
#ifdef GRANWAVE_TEST_LAW
                         , TestLinearDashpotCase
#endif
                         >;

// The description of enumerator L in CaseLaws (exactly one).
template <ContactLaw L, class List = CaseLaws>
struct Described;
template <ContactLaw L, class... D>
struct Described<L, LawList<D...>> {
  static_assert(((D::law == L) + ... + 0) == 1, "a ContactLaw enumerator needs exactly one description in CaseLaws");
  using type = std::tuple_element_t<0, decltype(std::tuple_cat(
                                           std::declval<std::conditional_t<D::law == L, std::tuple<D>, std::tuple<>>>()...))>;
};

// f(D{}) for the description D of `law`.
template <class F>
decltype(auto) visit_law(ContactLaw law, F&& f) {
  switch (law) {
    case ContactLaw::linear: return f(typename Described<ContactLaw::linear>::type{});
    case ContactLaw::hertz_mindlin: return f(typename Described<ContactLaw::hertz_mindlin>::type{});
#ifdef GRANWAVE_TEST_LAW
    case ContactLaw::test_linear_dashpot: return f(typename Described<ContactLaw::test_linear_dashpot>::type{});
#endif
  }
  throw std::logic_error("contact law: a value that is no enumerator");
}

// f(D{}) for every description, in list order.
template <class F, class... D>
void for_each_law(F&& f, LawList<D...>) {
  (f(D{}), ...);
}
template <class F>
void for_each_law(F&& f) {
  for_each_law(f, CaseLaws{});
}

}  // namespace granwave::contact
