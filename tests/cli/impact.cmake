# The impact model (data/SCHEMA.md §7): bad cases exit 2 naming the key and write nothing; run and
# analyze measure a trace alike; build is refused (no system file). Included by tests/cli.cmake.
granwave_cli_refuses(impact_modulus_in_contact impact_modulus_in_contact.toml "contact.youngs_modulus")
granwave_cli_refuses(impact_restitution_range impact_restitution_range.toml "contact.restitution")
granwave_cli_refuses(impact_overlap impact_overlap.toml "impact.body2.position")
granwave_cli_refuses(impact_wall_material impact_wall_material.toml "impact.wall.material")
foreach(verb check run theory)
  set(o "")
  if(verb STREQUAL "run")
    set(o "-o ${CLI_TMP}/receding.h5")
  endif()
  add_test(NAME "cli: impact: ${verb} refuses bodies that do not approach"
    COMMAND sh -c "rm -f ${CLI_TMP}/receding.h5*; ${GW} ${verb} ${BAD}/impact_receding.toml ${o} 2> ${CLI_TMP}/receding.${verb}.err; rc=$?; \
test $rc -eq 2 || { echo \"exit code $rc, expected 2\"; exit 1; }; \
grep -q -- 'impact.body1.velocity' ${CLI_TMP}/receding.${verb}.err || { cat ${CLI_TMP}/receding.${verb}.err; exit 1; }; \
! ls ${CLI_TMP}/receding.h5* 2>/dev/null || { echo 'wrote a file'; exit 1; }")
  set_tests_properties("cli: impact: ${verb} refuses bodies that do not approach" PROPERTIES LABELS "cli;unit")
endforeach()
add_test(NAME "cli: impact: run --json carries exactly what analyze --json measures on its trace"
  COMMAND sh -c "rm -f ${CLI_TMP}/t2.h5; ${GW} run ${CMAKE_SOURCE_DIR}/data/impact/t2/t2_al_alloy_t2.toml -o ${CLI_TMP}/t2.h5 --json > ${CLI_TMP}/t2.run.json && \
${GW} analyze ${CLI_TMP}/t2.h5 --json > ${CLI_TMP}/t2.analyze.json && \
/usr/bin/python3 -c \"import json; r = json.load(open('${CLI_TMP}/t2.run.json')); a = json.load(open('${CLI_TMP}/t2.analyze.json')); \
assert r['model'] == 'impact' and r['analysis'] == a, (r['analysis'], a); assert a['rebound']['separated']\"")
add_test(NAME "cli: impact: build is refused (an impact case has no system file)"
  COMMAND sh -c "${GW} build ${CMAKE_SOURCE_DIR}/data/impact/t1/t1_glass.toml -o ${CLI_TMP}/t1.system.h5 2> ${CLI_TMP}/t1.build.err; rc=$?; \
test $rc -eq 2 && grep -q 'no system file' ${CLI_TMP}/t1.build.err && ! test -e ${CLI_TMP}/t1.system.h5")
set_tests_properties("cli: impact: run --json carries exactly what analyze --json measures on its trace"
                     "cli: impact: build is refused (an impact case has no system file)" PROPERTIES LABELS "cli;unit")
