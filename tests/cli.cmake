# Command-line tests: exit codes and files, run through the real binary (label "cli").
# Each bad case must exit 2 with a message naming the key, and write nothing.
set(GW $<TARGET_FILE:granwave>)
set(BAD ${CMAKE_SOURCE_DIR}/tests/data/bad)
set(CLI_TMP ${CMAKE_BINARY_DIR}/cli-tests)
file(MAKE_DIRECTORY ${CLI_TMP})

function(granwave_cli_refuses name file key)
  foreach(verb check run build)
    if(verb STREQUAL "check")
      set(out_option "")  # check writes nothing and takes no -o
    else()
      set(out_option "-o ${CLI_TMP}/${name}.${verb}.h5")
    endif()
    add_test(NAME "cli: ${verb} refuses ${name}"
      COMMAND sh -c "rm -f ${CLI_TMP}/${name}.${verb}.h5*; ${GW} ${verb} ${BAD}/${file} ${out_option} 2> ${CLI_TMP}/${name}.${verb}.err; rc=$?; \
test $rc -eq 2 || { echo \"exit code $rc, expected 2\"; exit 1; }; \
grep -q -- '${key}' ${CLI_TMP}/${name}.${verb}.err || { cat ${CLI_TMP}/${name}.${verb}.err; echo 'message does not name ${key}'; exit 1; }; \
grep -q -- '${file}' ${CLI_TMP}/${name}.${verb}.err || { echo 'message does not name the file'; exit 1; }; \
! ls ${CLI_TMP}/${name}.${verb}.h5* 2>/dev/null || { echo 'wrote a file'; exit 1; }")
    set_tests_properties("cli: ${verb} refuses ${name}" PROPERTIES LABELS "cli;unit")
  endforeach()
endfunction()

granwave_cli_refuses(unknown_key unknown_key.toml "case.colour")
granwave_cli_refuses(negative_modulus negative_modulus.toml "materials.steel.youngs_modulus")
granwave_cli_refuses(off_grid_m off_grid_m.toml "magnetisation")
granwave_cli_refuses(crystal_mu crystal_mu.toml "contact.mu_dynamic")
# Issue 40: a random packing whose radius law makes radii negative (refused before any compression).
granwave_cli_refuses(random_width random_width.toml "random.width")
# A frictional preparation under a law without a tangential spring, and one asked for FIRE's finish.
granwave_cli_refuses(random_friction_no_spring random_friction_no_spring.toml "random.preparation_friction")
granwave_cli_refuses(random_friction_fire random_friction_fire.toml "random.minimise_from")
# Issue 40: the uncompressed gas is for `granwave packing CASE -o FILE` only.
granwave_cli_refuses(random_stop_gas random_stop_gas.toml "random.stop_at")
# A step budget that runs out at FIRE's preload says so.
granwave_cli_refuses(random_preload_steps random_preload_steps.toml "at the preload")
# Issue #14: the Hertz-Mindlin law's keys.
granwave_cli_refuses(hertz_negative_modulus hertz_negative_modulus.toml "contact.youngs_modulus")
granwave_cli_refuses(hertz_poisson_half hertz_poisson_half.toml "contact.poisson_ratio")
granwave_cli_refuses(hertz_with_kn hertz_with_kn.toml "contact.kn")
granwave_cli_refuses(linear_with_modulus linear_with_modulus.toml "contact.youngs_modulus")
granwave_cli_refuses(hertz_history hertz_history.toml "contact.tangential_history")

add_test(NAME "cli: missing case file exits 2" COMMAND sh -c "${GW} check /nonexistent/case.toml; test $? -eq 2")
add_test(NAME "cli: unknown verb exits 2" COMMAND sh -c "${GW} frobnicate; test $? -eq 2")
add_test(NAME "cli: unknown option exits 2" COMMAND sh -c "${GW} check ${BAD}/unknown_key.toml --frob; test $? -eq 2")
add_test(NAME "cli: every verb has --help" COMMAND sh -c "for v in build run check analyze theory probe sweep figures; do ${GW} $v --help > /dev/null || { echo $v; exit 1; }; done")
set_tests_properties("cli: missing case file exits 2" "cli: unknown verb exits 2" "cli: unknown option exits 2"
                     "cli: every verb has --help" PROPERTIES LABELS "cli;unit")
add_test(NAME "cli: sweep --threads -3 names the option and its range"
  COMMAND sh -c "${GW} sweep ${CMAKE_SOURCE_DIR}/data/studies/smoke.toml -o ${CLI_TMP}/threads.h5 --threads -3 2> ${CLI_TMP}/threads.err; rc=$?; \
test $rc -eq 2 || { echo \"exit code $rc, expected 2\"; exit 1; }; \
grep -q -- '--threads must be a positive integer' ${CLI_TMP}/threads.err || { cat ${CLI_TMP}/threads.err; exit 1; }; \
! ls ${CLI_TMP}/threads.h5* 2>/dev/null || { echo 'wrote a file'; exit 1; }")
set_tests_properties("cli: sweep --threads -3 names the option and its range" PROPERTIES LABELS "cli;unit")
include(${CMAKE_SOURCE_DIR}/tests/cli/guards.cmake)
include(${CMAKE_SOURCE_DIR}/tests/cli/ruler.cmake)
include(${CMAKE_SOURCE_DIR}/tests/cli/law_registry.cmake)
# ARCHITECTURE.md's "only X includes Y" claims against the #include lines of src/ and python/ (one row each in
# tests/cli/include_claims.py, with the rules that forbid an include).
add_test(NAME "cli: ARCHITECTURE.md's include claims hold"
  COMMAND /usr/bin/python3 ${CMAKE_SOURCE_DIR}/tests/cli/include_claims.py ${CMAKE_SOURCE_DIR})
set_tests_properties("cli: ARCHITECTURE.md's include claims hold" PROPERTIES LABELS "cli")
include(${CMAKE_SOURCE_DIR}/tests/cli/observables.cmake)
include(${CMAKE_SOURCE_DIR}/tests/cli/impact.cmake)
# granwave theory: the lattice-dynamics part (issue 15). Bad grid refused; JSON keys present for a
# Bravais packing, omitted with a note (exit 0) for a polydisperse one. Both 4 x 4 x 40 (kt = kn): a unit
# test, also run under the sanitizers, where the relaxed moduli of a 4 x 4 x 200 crystal take minutes.
add_test(NAME "cli: theory --nk 4 exits 2 naming the option and its range"
  COMMAND sh -c "${GW} theory ${CMAKE_SOURCE_DIR}/data/cases/crystal_kt10.toml --nk 4 2> ${CLI_TMP}/nk.err; rc=$?; \
test $rc -eq 2 || { echo \"exit code $rc, expected 2\"; exit 1; }; \
grep -q -- '--nk 4: must be an odd integer in \\[3, 10001\\]' ${CLI_TMP}/nk.err || { cat ${CLI_TMP}/nk.err; exit 1; }")
add_test(NAME "cli: theory --json gives the lattice speeds and six branches; polydisperse: a note"
  COMMAND sh -c "${GW} theory ${CMAKE_SOURCE_DIR}/tests/crosscheck/cases/crystal_small_stickslip.toml --json --nk 9 > ${CLI_TMP}/lat.json && \
${GW} theory ${CMAKE_SOURCE_DIR}/tests/crosscheck/cases/crystal_small_poly2.toml --json > ${CLI_TMP}/lat_poly.json && \
/usr/bin/python3 -c \"import json; d = json.load(open('${CLI_TMP}/lat.json')); D = d['dispersion']; \
assert len(D['branches']) == 6 and all(len(b['omega']['values']) == len(D['k']['values']) == 9 for b in D['branches']); \
assert sum(b['kind'] == 'acoustic' for b in D['branches']) == 3; \
assert d['V_sz_lattice']['value'] < d['V_sz']['value'] and abs(d['V_pz_lattice']['value'] / d['V_pz']['value'] - 1) < 1e-3; \
p = json.load(open('${CLI_TMP}/lat_poly.json')); assert not p['lattice']['available'] and 'polydisperse' in p['lattice']['note']; \
assert 'V_sz_lattice' not in p and 'V_sz' in p\"")
set_tests_properties("cli: theory --nk 4 exits 2 naming the option and its range"
                     "cli: theory --json gives the lattice speeds and six branches; polydisperse: a note" PROPERTIES LABELS "cli;unit")
# Issue 39: the relaxed moduli in theory --json. The FCC bulk's relaxed speeds are the lattice's
# long-wave speeds with rotations (1e-6); the slab relaxes less; Hertz-Mindlin gets Walton's estimate.
add_test(NAME "cli: theory --json gives the relaxed slab and bulk moduli and the effective-medium estimate"
  COMMAND sh -c "${GW} theory ${CMAKE_SOURCE_DIR}/data/cases/crystal_kt10.toml --json --nk 3 > ${CLI_TMP}/relaxed.json && \
${GW} theory ${CMAKE_SOURCE_DIR}/data/cases/crystal_hm_s.toml --json --nk 3 > ${CLI_TMP}/relaxed_hm.json && \
/usr/bin/python3 -c \"import json; d = json.load(open('${CLI_TMP}/relaxed.json')); r = d['relaxed']; v = lambda x: x['value']; \
assert abs(v(r['bulk']['V_sz']) / v(d['V_sz_lattice']) - 1) < 1e-6 and abs(v(r['bulk']['V_pz']) / v(d['V_pz_lattice']) - 1) < 1e-6, r['bulk']; \
assert v(r['bulk']['V_sz']) <= v(r['slab']['V_sz']) <= v(r['slab']['V_sz_affine']); \
assert r['slab']['rattlers'] == 0 and r['slab']['zero_modes']['mechanisms'] == 0 and r['slab']['unstable_modes'] == 0; \
e = d['effective_medium']; assert e['label'] == 'affine estimate' and e['model'] == 'linear_springs'; \
h = json.load(open('${CLI_TMP}/relaxed_hm.json'))['effective_medium']; assert h['model'] == 'walton_hertz_mindlin' and h['K']['value'] > 0\"")
set_tests_properties("cli: theory --json gives the relaxed slab and bulk moduli and the effective-medium estimate" PROPERTIES LABELS "cli")
# Issue 39: the relaxed moduli of a packing from a file. The FCC of tests/data/theory as an x y z r
# table: its bulk (the file's periodic packing relaxed, at rest already) is the built crystal's to
# 1e-9, the effective medium too; its slab (V = the file's box, 12 layers, no end-layer weights) has
# the zz-type components of the built slab (11 layer spacings) times 11/12: V_pz by sqrt(11/12).
add_test(NAME "cli: theory --json of an FCC read from a file: the built crystal's bulk, the slab's volume convention"
  COMMAND sh -c "${GW} theory ${CMAKE_SOURCE_DIR}/tests/data/theory/fcc_kt10_small.toml --json --nk 3 > ${CLI_TMP}/th_built.json && \
${GW} theory ${CMAKE_SOURCE_DIR}/tests/data/theory/fcc_kt10_small_file.toml --json > ${CLI_TMP}/th_file.json && \
/usr/bin/python3 -c \"import json, math; b = json.load(open('${CLI_TMP}/th_built.json')); f = json.load(open('${CLI_TMP}/th_file.json')); \
v = lambda x: x['value']; rb, rf = b['relaxed'], f['relaxed']; \
assert all(abs(v(rf['bulk'][k]) / v(rb['bulk'][k]) - 1) < 1e-9 for k in ('V_pz', 'V_sz', 'V_sy', 'pressure')), (rf['bulk'], rb['bulk']); \
assert 'triply periodic' in rf['bulk']['note'] and rf['bulk']['unbalanced'] < 1e-10 and rf['bulk']['unstable_modes'] == 0; \
assert abs(v(rf['slab']['V_pz']) / v(rb['slab']['V_pz']) - math.sqrt(11 / 12)) < 1e-9, (rf['slab'], rb['slab']); \
assert all(abs(v(f['effective_medium'][k]) / v(b['effective_medium'][k]) - 1) < 1e-9 for k in ('Z', 'phi', 'K', 'G'))\"")
set_tests_properties("cli: theory --json of an FCC read from a file: the built crystal's bulk, the slab's volume convention" PROPERTIES LABELS "cli")
# Issue 39: the static probe through the command line on the YADE packing (JSON keys, agreement with
# the relaxed slab tensor, nothing slides, a list of strains); xy (not offered) and a bad amplitude exit 2 naming what is allowed.
add_test(NAME "cli: probe --json agrees with the relaxed slab tensor (zx, yx); a bad strain and a bad amplitude exit 2"
  COMMAND sh -c "${GW} probe ${CMAKE_SOURCE_DIR}/tests/crosscheck/cases/packing_yade_p.toml --strain zx,yx --json > ${CLI_TMP}/probe.json && \
/usr/bin/python3 -c \"import json; d = json.load(open('${CLI_TMP}/probe.json')); \
assert [s['strain'] for s in d['strains']] == ['zx', 'yx'] and d['max_relative_error'] < 1e-4, d; \
assert all(s['sliding'] == 0 and s['contacts_changed'] == 0 for s in d['strains']), d; \
assert d['strains'][1]['component'] == 'A[1][0][1][0]', d; \
assert 'first Piola-Kirchhoff' in d['stress'] and all(abs(s['dP']['value'] / s['A_relaxed']['value'] - 1) < 1e-4 for s in d['strains'])\" && \
${GW} probe ${CMAKE_SOURCE_DIR}/tests/crosscheck/cases/packing_yade_p.toml --strain xy 2> ${CLI_TMP}/probe_xy.err; rc=$?; \
test $rc -eq 2 && grep -q 'allowed: zz, zx, xx, yy, yx' ${CLI_TMP}/probe_xy.err || { cat ${CLI_TMP}/probe_xy.err; exit 1; }; \
${GW} probe ${CMAKE_SOURCE_DIR}/tests/crosscheck/cases/packing_yade_p.toml --amplitude 0.1 2> ${CLI_TMP}/probe_a.err; rc=$?; \
test $rc -eq 2 && grep -q 'amplitude' ${CLI_TMP}/probe_a.err || { cat ${CLI_TMP}/probe_a.err; exit 1; }")
set_tests_properties("cli: probe --json agrees with the relaxed slab tensor (zx, yx); a bad strain and a bad amplitude exit 2" PROPERTIES LABELS "cli")
# Crystal studies honour --limit (stop, keep the batches, resume) and --threads (the study file does
# not depend on it): `granwave sweep` used to pass neither to crystal studies.
add_test(NAME "cli: crystal sweep --limit stops and resumes, --threads changes nothing"
  COMMAND sh -c "d=${CLI_TMP}/crystal_limit; rm -rf $d; mkdir -p $d; \
${GW} sweep ${CMAKE_SOURCE_DIR}/tests/data/mpi/crystal_tiny.toml -o $d/a.h5 --limit 1 --threads 1 --quiet > /dev/null 2> $d/err; rc=$?; \
test $rc -eq 0 || { cat $d/err; echo \"exit code $rc\"; exit 1; }; \
grep -q 'stopped after --limit 1 runs; 3 left' $d/err || { cat $d/err; exit 1; }; \
test ! -e $d/a.h5 && test -d $d/a.h5.parts || { ls -la $d; echo 'expected batches and no study file'; exit 1; }; \
${GW} sweep ${CMAKE_SOURCE_DIR}/tests/data/mpi/crystal_tiny.toml -o $d/a.h5 --threads 1 --quiet > $d/out 2>&1 || { cat $d/out; exit 1; }; \
grep -q '1 resumed, 3 computed' $d/out || { cat $d/out; exit 1; }; \
${GW} sweep ${CMAKE_SOURCE_DIR}/tests/data/mpi/crystal_tiny.toml -o $d/b.h5 --threads 2 --quiet > /dev/null 2>&1 || exit 1; \
h5diff $d/a.h5 $d/b.h5 /members /members || { echo 'members differ'; exit 1; }")
set_tests_properties("cli: crystal sweep --limit stops and resumes, --threads changes nothing" PROPERTIES LABELS "cli")
# Issue #14: every crystal trace records its contact law and tangential history (root attributes);
# a linear case says "linear" / "displacement", a Hertz-Mindlin case what it ran.
add_test(NAME "cli: crystal traces record contact_law and tangential_history"
  COMMAND sh -c "rm -f ${CLI_TMP}/law_lin.h5 ${CLI_TMP}/law_hm.h5; \
${GW} run ${CMAKE_SOURCE_DIR}/data/cases/crystal_small.toml -o ${CLI_TMP}/law_lin.h5 > /dev/null && \
${GW} run ${CMAKE_SOURCE_DIR}/tests/cli/cases/crystal_hertz_small.toml -o ${CLI_TMP}/law_hm.h5 > /dev/null && \
/usr/bin/python3 -c \"import h5py; a = h5py.File('${CLI_TMP}/law_lin.h5').attrs; b = h5py.File('${CLI_TMP}/law_hm.h5').attrs; \
s = lambda v: v.decode() if isinstance(v, bytes) else str(v); \
assert (s(a['contact_law']), s(a['tangential_history'])) == ('linear', 'displacement'), dict(a); \
assert (s(b['contact_law']), s(b['tangential_history']), s(b['lever_arm'])) == ('hertz_mindlin', 'force', 'contact_point'), dict(b)\"")
set_tests_properties("cli: crystal traces record contact_law and tangential_history" PROPERTIES LABELS "cli")
# Issue #14: granwave theory of a Hertz-Mindlin case, against the closed forms linearised at delta_0
# (glass beads: E = 63 GPa, nu = 0.23, rho = 2500, a = 1 mm, delta_0 = 1e-4 d): k_n = 2 E* sqrt(R* delta_0),
# k_t = 8 G* sqrt(R* delta_0), f0 = (4/3) E* sqrt(R*) delta_0^(3/2), eq. (10)'s V_pz = d' sqrt(k_n/m) sqrt(1 + k_t/k_n),
# the linearised t_c = pi sqrt(m*/k_n), the Hertz impact time at 1 m/s 2.86827 (m*^2/(R* E*^2 v))^(1/5); to the JSON's 10 digits.
add_test(NAME "cli: theory of a Hertz-Mindlin case: k_n, k_t, f0, V_pz, t_c against the closed forms at delta_0"
  COMMAND sh -c "${GW} theory ${CMAKE_SOURCE_DIR}/data/cases/crystal_hertz.toml --json --nk 9 > ${CLI_TMP}/hertz_theory.json && \
/usr/bin/python3 -c \"import json, math; d = json.load(open('${CLI_TMP}/hertz_theory.json')); v = lambda k: d[k]['value']; \
E, nu, rho, a = 63e9, 0.23, 2500.0, 1e-3; d0 = 1e-4 * 2 * a; Rs = a / 2; m = rho * 4 / 3 * math.pi * a ** 3; ms = m / 2; \
Es = E / (2 * (1 - nu * nu)); Gs = E / (2 * (1 + nu)) / (2 * (2 - nu)); kn = 2 * Es * math.sqrt(Rs * d0); kt = 8 * Gs * math.sqrt(Rs * d0); \
close = lambda x, y, e: abs(x / y - 1) < e; dp = 2 * a - d0; \
assert d['contact_law'] == 'hertz_mindlin'; \
assert close(v('k_n'), kn, 2e-9) and close(v('k_t'), kt, 2e-9), (v('k_n'), kn, v('k_t'), kt); \
assert close(v('f0'), 4 / 3 * Es * math.sqrt(Rs) * d0 ** 1.5, 2e-9); \
assert close(v('V_pz'), dp * math.sqrt(kn / m) * math.sqrt(1 + kt / kn), 2e-9), v('V_pz'); \
assert close(v('V_pz_frictionless'), dp * math.sqrt(kn / m), 2e-9); \
assert close(v('V_pz_lattice'), v('V_pz'), 1e-4); \
assert close(v('t_c'), math.pi * math.sqrt(ms / kn), 2e-9); \
h = d['hertz_impact']; assert close(h['t_c']['value'], 2.86827 * (ms * ms / (Rs * Es * Es * 1.0)) ** 0.2, 1e-6)\"")
set_tests_properties("cli: theory of a Hertz-Mindlin case: k_n, k_t, f0, V_pz, t_c against the closed forms at delta_0" PROPERTIES LABELS "cli")
# A Hertz-Mindlin run's summary takes the lattice speed from the law linearised at delta_0 (it read
# the linear law's kn, 0 for a Hertz case, and printed 0 m/s): a P wave turns no particle, so the
# lattice speed is eq. (10)'s up to the prestress term (2/3) delta_0/d' (7e-5 here).
add_test(NAME "cli: run --json of a Hertz-Mindlin crystal gives the lattice P speed of the linearised law"
  COMMAND sh -c "${GW} run ${CMAKE_SOURCE_DIR}/tests/cli/cases/crystal_hertz_small.toml -o ${CLI_TMP}/hm_lattice.h5 --json > ${CLI_TMP}/hm_lattice.json && \
/usr/bin/python3 -c \"import json; d = json.load(open('${CLI_TMP}/hm_lattice.json')); \
v, w = d['speed_theory'], d['speed_theory_lattice']; assert abs(w / v - 1) < 1e-3, (v, w)\"")
set_tests_properties("cli: run --json of a Hertz-Mindlin crystal gives the lattice P speed of the linearised law" PROPERTIES LABELS "cli")
# The contact-list builds (issue #41 item 3, the side-by-side's rebuild count): the construction's build is
# counted, and a wave of 1e-7 d never moves a particle by half the skin (0.05 a): 1; the crystal keeps its contacts.
add_test(NAME "cli: run --json counts the contact-list builds, the construction's included"
  COMMAND sh -c "${GW} run ${CMAKE_SOURCE_DIR}/tests/cli/cases/crystal_hertz_small.toml -o ${CLI_TMP}/builds.h5 --json > ${CLI_TMP}/builds.json && \
/usr/bin/python3 -c \"import json; d = json.load(open('${CLI_TMP}/builds.json')); \
assert d['contact_list_builds'] == 1, d['contact_list_builds']; assert d['contact_list_relists'] == 0, d; assert d['coordination_end'] == d['coordination'], d\"")
set_tests_properties("cli: run --json counts the contact-list builds, the construction's included" PROPERTIES LABELS "cli")
# The time loop's phases (crystal::RunResult::phases): every name, the sum the loop's wall time
# within 2 %, and one line of the text summary; `run --help` says what --quiet does. Bookkeeping,
# not physics.
add_test(NAME "cli: run --json carries the phases of the time loop, which add up to its wall time"
  COMMAND sh -c "${GW} run ${CMAKE_SOURCE_DIR}/data/cases/crystal_small.toml -o ${CLI_TMP}/phases.h5 --json --quiet > ${CLI_TMP}/phases.json && \
/usr/bin/python3 -c \"import json; d = json.load(open('${CLI_TMP}/phases.json')); p = d['phases']; \
assert set(p) == {'kick_drift', 'halo', 'list_upkeep', 'contact_pass', 'finish', 'sample', 'other'}, p; \
assert abs(sum(p.values()) - d['wall_seconds']) <= 0.02 * d['wall_seconds'], (p, d['wall_seconds'])\" && \
${GW} run ${CMAKE_SOURCE_DIR}/data/cases/crystal_small.toml -o ${CLI_TMP}/phases_text.h5 | grep -q '^  phases: kick+drift .* contact pass .* other ' && \
${GW} run --help | grep -q -- '--quiet leaves the progress line out'")
set_tests_properties("cli: run --json carries the phases of the time loop, which add up to its wall time" PROPERTIES LABELS "cli")
# Issue #25: a damaged trace on which the HDF5 library throws while looking a dataset up (it aborted
# granwave before: H5::Exception is no std::exception). Exit 2, naming the file and the dataset.
add_test(NAME "cli: analyze of a damaged trace exits 2 naming the file and the dataset"
  COMMAND sh -c "gzip -dc ${CMAKE_SOURCE_DIR}/tests/data/damaged/trace_lookup_throws.h5.gz > ${CLI_TMP}/damaged_lookup.h5 && \
${GW} analyze ${CLI_TMP}/damaged_lookup.h5 --json > /dev/null 2> ${CLI_TMP}/damaged_lookup.err; rc=$?; \
test $rc -eq 2 || { cat ${CLI_TMP}/damaged_lookup.err; echo \"exit code $rc, expected 2\"; exit 1; }; \
grep -q -- 'damaged_lookup.h5: damaged file: cannot look up .*/time' ${CLI_TMP}/damaged_lookup.err || { cat ${CLI_TMP}/damaged_lookup.err; exit 1; }")
set_tests_properties("cli: analyze of a damaged trace exits 2 naming the file and the dataset" PROPERTIES LABELS "cli;unit")
# analyze --pulse-field: a value other than stress | velocity | auto, or any value on a chain trace, exits 2
# naming the option.
add_test(NAME "cli: analyze --pulse-field refuses a bad value and a chain trace (exit 2)"
  COMMAND sh -c "${GW} run ${CMAKE_SOURCE_DIR}/data/cases/crystal_small.toml -o ${CLI_TMP}/pulse_crystal.h5 --quiet > /dev/null && \
${GW} run ${CMAKE_SOURCE_DIR}/data/cases/oriented20.toml -o ${CLI_TMP}/pulse_chain.h5 --quiet > /dev/null && \
${GW} analyze ${CLI_TMP}/pulse_crystal.h5 --pulse-field velocity --json > /dev/null && \
{ ${GW} analyze ${CLI_TMP}/pulse_crystal.h5 --pulse-field force 2> ${CLI_TMP}/pulse_bad.err; test $? -eq 2; } && \
grep -q -- '--pulse-field must be auto, stress or velocity' ${CLI_TMP}/pulse_bad.err && \
{ ${GW} analyze ${CLI_TMP}/pulse_chain.h5 --pulse-field velocity 2> ${CLI_TMP}/pulse_chain.err; test $? -eq 2; } && \
grep -q -- 'pulse_chain.h5: --pulse-field is for crystal traces' ${CLI_TMP}/pulse_chain.err")
set_tests_properties("cli: analyze --pulse-field refuses a bad value and a chain trace (exit 2)" PROPERTIES LABELS "cli")
# Issue 37's house rules: no source over 600 lines, each opening with its job, design.md's contracts <= 700 lines.
add_test(NAME "cli: house rules (file sizes, each file's job, design.md)"
  COMMAND /usr/bin/python3 ${CMAKE_SOURCE_DIR}/tests/cli/house_rules.py ${CMAKE_SOURCE_DIR})
set_tests_properties("cli: house rules (file sizes, each file's job, design.md)" PROPERTIES LABELS "cli")

# Issue 40: a random packing is the same bits on one thread and on two (the compression is serial,
# its pair sums sorted; the relaxation after it is the crystal's).
add_test(NAME "cli: a random packing builds the same bits on 1 and 2 threads"
  COMMAND sh -c "cd ${CLI_TMP} && rm -f random1.h5 random2.h5 && \
OMP_NUM_THREADS=1 ${GW} build ${CMAKE_SOURCE_DIR}/data/cases/random_small.toml -o random1.h5 2>/dev/null && \
OMP_NUM_THREADS=2 ${GW} build ${CMAKE_SOURCE_DIR}/data/cases/random_small.toml -o random2.h5 2>/dev/null && \
for d in /position /radius /mass /layer /role; do h5diff random1.h5 random2.h5 $d || exit 1; done")
set_tests_properties("cli: a random packing builds the same bits on 1 and 2 threads" PROPERTIES LABELS "cli")
# Issue 40: `granwave packing` writes the gas of random.stop_at = "gas" (docs/random-packing.md step 1): at the
# initial solid fraction 0.3, no two spheres touching, every particle in the dump.
add_test(NAME "cli: granwave packing writes the uncompressed gas"
  COMMAND sh -c "cd ${CLI_TMP} && rm -f gas.dump gas.json && ${GW} packing ${BAD}/random_stop_gas.toml -o gas.dump --json > gas.json && \
/usr/bin/python3 -c \"import json; d = json.load(open('gas.json')); assert d['particles'] == 300 and d['contacts'] == 0 and abs(d['solid_fraction'] - 0.3) < 1e-12, d; \
t = open('gas.dump').read().split('ITEM: ATOMS')[1].split(chr(10)); assert len([r for r in t[1:] if r]) == 300, 'rows'\"")
set_tests_properties("cli: granwave packing writes the uncompressed gas" PROPERTIES LABELS "cli")
# Issue 40: a frictional random packing (tests/data/random/random_friction.toml): its springs are
# written (spring_pairs, spring_xi); a system file whose springs are damaged is refused naming the
# dataset, nothing written (1 and 2 threads: tests/physics/randompacking_threads.cpp).
add_test(NAME "cli: a frictional random packing writes its springs, and run refuses a damaged spring dataset"
  COMMAND sh -c "cd ${CLI_TMP} && rm -f fric.h5 fric_bad.h5 fric_run.h5* && \
${GW} build ${CMAKE_SOURCE_DIR}/tests/data/random/random_friction.toml -o fric.h5 2>/dev/null && \
h5dump -H -d /spring_xi fric.h5 > /dev/null && h5dump -H -d /spring_pairs fric.h5 > /dev/null && \
/usr/bin/python3 -c \"import h5py,shutil; shutil.copy('fric.h5','fric_bad.h5'); f=h5py.File('fric_bad.h5','r+'); x=f['spring_xi'][()]; del f['spring_xi']; f['spring_xi']=x[:, :2]; f.close()\" && \
${GW} run ${CMAKE_SOURCE_DIR}/tests/data/random/random_friction.toml --system fric_bad.h5 -o fric_run.h5 2> fric_bad.err; rc=\$?; \
test \$rc -eq 2 || { cat fric_bad.err; echo \"exit code \$rc, expected 2\"; exit 1; }; \
grep -q 'spring_xi' fric_bad.err || { cat fric_bad.err; exit 1; }; \
! ls fric_run.h5* 2>/dev/null")
set_tests_properties("cli: a frictional random packing writes its springs, and run refuses a damaged spring dataset" PROPERTIES LABELS "cli")
# A random packing's system file holds it as prepared (/prepared, data/SCHEMA.md §2): a run from it
# prepares nothing and writes the trace bit for bit as the run that prepares it (frictionless, and
# frictional with its springs); a damaged group and another seed's file are refused (exit 2).
add_test(NAME "cli: a run from a random packing's system file takes it as prepared, the same bits"
  COMMAND /usr/bin/python3 ${CMAKE_SOURCE_DIR}/tests/cli/random_system.py ${GW} ${CLI_TMP}/random_system
          ${CMAKE_SOURCE_DIR}/data/cases/random_small.toml ${CMAKE_SOURCE_DIR}/tests/data/random/random_friction.toml)
set_tests_properties("cli: a run from a random packing's system file takes it as prepared, the same bits" PROPERTIES LABELS "cli")
