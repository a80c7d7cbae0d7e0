# Adding a ContactLaw enumerator without its description does not compile (issue #26): a tiny
# translation unit that dispatches through the registry (contact/case_laws.hpp) is compiled
# against a copy of contact/law_id.hpp with one more enumerator, and must fail at the registry's
# switch (-Werror=switch); with the case added to the switch but no description in CaseLaws it
# must fail at Described's static_assert; the unchanged headers must compile.
# cmake -DCXX=... -DSRC=<source dir> -DOUT=<scratch dir> -P law_enumerator_probe.cmake
file(REMOVE_RECURSE ${OUT})
file(MAKE_DIRECTORY ${OUT}/enum/contact ${OUT}/case/contact)
file(WRITE ${OUT}/probe.cpp
"#include \"contact/case_laws.hpp\"
int main() {
  return granwave::contact::visit_law(granwave::contact::ContactLaw::linear, [](auto d) { return int(sizeof(d)); });
}
")
file(READ ${SRC}/src/contact/law_id.hpp case_hpp)
string(REPLACE "  hertz_mindlin,\n" "  hertz_mindlin,\n  rolling_resistance,\n" case_more "${case_hpp}")
if(case_more STREQUAL case_hpp)
  message(FATAL_ERROR "contact/law_id.hpp: the enumerator list 'hertz_mindlin,' was not found; update this probe")
endif()
file(WRITE ${OUT}/enum/contact/law_id.hpp "${case_more}")
file(WRITE ${OUT}/case/contact/law_id.hpp "${case_more}")
file(READ ${SRC}/src/contact/case_laws.hpp laws_hpp)
string(REPLACE "  switch (law) {\n" "  switch (law) {\n    case ContactLaw::rolling_resistance: return f(typename Described<ContactLaw::rolling_resistance>::type{});\n"
       laws_more "${laws_hpp}")
if(laws_more STREQUAL laws_hpp)
  message(FATAL_ERROR "contact/case_laws.hpp: its switch was not found; update this probe")
endif()
file(WRITE ${OUT}/case/contact/case_laws.hpp "${laws_more}")

function(probe name include expect_ok pattern)
  execute_process(COMMAND ${CXX} -std=c++20 -fsyntax-only -Wall -Werror=switch ${include} -I${SRC}/src ${OUT}/probe.cpp
                  RESULT_VARIABLE rc ERROR_VARIABLE err OUTPUT_QUIET)
  if(expect_ok AND NOT rc EQUAL 0)
    message(FATAL_ERROR "${name}: the unchanged registry does not compile:\n${err}")
  elseif(NOT expect_ok AND rc EQUAL 0)
    message(FATAL_ERROR "${name}: compiled, but a law without its description must not")
  elseif(NOT expect_ok AND NOT err MATCHES "${pattern}")
    message(FATAL_ERROR "${name}: failed for another reason than expected (${pattern}):\n${err}")
  endif()
  message(STATUS "${name}: as expected")
endfunction()

probe("unchanged registry" "" TRUE "")
probe("enumerator without a case" "-I${OUT}/enum" FALSE "rolling_resistance.*not handled in switch")
probe("case without a description" "-I${OUT}/case" FALSE "needs exactly one description in CaseLaws")
