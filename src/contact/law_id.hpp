// The enumerator of each case-file contact law: the registry's dispatch key (contact/case_laws.hpp).
// Only the registry and each law's own description name an enumerator (tests/cli/law_registry_grep.sh).
#pragma once

namespace granwave::contact {

// linear: the linear spring-dashpot with Luding's tangential spring (seed 002 sec. 2.1, the
// default); hertz_mindlin: Hertz normal + Mindlin tangential. GRANWAVE_TEST_LAW (tests only) adds
// the test law of tests/laws/, registered through the same path.
enum class ContactLaw : unsigned char {
  linear,
  hertz_mindlin,
#ifdef GRANWAVE_TEST_LAW
  test_linear_dashpot,  // tests/laws/test_linear_dashpot.hpp
#endif
};

}  // namespace granwave::contact
