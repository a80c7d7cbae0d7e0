#!/usr/bin/python3
"""granwave, LAMMPS and LIGGGHTS side by side: the same crystal, one thread, end to end.

    /usr/bin/python3 bench/side_by_side.py [--cases frictionless,friction,friction_radius,hertz,rolling,rolling_luding,rolling_s,long]
        [--codes granwave,lammps,liggghts] [--granwave build/granwave] [--granwave-avx2 build-avx2/granwave]
        [--reps 3] [--out table.md] [--json results.json] [--workdir DIR] [--keep]

What is timed
-------------
Each code runs the same system (the file `granwave build` writes; the other two read it as a LAMMPS
data file rendered from it, not timed) in a fresh directory, one process, one thread
(OMP_NUM_THREADS=1 for every code; Debian's LAMMPS and LIGGGHTS are MPI builds, run here as one
process without mpirun; Debian's LAMMPS has no OPENMP, KOKKOS or INTEL package: a generic build, its
gran styles have no accelerated variant in it). The time is the whole process, start-up, input, run and output
included: wall time, and CPU time (user + system, from the child's rusage). Every code writes the
six per-layer fields of a granwave trace (data/SCHEMA.md §3: sigma_zz, sigma_zx, mean velocity z
and x, mean displacement z and x) every 5 steps (the seed's 1 us at dt = 2e-7 s); granwave's trace
also carries its energies and coordination, which the other two do not compute.

The runs alternate: repetition k runs every code once, in an order rotated by k, so that a change
of machine load hits all codes alike. Each code's time is the median of its runs; each ratio is the
median of the per-repetition ratios (other code / granwave build, same repetition), so a ratio
compares runs made next to each other. Ratios > 1: granwave is faster.

Cases (`--cases`)
-----------------
frictionless  data/cases/crystal_p.toml: the seed's 4 x 4 x 200 FCC crystal (3200 particles), kt = 0,
              6000 steps of 2e-7 s, step of the two bottom layers by 1e-4 d (seed 002 secs. 3.1-3.3)
friction      data/cases/crystal_kt10.toml: the same with kt = k, mu = 0.5, lever_arm = "contact_point"
              (seed 002 sec. 3.5): LIGGGHTS' physics (its tangential arm is the contact point); LAMMPS
              runs its own, the radius arm, so its ratio in this row compares different physics
friction_radius
              the same with lever_arm = "radius" (seed 002 eq. (4)): LAMMPS' gran/hooke/history physics,
              the fair row against LAMMPS; LIGGGHTS is not run in it (its arm is the contact point)
long          crystal_p with 4 x 4 x 20000 cells (320 000 particles), 200 steps
long_friction_radius, long_hertz, long_rolling
              friction_radius, hertz and rolling on the same 320 000 particles, 200 steps each
hertz         data/cases/crystal_hertz.toml: the same crystal of glass beads with Hertz normal and Mindlin
              tangential forces (issue #14), 6000 steps of 1.7e-7 s; LAMMPS `pair_style granular` with
              `hertz/material E 0 nu tangential mindlin NULL 0 mu`, LIGGGHTS `model hertz tangential history`
rolling       bench/cases/crystal_rolling.toml: friction_radius with Luding's rolling and torsion springs (issue
              #28), kr = ko = kt/2, mu_r = mu_o = 0.1; LAMMPS `pair_style granular` with `hooke`, `tangential
              linear_history`, `rolling sds`, `twisting sds` (the crosscheck's map, xclib.codefacts: k_twist = ko
              a'^2, mu_twist = mu_o a'), the only LAMMPS style with them; LIGGGHTS is not run (its `rolling_friction
              luding` has no separate torsion spring or limits: its driver refuses the case). The P step turns no
              sphere, so the springs stay near zero: the case times their arithmetic (the physics check is the P
              wave's)
rolling_luding  the rolling case as LIGGGHTS' `model luding tangential tan_luding rolling_friction luding torsion
              on` runs it (the crosscheck's map): contact-point arm, rolling_lever = "radii", rolling_history =
              "fixed", torsion lumped with rolling (ko = kr), no limits; granwave and LIGGGHTS (LAMMPS' sds turns
              its history with the pair)
rolling_s, rolling_luding_s
              the two rolling cases with seed 002's S step (1.7e-3 s, as data/cases/crystal_s.toml): the
              springs turn with the wave (physics check on the layer velocity v_x)
disordered    bench/cases/disordered.toml (issue #41 item 3): a disordered polydisperse column of 20 000 glass
              beads (radii 0.5 mm (1 +- 0.15), 10 x 10 x 161 mean diameters) that LAMMPS made with
              bench/cases/disordered_packing.lmp (frictionless gran/hooke, fix deform to solid fraction 0.655,
              10 000 steps; made once, about 1 min of CPU, kept in --packing-cache); granwave imports it, cuts it
              open in z and relaxes it under the case's law (`granwave build`, not timed); Hertz-Mindlin of the
              `hertz` case (E = 63 GPa, nu = 0.23, mu = 0.5), the radius arm, a P step of 1e-4 d, 3032 steps of
              t_c/50, output every 30 steps (1 us); granwave and LAMMPS (`gran/hertz/history Kn Kt 0 0 mu 0`,
              Kn = 4/3 E*, Kt = 8 G*: the crosscheck's map, the radius arm). After the timed runs, one more run
              of each code, not timed, writes positions at 11 instants: the contacts that open and close (below).
disordered_cp the same with the contact-point arm: granwave and LIGGGHTS (`model hertz tangential history`)
disordered_small, disordered_small_cp
              the two on the committed 3060-particle column data/packings/lammps_tall/packing_w5.dump
              (1764 steps): the smoke cases of the packing decks
small         data/cases/crystal40.toml (4 x 4 x 40, 1300 steps): a smoke case for the tests, not a benchmark

Each code's set-up, and why it is the fastest fair equivalent
--------------------------------------------------------------
granwave: `granwave run CASE --system system.h5 -o traces.h5 --json`, its normal trace output (all
  layer fields, energies, coordination every 5 steps). `--granwave PATH` times a given build;
  `--granwave-avx2 PATH` a second one (e.g. built with -DCMAKE_CXX_FLAGS=-mno-avx512f).
LAMMPS (lammps_inputs/templates/crystal_layers.in.tmpl):
  * frictionless: `pair_style gran/hooke kn 0 0 0 mu 0` (no shear history to store, look up or rotate)
    and `fix nve` (no torque acts, so no rotational integration); with friction
    `gran/hooke/history kn kt 0 0 mu 0` and `fix nve/sphere`; with rolling and torsion `pair_style granular`
    (`hooke kn 0 tangential linear_history kt 0 mu damping velocity rolling sds ... twisting sds ...`, the
    crosscheck deck's, whose torque arm is a - delta/2). LAMMPS's tangential arm is the radius a
    (pair_gran_hooke_history.cpp: radi * omega, radi * torque), i.e. granwave's lever_arm = "radius":
    the case friction_radius compares the same physics; in the case friction granwave runs its (dearer)
    "contact_point", LIGGGHTS' physics.
  * `newton on`: each pair once, ghosts included (faster than `off` on the 3200-particle crystal,
    one run each on a busy machine: loop 4.1 s against 5.3 s frictionless, 4.8 against 5.2 s with
    friction).
  * neighbours: skin 0.2 a (`bin`), so the list holds the 12 touching neighbours and nothing else
    (the next shell is 0.83 a beyond contact); the atoms move about 1e-4 d, far below skin/2, so
    `neigh_modify delay 0 every 10 check yes` never rebuilds (the log's "Neighbor list builds" is
    recorded and must be 0) and checks only every 10 steps. Pairs of two fixed atoms are excluded
    (`exclude type`), as granwave does. The data file carries mass as density (monodisperse), so
    no per-atom `set` commands.
  * per-layer output by LAMMPS itself: `compute stress/atom NULL pair` + `compute chunk/atom bin/1d z`
    (bins of height l0 centred on the layers, `ids once`: the lattice is static) + `fix ave/chunk 5 1 5`;
    the per-atom virial is tallied only on the output steps.
LIGGGHTS (liggghts_inputs/templates/crystal_layers.in.tmpl): `gran model hooke/stiffness` with `tangential
  no_history` frictionless (`fix nve`) or `tangential history` with friction (`fix nve/sphere`);
  the same neighbour settings; `newton on` frictionless (loop 6.6 s against 8.5 s with `off`, measured
  as for LAMMPS), `off`
  with friction (LIGGGHTS refuses shear history with `newton on`); per-layer output
  by `compute stress/atom pair` + `fix ave/spatial 5 1 5 z` (LIGGGHTS 3.8 has no chunk commands), no
  per-pair dumps (the crosscheck's dumps are 2.4 GB on this crystal, 138 s of a 250 s run).

The disordered case: list rules and counts
-----------------------------------------
The same skin and rebuild rule in the three codes: granwave's Verlet list holds the pairs closer than
a_i + a_j + skin, skin = 0.1 x the mean radius (src/crystal/dynamics.cpp, list_skin), and is rebuilt when a
particle has moved more than skin/2 since the last build, tested every step; LAMMPS and LIGGGHTS run
`neighbor SKIN bin` with that skin (their granular lists hold the pairs within r_i + r_j + skin) and
`neigh_modify delay 0 every 1 check yes` (the same displacement test every step). What differs: granwave
rebuilds once at construction and counts it (`run --json` contact_list_builds, so 1 = no rebuild in the run);
LAMMPS' and LIGGGHTS' "Neighbor list builds" count only the builds of the run after its set-up; LAMMPS and
LIGGGHTS bin atoms into cells of the skin-extended cut-off, granwave into its own cells (same pairs).
Pairs of two fixed particles are left out everywhere. The contacts that open and close: each code's
position snapshots (granwave: .vtp files of [output] vtk_every, positions = the system's + the written
displacement; LAMMPS and LIGGGHTS: `dump custom id x y z` at 17 digits) at the same 11 steps (step 0 after the
source's step, then every ~10 % of the run); at each the touching pairs |x_j - x_i| < a_i + a_j (minimum image
in x, y; fixed pairs left out), counted by one Python function (sidebyside/packing.py) for every code:
opened / closed = pairs that appear / disappear between consecutive snapshots, summed (a contact that opens
and closes between two snapshots is missed).
The arms: LAMMPS' gran/hertz/history takes the radius (granwave's lever_arm = "radius"; its pair granular,
the `hertz` row's style, takes the radius in the velocity and a - delta/2 in the torque, which granwave does
not run: 2 % of the peak in v_z on the 3060-particle column), LIGGGHTS' the contact point: one row each.
LIGGGHTS bins by the atoms' current z (no chunks in 3.8): an atom that crosses a bin boundary during the run
would show in its v_z difference (none did on the 3060-particle column: 1.2e-6, its 6 printed digits).

Physics check
-------------
The packing cases: the half-peak speed of the bins' v_z (granwave's own pulse field on a packing), and the
largest difference of v_z and of sigma_zz's change from t = 0 (layers.packing_deviations says why not sigma_zz
itself: stress/atom gives each atom half a pair's virial, granwave the branch to the contact point).
The crystals:
So that nobody benchmarks a wrong set-up, the last repetition's output of every code is measured
by the one ruler, `granwave analyze --json` (LAMMPS' and LIGGGHTS' layer files are turned into
trace files first): the half-peak speed (z/l0 = 10..150; 1..4 for the `long` rows, whose 200 steps carry
the front about 6 layers), and the largest difference of sigma_zz (S cases: of the layer velocity v_x;
the layer files' stress/atom xz is delx fz, the transpose of sigma_zx) from granwave's trace over all
layers and samples, relative to granwave's largest change (the wave's peak), beside what the
layer file's printed digits allow (half a unit in the last digit; LIGGGHTS prints 6 digits, so on the
`hertz` case, a wave of 1e-3 of the prestress, its 1.9e-3 is its output's resolution, not its physics).

Modules (bench/sidebyside/; this file is the command line)
----------------------------------------------------------
cases    the cases and their decks, taken from the drivers (`render(..., output="layers")` of
         lammps_inputs/lammps_case.py and liggghts_inputs/liggghts_case.py)
running  running and timing each code; a case's alternating repetitions and its physics check
layers   LAMMPS' and LIGGGHTS' per-layer output -> trace files; the physics check's measures
packing  the disordered case's packing (made and cached) and the contact counts
stats    medians, paired ratios, the rotated order of the runs
machine  CPU model and SIMD flags, load, the granwave build's flags, the codes' versions
report   the Markdown tables and document, the JSON document
"""
from __future__ import annotations

import argparse
import os
import shutil
import sys
import tempfile
import time

HERE = os.path.dirname(os.path.abspath(__file__))
REPO = os.path.dirname(HERE)
sys.path.insert(0, HERE)
sys.path.insert(0, os.path.join(REPO, "crosscheck"))
from xclib import traces as T  # noqa: E402,F401  (bench/mpi_crystal.py reads cases through it)

from sidebyside.cases import (CASE_CODES, CASES, CODE_TITLES, CODES, DEFAULT_CASES, BenchError,  # noqa: E402,F401
                              case_text, render_lammps, render_liggghts)
from sidebyside.layers import layers_to_trace, packing_layers_to_trace, read_layer_file  # noqa: E402,F401
from sidebyside.machine import cmake_cache, code_version, cpu_facts, granwave_build_facts, load_facts  # noqa: E402,F401
from sidebyside.report import memory_table, sanity_table, table, write_report  # noqa: E402,F401
from sidebyside.running import Runner, bench_case  # noqa: E402,F401
from sidebyside.stats import median, paired_ratio, rotation, summarize  # noqa: E402,F401


def main(argv=None) -> int:
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("--cases", default=",".join(DEFAULT_CASES), help="comma list of %s" % ", ".join(CASES))
    ap.add_argument("--codes", default=",".join(CODES), help="comma list of granwave, lammps, liggghts")
    ap.add_argument("--granwave", default=os.path.join(REPO, "build", "granwave"), help="the granwave binary to time")
    ap.add_argument("--granwave-avx2", default=None, help="a second granwave build to time (e.g. -mno-avx512f)")
    ap.add_argument("--lammps", default="lmp")
    ap.add_argument("--liggghts", default="liggghts")
    ap.add_argument("--reps", type=int, default=3, help="runs of each code per case (median; >= 3 for a benchmark)")
    ap.add_argument("--out", help="also write the Markdown report here")
    ap.add_argument("--json", help="write every run and fact as JSON here")
    ap.add_argument("--workdir", help="where the runs go (default: a temporary directory, removed at the end)")
    ap.add_argument("--keep", action="store_true", help="keep every run's directory")
    ap.add_argument("--timeout", type=float, default=3600, help="seconds per run")
    ap.add_argument("--packing-cache", default=None,
                    help="where the disordered case's LAMMPS packing is made once and kept (default: "
                         "$XDG_CACHE_HOME/granwave-bench or ~/.cache/granwave-bench)")
    a = ap.parse_args(argv)
    try:
        cases = [c.strip() for c in a.cases.split(",") if c.strip()]
        for c in cases:
            if c not in CASES:
                raise BenchError("side_by_side: --cases: unknown case %r (allowed: %s)" % (c, ", ".join(CASES)))
        codes = [c.strip() for c in a.codes.split(",") if c.strip()]
        for c in codes:
            if c not in CODES:
                raise BenchError("side_by_side: --codes: unknown code %r (allowed: %s)" % (c, ", ".join(CODES)))
        if "granwave" not in codes:
            raise BenchError("side_by_side: --codes must include granwave (the reference of every ratio)")
        if a.reps < 1:
            raise BenchError("side_by_side: --reps must be >= 1 (>= 3 for a benchmark)")
        runners = []
        gws = [("granwave", a.granwave)] + ([("granwave-avx2", a.granwave_avx2)] if a.granwave_avx2 else [])
        gw_facts = {}
        for key, path in gws:
            exe = shutil.which(path) if "/" not in path else (os.path.abspath(path) if os.access(path, os.X_OK) else None)
            if not exe:
                raise BenchError("side_by_side: granwave binary not found: %s (build it: cmake --build build --target "
                                 "granwave, or pass --%s PATH)" % (path, key))
            gw_facts[key] = granwave_build_facts(exe)
            title = "granwave [%s]" % gw_facts[key]["flags"].replace("-O3 ", "")
            runners.append(Runner(key, "granwave", exe, title))
        versions = {}
        for code, exe_name, pkg in (("lammps", a.lammps, "lammps"), ("liggghts", a.liggghts, "liggghts")):
            if code not in codes:
                continue
            exe = shutil.which(exe_name)
            if not exe:
                raise BenchError("side_by_side: %s not found (%s): install Debian's %s (scripts/setup.sh) or leave it "
                                 "out with --codes" % (CODE_TITLES[code], exe_name, pkg))
            versions[code] = code_version(exe, code)
            runners.append(Runner(code, code, exe, CODE_TITLES[code]))
    except BenchError as e:
        print(str(e), file=sys.stderr)
        return 2
    skipped = [c for c in CODES if c not in codes]
    notes = []
    for c in skipped:
        notes.append("**NOTE: %s was left out by --codes: its columns are empty.**" % CODE_TITLES[c])
    if a.reps < 3:
        notes.append("**NOTE: --reps %d: fewer than 3 runs per code, not a benchmark (a smoke run).**" % a.reps)
    for n in notes:
        print(n, file=sys.stderr)

    env = dict(os.environ, OMP_NUM_THREADS="1", OMP_PROC_BIND="false")
    root = a.workdir or tempfile.mkdtemp(prefix="side_by_side.")
    os.makedirs(root, exist_ok=True)
    cpu = cpu_facts()
    load0 = load_facts()
    log = lambda s: print(s, file=sys.stderr, flush=True)  # noqa: E731
    results = []
    t_start = time.time()
    try:
        for name in cases:
            log("case %s" % name)
            results.append(bench_case(name, runners, a.reps, root, runners[0].exe, a.timeout, env, a.keep, log,
                                      cache=a.packing_cache, lmp=a.lammps))
    except RuntimeError as e:
        print("side_by_side: %s" % e, file=sys.stderr)
        return 1
    finally:
        if not a.workdir and not a.keep:
            shutil.rmtree(root, ignore_errors=True)
    write_report(a, argv if argv is not None else sys.argv[1:], cpu, load0, load_facts(), t_start, gw_facts, versions,
                 notes, results, runners, codes)
    return 0


if __name__ == "__main__":
    sys.exit(main())
