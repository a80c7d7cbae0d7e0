"""bench/side_by_side.py: deck rendering, layer-file reading, the ratio and median maths, the exit
codes (fast, no real runs); one short real run of the three codes under the `realcodes` marker."""
import json
import math
import os
import shutil
import sys

import numpy as np
import pytest

from xclib import sysbuild
from xclib import traces as T

HERE = os.path.dirname(os.path.abspath(__file__))
REPO = os.path.dirname(os.path.dirname(HERE))
sys.path.insert(0, os.path.join(REPO, "bench"))
import side_by_side as S  # noqa: E402


def _system(tmp_path, cases_dir, name):
    case, _ = T.load_case(os.path.join(cases_dir, name))
    sp = str(tmp_path / "sys.h5")
    sysbuild.build(case, sp)
    return case, T.read_system(sp), sp


# ---------------------------------------------------------------- statistics
def test_paired_ratio_is_the_median_of_the_per_repetition_ratios():
    # repetition 2 ran under load for both codes: its ratio stays 2, the medians of the times do not
    other = [10.0, 40.0, 12.0]
    ref = [5.0, 20.0, 4.0]
    assert S.paired_ratio(other, ref) == 2.0                      # ratios 2, 2, 3
    assert S.median(other) / S.median(ref) == 12.0 / 5.0           # what a ratio of medians would say
    assert S.paired_ratio([3.0, 9.0], [1.0, 1.0]) == 6.0           # even count: the mean of the middle two
    assert S.paired_ratio([1.0, None], [1.0, 2.0]) == 1.0          # a missing run drops its pair only
    assert S.paired_ratio([], []) is None
    assert S.median([3.0, 1.0, 2.0]) == 2.0 and S.median([None]) is None


def test_rotation_puts_every_code_in_every_place():
    items = ["g", "l", "L"]
    orders = [S.rotation(items, k) for k in range(3)]
    assert orders == [["g", "l", "L"], ["l", "L", "g"], ["L", "g", "l"]]
    for pos in range(3):
        assert sorted(o[pos] for o in orders) == sorted(items)
    assert S.rotation(items, 4) == orders[1] and S.rotation([], 2) == []


# ---------------------------------------------------------------- machine facts
def test_cpu_facts_reads_the_simd_flags():
    info = "model name\t: Some CPU\nflags\t\t: fpu sse2 avx avx2 fma avx512f avx512vl\n\nflags\t: fpu\n"
    f = S.cpu_facts(info)
    assert f["model"] == "Some CPU" and f["avx2"] and f["avx512f"]
    assert f["simd"] == ["avx2", "fma", "avx512f", "avx512vl"]
    assert not S.cpu_facts("flags : sse2 avx2\n")["avx512f"]


def test_cmake_cache_finds_the_build_flags(tmp_path):
    b = tmp_path / "build-avx2"
    b.mkdir()
    (b / "CMakeCache.txt").write_text("CMAKE_CXX_FLAGS:STRING=-mno-avx512f\nCMAKE_BUILD_TYPE:STRING=Release\n"
                                      "GRANWAVE_NATIVE:BOOL=ON\nOTHER:STRING=x\n")
    c = S.cmake_cache(str(b / "granwave"))
    assert c["CMAKE_CXX_FLAGS"] == "-mno-avx512f" and c["GRANWAVE_NATIVE"] == "ON" and "OTHER" not in c
    assert S.cmake_cache(str(tmp_path / "nowhere" / "deeper" / "granwave")) == {}


# ---------------------------------------------------------------- cases and decks
def test_case_texts():
    long = S.case_text("long")
    assert "cells = [4, 4, 20000]" in long and "t_end = 4e-5" in long and 'name = "bench_long"' in long
    assert "interval = 1e-6" in long and "dt = 2e-7" in long          # output every 5 steps, as the others
    fr = S.case_text("friction")
    assert "kt = 100000" in fr and 'lever_arm = "contact_point"' in fr and "mu_static = 0.5" in fr
    assert "kt = 0.0" in S.case_text("frictionless")
    # the fair row against LAMMPS: its gran/hooke/history arm is the radius; LIGGGHTS (contact point) not run
    radius = S.case_text("friction_radius")
    assert 'lever_arm = "radius"' in radius and 'lever_arm = "contact_point"' not in radius
    changed = [(a, b) for a, b in zip(fr.splitlines(), radius.splitlines()) if a != b]
    assert changed == [('name = "bench_friction"', 'name = "bench_friction_radius"'),
                       ('lever_arm = "contact_point"', 'lever_arm = "radius"')]
    assert S.CASE_CODES["friction_radius"] == ("granwave", "lammps")


def test_lammps_deck_frictionless(tmp_path, cases_dir):
    case, system, _ = _system(tmp_path, cases_dir, "crystal_small.toml")
    f = S.render_lammps(case, system, str(tmp_path))
    deck = (tmp_path / "in.case").read_text()
    assert f["nsteps"] == 1000 and f["every"] == 5 and f["n"] == 640
    assert "pair_style      gran/hooke 100000.0 0.0 0.0 0.0 0.5 0" in deck      # no history, no dashpots
    assert "fix             integr free nve\n" in deck                          # no torque: no rotation
    assert "newton          on" in deck and "comm_modify     vel yes" in deck
    assert "neighbor        0.0002 bin" in deck                                 # 0.2 a: the touching shell
    assert "neigh_modify    delay 0 every 10 check yes exclude type 2 2 exclude type 2 3 exclude type 3 3" in deck
    assert "compute         sa all stress/atom NULL pair" in deck
    assert "fix             layers all ave/chunk 5 1 5 layers c_sa[3] c_sa[5] vz vx c_dsp[3] c_dsp[1]" in deck
    assert "displace_atoms  source move 0.0 0.0 2.0000000000000002e-07 units box" in deck  # 1e-4 d
    assert "run             1000" in deck and "$" not in deck
    # the bins are centred on the layers: layer 0 sits at origin + l0/2
    lay = T.crystal_layout(system)
    origin = float(deck.split("bin/1d z ")[1].split()[0])
    z0 = np.min(np.asarray(system["position"])[lay["layer"] == 0, 2])
    assert math.isclose(origin + 0.5 * lay["l0"], z0, rel_tol=1e-12)


def test_lammps_and_liggghts_decks_with_friction(tmp_path, cases_dir):
    case, system, _ = _system(tmp_path, cases_dir, "crystal_small.toml")
    case["contact"].update(kt=1e5, mu_static=0.001, mu_dynamic=0.001, lever_arm="contact_point")
    S.render_lammps(case, system, str(tmp_path))
    deck = (tmp_path / "in.case").read_text()
    c = T.contact_params(case)
    assert "pair_style      gran/hooke/history 100000.0 %r 0.0 0.0 %r 0" % (float(c["kt"]), float(c["mu_static"])) in deck
    assert "fix             integr free nve/sphere" in deck
    S.render_liggghts(case, system, str(tmp_path))
    lig = (tmp_path / "in.case").read_text()
    assert "tangential history absolute_damping on limitForce off" in lig
    assert "newton          off" in lig          # LIGGGHTS refuses shear history with newton on
    assert "fix             integr free nve/sphere" in lig
    assert "coefficientFriction peratomtypepair 3 " + " ".join([repr(float(c["mu_static"]))] * 9) in lig
    assert "dump" not in lig and "pair/gran/local" not in lig          # no per-pair dumps
    assert "fix             layers all ave/spatial 5 1 5 z " in lig and "$" not in lig


def test_rolling_decks(tmp_path, cases_dir):
    """The rolling cases: LAMMPS' pair granular with sds (rolling), LIGGGHTS' luding deck (rolling_luding,
    its conventions in the granwave case); each refuses what it cannot express."""
    luding = S.case_text("rolling_luding")
    for line in ('lever_arm = "contact_point"', 'rolling_lever = "radii"', 'rolling_history = "fixed"', "ko = 5e4"):
        assert line in luding, line
    assert "\nmu_r =" not in luding and "\nmu_o =" not in luding
    assert S.CASE_CODES["rolling"] == ("granwave", "lammps") and S.CASE_CODES["rolling_luding"] == ("granwave", "liggghts")
    for name, codes in (("rolling_s", ("granwave", "lammps")), ("rolling_luding_s", ("granwave", "liggghts"))):
        text = S.case_text(name)   # the same springs with seed 002's S step
        assert S.CASE_CODES[name] == codes and 'mode = "S"' in text and "t_end = 1.7e-3" in text
        assert ('rolling_history = "fixed"' in text) == (name == "rolling_luding_s")
    case, system, _ = _system(tmp_path, cases_dir, "crystal_small.toml")
    case["contact"].update(kt=1e5, mu_static=0.5, mu_dynamic=0.5, lever_arm="contact_point", kr=5e4, ko=5e4)
    S.render_liggghts(case, system, str(tmp_path))
    lig = (tmp_path / "in.case").read_text()
    assert "pair_style      gran model luding tangential tan_luding rolling_friction luding torsion on limitForce off" in lig
    assert "coeffRollingStiffness peratomtypepair 3 " + " ".join(["0.5"] * 9) in lig
    assert "dump" not in lig and "pair/gran/local" not in lig and "$" not in lig
    S.render_lammps(case, system, str(tmp_path))
    deck = (tmp_path / "in.case").read_text()
    assert "rolling sds" in deck and "twisting sds" in deck
    case["contact"].update(mu_r=0.1)   # LIGGGHTS' lumped torsion has one limit for both: refused
    with pytest.raises(S.BenchError, match="torsion on"):
        S.render_liggghts(case, system, str(tmp_path / "x"))


def test_hertz_decks(tmp_path, cases_dir):
    """Issue #14's row: LAMMPS pair granular hertz/material + mindlin, LIGGGHTS model hertz with
    tangential history, from the case's E and nu; damped or force-history cases are refused."""
    text = S.case_text("hertz")
    assert 'law = "hertz_mindlin"' in text and "dt = 1.7e-7" in text and "dt_over_tc" not in text
    assert "t_end = 1.02e-3" in text and "interval = 8.5e-7" in text      # 6000 steps, output every 5
    case, system, _ = _system(tmp_path, cases_dir, "crystal_small.toml")
    case["contact"] = dict(law="hertz_mindlin", youngs_modulus=63e9, poisson_ratio=0.23, mu_static=0.5,
                           mu_dynamic=0.5)
    S.render_lammps(case, system, str(tmp_path))
    deck = (tmp_path / "in.case").read_text()
    assert "pair_style      granular\n" in deck
    assert "pair_coeff      * * hertz/material 63000000000.0 0.0 0.23 tangential mindlin NULL 0.0 0.5\n" in deck
    assert "fix             integr free nve/sphere" in deck and "$" not in deck
    S.render_liggghts(case, system, str(tmp_path))
    lig = (tmp_path / "in.case").read_text()
    assert "hard_particles  yes" in lig and "pair_style      gran model hertz tangential history\n" in lig
    assert "youngsModulus peratomtype 63000000000.0 63000000000.0 63000000000.0" in lig
    assert "coefficientRestitution peratomtypepair 3 " + " ".join(["1.0"] * 9) in lig
    assert "newton          off" in lig and "kn peratomtypepair" not in lig and "$" not in lig
    for bad in (dict(damping_ratio=0.1), dict(tangential_history="force"), dict(tangential="none")):
        c = dict(case, contact=dict(case["contact"], **bad))
        with pytest.raises(S.BenchError):
            S.render_lammps(c, system, str(tmp_path))


def test_liggghts_deck_frictionless(tmp_path, cases_dir):
    case, system, _ = _system(tmp_path, cases_dir, "crystal_small.toml")
    S.render_liggghts(case, system, str(tmp_path))
    lig = (tmp_path / "in.case").read_text()
    assert "tangential no_history" in lig and "newton          on" in lig
    assert "fix             integr free nve\n" in lig
    assert "compute         sa all stress/atom pair" in lig


def test_data_file(tmp_path, cases_dir):
    case, system, _ = _system(tmp_path, cases_dir, "crystal_small.toml")
    S.render_lammps(case, system, str(tmp_path))
    text = (tmp_path / "data.system").read_text()
    assert "640 atoms" in text and "3 atom types" in text
    rows = np.loadtxt(text.split("Atoms\n\n")[1].splitlines())
    lay = T.crystal_layout(system)
    fixed = np.asarray(system["fixed"]).astype(bool)
    types = rows[:, 1].astype(int)
    assert np.all(types[~fixed] == 1)
    assert np.all(types[fixed & (lay["layer"] < 2)] == 3) and np.all(types[fixed & (lay["layer"] >= 2)] == 2)
    # mass as density: LAMMPS' 4/3 pi r^3 rho gives the system's mass back to rounding
    m = 4.0 / 3.0 * math.pi * (rows[:, 2] / 2) ** 3 * rows[:, 3]
    assert np.allclose(m, system["mass"], rtol=1e-15, atol=0)
    assert np.all(rows[:, 4] >= 0) and np.all(rows[:, 4] < lay["box_x"])


def test_unrenderable_cases_are_refused(tmp_path, cases_dir):
    for name in ("crystal_small_damped.toml", "crystal_small_stickslip.toml"):
        case, system, _ = _system(tmp_path, cases_dir, name)
        with pytest.raises(S.BenchError, match="cannot be rendered"):
            S.render_lammps(case, system, str(tmp_path))


# ---------------------------------------------------------------- layer output -> trace
def _layer_file(path, fmt_header, steps, coords, counts, values):
    with open(path, "w") as f:
        f.write("# header\n# %s\n# Chunk Coord1 Ncount ...\n" % fmt_header)
        for s, vals in zip(steps, values):
            f.write("%d %d %d\n" % (s, len(coords), int(sum(counts))))
            for k, (z, c) in enumerate(zip(coords, counts)):
                f.write("  %d %.10g %d %s\n" % (k + 1, z, c, " ".join("%.10g" % x for x in vals[k])))


def test_layer_file_to_trace(tmp_path, cases_dir):
    """Synthetic ave/chunk output with empty bins below and above the crystal: the layers come out in
    order, with the stress in granwave's convention (compression positive) and the means as they are."""
    case, system, sp = _system(tmp_path, cases_dir, "crystal_small.toml")
    cp = tmp_path / "case.toml"
    cp.write_text(open(os.path.join(cases_dir, "crystal_small.toml")).read())
    lay = T.crystal_layout(system)
    nl, l0 = lay["nlayers"], lay["l0"]
    z0 = float(np.min(np.asarray(system["position"])[lay["layer"] == 0, 2]))
    coords = z0 + l0 * np.arange(-2, nl + 2)              # two empty bins at each end
    counts = [0, 0] + [16] * nl + [0, 0]
    steps = [0, 5, 10]
    vals = []
    for q, _ in enumerate(steps):
        v = np.zeros((len(coords), 6))
        for k in range(nl):
            v[k + 2] = [-(k + 1) * 1e-4 * (q + 1), 0.0, 1e-3 * k, 0.0, 2e-7 * q, 0.0]
        vals.append(v)
    lf = tmp_path / "layers.txt"
    _layer_file(lf, "Timestep Number-of-chunks Total-count", steps, coords, counts, vals)
    out = tmp_path / "t.h5"
    S.layers_to_trace(str(lf), str(cp), sp, str(out), "lammps", "LAMMPS test")
    tr = T.read_trace(str(out))
    vol = lay["box_x"] * lay["box_y"] * l0
    assert np.allclose(tr["time"], np.array(steps) * 2e-7)
    expect = np.array([[16 * (k + 1) * 1e-4 * (q + 1) / vol for k in range(nl)] for q in range(3)])
    assert np.allclose(tr["/crystal/layer_stress_zz"], expect, rtol=1e-9, atol=0)
    assert np.allclose(tr["/crystal/layer_velocity_z"][1], 1e-3 * np.arange(nl))
    assert np.allclose(tr["/crystal/layer_displacement_z"][2], 4e-7)
    assert tr["attrs"]["code"] == "lammps"
    # a file whose bins miss a layer is refused, not misread
    bad = tmp_path / "bad.txt"
    _layer_file(bad, "Timestep Number-of-bins", steps, coords[:-4], counts[:-4], [v[:-4] for v in vals])
    with pytest.raises(ValueError, match="one to one"):
        S.layers_to_trace(str(bad), str(cp), sp, str(tmp_path / "b.h5"), "liggghts", "x")


def test_truncated_layer_file_is_an_error(tmp_path):
    p = tmp_path / "l.txt"
    p.write_text("# x\n0 3\n 1 0.0 16 1 2\n 2 1.0 16 1 2\n")
    with pytest.raises(ValueError, match="2 of 3 rows"):
        S.read_layer_file(str(p))


# ---------------------------------------------------------------- command line
def _fake_granwave(tmp_path):
    p = tmp_path / "granwave"
    p.write_text("#!/bin/sh\necho granwave fake\n")
    p.chmod(0o755)
    return str(p)


def test_missing_code_exits_2_naming_it(tmp_path, capsys):
    gw = _fake_granwave(tmp_path)
    assert S.main(["--granwave", gw, "--lammps", "no-such-lmp-binary", "--codes", "granwave,lammps"]) == 2
    err = capsys.readouterr().err
    assert "LAMMPS not found (no-such-lmp-binary)" in err and "--codes" in err
    assert S.main(["--granwave", str(tmp_path / "missing"), "--codes", "granwave"]) == 2
    assert "granwave binary not found" in capsys.readouterr().err
    assert S.main(["--granwave", gw, "--cases", "nonsense"]) == 2
    assert "unknown case 'nonsense'" in capsys.readouterr().err
    assert S.main(["--granwave", gw, "--codes", "lammps"]) == 2
    assert S.main(["--granwave", gw, "--reps", "0", "--codes", "granwave"]) == 2


def test_table_and_ratios_from_runs():
    runners = [S.Runner("granwave", "granwave", "gw", "granwave"), S.Runner("lammps", "lammps", "lmp", "LAMMPS")]
    run = lambda w, c: dict(wall=w, cpu=c, maxrss_kb=32000)  # noqa: E731
    res = dict(case="frictionless", particles=3200, steps=6000,
               runs={"granwave": [run(2.0, 1.0), run(4.0, 2.0), run(2.2, 1.1)],
                     "lammps": [run(8.0, 4.0), run(16.0, 8.0), run(9.9, 5.5)]},
               sanity={"granwave": dict(v_half=218.694, z_over_l0=[10, 150]),
                       "lammps": dict(v_half=218.694, z_over_l0=[10, 150], stress_dev=4.5e-9)})
    sm = S.summarize(res, runners)
    assert sm["times"]["granwave"]["wall"] == 2.2 and sm["times"]["lammps"]["cpu"] == 5.5
    assert sm["ratios"]["lammps/granwave"]["wall"] == 4.0           # 4, 4, 4.5
    assert sm["ratios"]["lammps/granwave"]["cpu"] == 4.0            # 4, 4, 5
    t = S.table([res], runners, ["granwave", "lammps"])
    assert "| frictionless | 3200 x 6000 | granwave | 2.20 / 1.10 | 9.90 / 5.50 | 4.00x (4.00x) | not run (--codes) | - |" in t
    s = S.sanity_table([res], runners)
    assert "218.694 (z/l0 10..150)" in s and "4.5e-09" in s
    assert "31; 10.24" in S.memory_table([res], runners)            # 32000 KiB over 3200 particles
    # a case that runs without LIGGGHTS (other physics): its columns say so
    lig = S.Runner("liggghts", "liggghts", "liggghts", "LIGGGHTS")
    res_r = dict(res, case="friction_radius")
    t = S.table([res_r], runners + [lig], ["granwave", "lammps", "liggghts"])
    assert "| friction_radius | 3200 x 6000 | granwave | 2.20 / 1.10 | 9.90 / 5.50 | 4.00x (4.00x) | " \
           "not run (other physics) | - |" in t
    assert "not run" in S.sanity_table([res_r], runners + [lig]) and "not run" in S.memory_table([res_r], runners + [lig])


# ---------------------------------------------------------------- real codes (short)
@pytest.mark.realcodes
def test_real_side_by_side_small(tmp_path, capsys):
    gw = os.path.join(REPO, "build", "granwave")
    if not os.path.exists(gw) or not shutil.which("lmp") or not shutil.which("liggghts"):
        pytest.skip("needs build/granwave, lmp and liggghts")
    js = tmp_path / "r.json"
    assert S.main(["--granwave", gw, "--cases", "small", "--reps", "1", "--json", str(js),
                   "--workdir", str(tmp_path / "w")]) == 0
    doc = json.loads(js.read_text())
    c = doc["cases"][0]
    assert c["particles"] == 640 and c["steps"] == 1300
    san = c["sanity"]
    v = san["granwave"]["v_half"]
    assert v is not None
    for code in ("lammps", "liggghts"):
        assert abs(san[code]["v_half"] - v) < 1e-3 * v, (code, san[code])
        assert san[code]["stress_dev"] < 1e-4              # LIGGGHTS writes 6 digits ...
        # ... and the difference is what the printed digits allow, plus at most 1e-7 of physics
        assert 0 < san[code]["stress_resolution"] and \
            san[code]["stress_dev"] <= san[code]["stress_resolution"] + 1e-7, (code, san[code])
        assert c["runs"][code][0]["neighbor_builds"] == 0
    r = c["summary"]["ratios"]
    assert r["lammps/granwave"]["wall"] > 0 and r["liggghts/granwave"]["cpu"] > 0
    assert "| small | 640 x 1300 |" in capsys.readouterr().out


@pytest.mark.realcodes
def test_real_side_by_side_small_s_wave_is_checked_on_the_layer_velocity(tmp_path):
    """An S case (LIGGGHTS' luding springs, 640 particles): the per-layer deck renders the S step, and the
    physics check measures and compares the layer velocity v_x (the layer file's stress/atom xz is not
    sigma_zx): LIGGGHTS is granwave to the digits its layer file prints."""
    gw = os.path.join(REPO, "build", "granwave")
    if not os.path.exists(gw) or not shutil.which("liggghts"):
        pytest.skip("needs build/granwave and liggghts")
    js = tmp_path / "r.json"
    assert S.main(["--granwave", gw, "--cases", "small_rolling_luding_s", "--codes", "granwave,liggghts", "--reps", "1",
                   "--json", str(js), "--workdir", str(tmp_path / "w")]) == 0
    c = json.loads(js.read_text())["cases"][0]
    san = c["sanity"]
    assert san["granwave"]["field"] == san["liggghts"]["field"] == "v_x"
    v = san["granwave"]["v_half"]
    assert v is not None and abs(san["liggghts"]["v_half"] - v) < 1e-6 * v, san
    assert 0 < san["liggghts"]["stress_resolution"] and \
        san["liggghts"]["stress_dev"] <= san["liggghts"]["stress_resolution"] + 1e-7, san


# ---------------------------------------------------------------- the disordered packing case (issue #41 item 3)
def _packing_case(tmp_path, name="disordered"):
    """The case text of a packing case (its packing file need not exist to render decks) and its dict."""
    p = tmp_path / ("%s.toml" % name)
    p.write_text(S.case_text(name, str(tmp_path / "packing.dump")))
    return str(p), T.load_case(str(p))[0]


def _packing_system(tmp_path):
    """A synthetic packing-file system (SCHEMA.md §2, generator "file"): 7 polydisperse particles in 5 bins of
    1 mm, two in the source slab, one in the top slab, one across the periodic x boundary from another."""
    import h5py
    pos = np.array([[0.2e-3, 0.5e-3, 0.4e-3], [1.2e-3, 0.5e-3, 0.5e-3], [0.5e-3, 0.5e-3, 1.4e-3],
                    [1.5e-3, 0.6e-3, 2.3e-3], [1.95e-3, 0.5e-3, 3.1e-3], [0.04e-3, 0.5e-3, 3.2e-3],
                    [1.0e-3, 1.0e-3, 4.6e-3]])
    r = np.array([0.45e-3, 0.5e-3, 0.55e-3, 0.5e-3, 0.48e-3, 0.52e-3, 0.5e-3])
    role = np.array([T.SOURCE, T.SOURCE, T.FREE, T.FREE, T.FREE, T.FREE, T.TOP])
    attrs = dict(generator="file", box_x=2e-3, box_y=2e-3, bin_origin=0.0, bin_width=1e-3, l0=1e-3, layers=5,
                 source_thickness=1e-3, dt=3e-8, d=1e-3, fixed_layers=0)
    data = dict(position=pos, radius=r, mass=2500 * 4 / 3 * np.pi * r ** 3, fixed=(role != T.FREE).astype(np.int8),
                role=role.astype(np.int8), layer=np.floor(pos[:, 2] / 1e-3).astype(np.int32),
                velocity=np.zeros((7, 3)))
    sp = str(tmp_path / "system.h5")
    with h5py.File(sp, "w") as f:
        g = f.create_group("system")
        for k, v in attrs.items():
            g.attrs[k] = v
        for k, v in data.items():
            g.create_dataset(k, data=v)
    return T.read_system(sp), sp


def test_disordered_case_texts(tmp_path):
    text = S.case_text("disordered", "/x/packing.dump")
    assert 'file = "/x/packing.dump"' in text and 'lattice = "file"' in text and 'law = "hertz_mindlin"' in text
    assert 'lever_arm = "radius"' in text and "mu_static = 0.5" in text and 'name = "bench_disordered"' in text
    assert 'lever_arm = "contact_point"' in S.case_text("disordered_cp", "/x/p.dump")
    assert "t_end = 6e-5" in S.case_text("disordered_small", "/x/p.dump")
    with pytest.raises(S.BenchError, match="packing file"):
        S.case_text("disordered")
    # each arm's row runs only the code with that arm (LAMMPS gran/hertz/history: radius; LIGGGHTS: contact point)
    assert S.CASE_CODES["disordered"] == ("granwave", "lammps") and S.CASE_CODES["disordered_cp"] == ("granwave", "liggghts")
    from sidebyside import packing as P
    assert "\nvtk_every = 3\n" in P.count_case_text(text, 3)
    assert P.snapshot_every(3032, 30) == (10, 300)


def test_disordered_lammps_deck_has_granwaves_list_rule_and_bins(tmp_path):
    _, case = _packing_case(tmp_path)
    system, _ = _packing_system(tmp_path)
    wd = tmp_path / "l"
    wd.mkdir()
    f = S.render_lammps(case, system, str(wd), packing=True)
    deck = (wd / f["deck"]).read_text()
    skin = 0.1 * np.mean(system["radius"])                       # granwave's list_skin
    assert "neighbor        %r bin" % skin in deck
    assert "neigh_modify    delay 0 every 1 check yes exclude type 2 2 exclude type 2 3 exclude type 3 3" in deck
    from xclib import hertz_mindlin as HM
    kn, kt = 4.0 / 3.0 * HM.e_star(63e9, 0.23), 8.0 * HM.g_star(63e9, 0.23)
    assert "pair_style      gran/hertz/history %r %r 0.0 0.0 0.5 0" % (kn, kt) in deck
    assert "fix             bins all property/atom mol" in deck and "read_data       data.system fix bins NULL Molecules" in deck
    assert "chunk/atom molecule nchunk once ids once compress no" in deck and "dump " not in deck
    assert "displace_atoms  source move 0.0 0.0 %r units box" % (1e-4 * 1e-3) in deck and "nve/sphere" in deck
    data = (wd / "data.system").read_text()
    atoms = data.split("Atoms")[1].split("Molecules")[0].split("\n")
    rows = [ln.split() for ln in atoms if ln.strip()]
    assert [int(r[1]) for r in rows] == [3, 3, 1, 1, 1, 1, 2]      # source, free, top
    mol = [ln.split() for ln in data.split("Molecules")[1].split("\n") if ln.strip()]
    assert [int(m[1]) for m in mol] == [int(b) + 1 for b in system["layer"]]   # the system's bins, not current z
    snap = tmp_path / "s"
    snap.mkdir()
    S.render_lammps(case, system, str(snap), packing=True, snapshots=30)
    d2 = (snap / "in.case").read_text()
    assert "dump            snap all custom 30 snap.txt id x y z" in d2 and '%.17g' in d2
    # the contact point is not LAMMPS' gran/hertz/history arm: refused, not run as something else
    _, cp = _packing_case(tmp_path, "disordered_cp")
    with pytest.raises(S.BenchError, match="lever_arm"):
        S.render_lammps(cp, system, str(tmp_path), packing=True)


def test_disordered_liggghts_deck(tmp_path):
    _, case = _packing_case(tmp_path, "disordered_cp")
    system, _ = _packing_system(tmp_path)
    f = S.render_liggghts(case, system, str(tmp_path), packing=True, snapshots=30)
    deck = (tmp_path / f["deck"]).read_text()
    assert "neighbor        %r bin" % (0.1 * np.mean(system["radius"])) in deck
    assert "neigh_modify    delay 0 every 1 check yes" in deck and "newton          off" in deck
    assert "gran model hertz tangential history" in deck and "hard_particles  yes" in deck
    assert "fix             layers all ave/spatial 33 1 33 z 0.0 0.001 c_sa[3]" in deck   # the system's bins, current z
    assert 'dump_modify     snap sort id format "%d %.17g %.17g %.17g"' in deck
    assert "Molecules" not in (tmp_path / "data.system").read_text()
    _, rad = _packing_case(tmp_path, "disordered")
    with pytest.raises(S.BenchError, match="contact_point"):
        S.render_liggghts(rad, system, str(tmp_path), packing=True)


def test_packing_layer_files_to_trace(tmp_path):
    """LAMMPS' chunks by molecule (rows "chunk count v...", the top bin missing) and LIGGGHTS' z-bins over the
    box (rows "bin coord count v...", bins below and above the system's): both land on the system's bins."""
    cp, _ = _packing_case(tmp_path)
    system, sp = _packing_system(tmp_path)
    vol = 2e-3 * 2e-3 * 1e-3
    steps = [0, 10]
    with open(tmp_path / "lmp.txt", "w") as f:
        f.write("# a\n# Timestep Number-of-chunks Total-count\n# Chunk Ncount c_sa[3] ...\n")
        for s in steps:
            f.write("%d 4 6\n" % s)
            for k in range(4):
                f.write("  %d 2 %g 0 %g 0 0 0\n" % (k + 1, -(k + 1) * 1e-4 * (s + 1), 1e-3 * k))
    out = tmp_path / "l.h5"
    S.packing_layers_to_trace(str(tmp_path / "lmp.txt"), cp, sp, str(out), "lammps", "test")
    tr = T.read_trace(str(out))
    szz = tr["/crystal/layer_stress_zz"]
    assert szz.shape == (2, 5) and np.allclose(szz[1, :4], [2 * (k + 1) * 1e-4 * 11 / vol for k in range(4)])
    assert szz[1, 4] == 0 and np.allclose(tr["/crystal/layer_velocity_z"][0, :4], 1e-3 * np.arange(4))
    with open(tmp_path / "lig.txt", "w") as f:
        f.write("# a\n# Timestep Number-of-bins\n# Bin Coord Ncount ...\n")
        for s in steps:
            f.write("%d 7\n" % s)
            for k in range(-1, 6):
                f.write("  %d %g %d %g 0 %g 0 0 0\n" % (k + 2, (k + 0.5) * 1e-3, 1, -1e-4 * (k + 2), 2e-3 * k))
    S.packing_layers_to_trace(str(tmp_path / "lig.txt"), cp, sp, str(out), "liggghts", "test")
    tr = T.read_trace(str(out))
    assert np.allclose(tr["/crystal/layer_stress_zz"][0], [1e-4 * (k + 2) / vol for k in range(5)])
    assert np.allclose(tr["/crystal/layer_velocity_z"][1], 2e-3 * np.arange(5))


def test_contact_counts_across_the_periodic_box(tmp_path):
    from sidebyside import packing as P
    system, _ = _packing_system(tmp_path)
    pos = np.asarray(system["position"], float)
    # 4-5 touch across x = 0 (1.95 mm and 0.04 mm: 0.09 mm apart through the boundary); 0-1 are both source
    # (fixed pairs left out); 2-3 are 1.28 mm apart: apart, until 3 moves down by 0.3 mm
    start = P.contact_set(pos, system["radius"], np.asarray(system["fixed"], bool), 2e-3, 2e-3)
    assert (4, 5) in start and (0, 1) not in start and (2, 3) not in start
    moved = pos.copy()
    moved[3, 2] -= 0.3e-3
    c = P.count_transitions([(0, pos), (5, moved), (10, pos)], system)
    assert c["opened"] == c["closed"] >= 1 and c["opened_net"] == c["closed_net"] == 0
    assert c["contacts_start"] == c["contacts_end"] == len(start) and c["steps"] == [0, 5, 10]
    snap = tmp_path / "snap.txt"
    with open(snap, "w") as f:
        for s, p in ((0, pos), (5, moved)):
            f.write("ITEM: TIMESTEP\n%d\nITEM: NUMBER OF ATOMS\n7\nITEM: BOX BOUNDS pp pp ff\n0 1\n0 1\n0 1\n"
                    "ITEM: ATOMS id x y z\n" % s)
            for k in (6, 5, 4, 3, 2, 1, 0):           # any order: rows by atom ID
                f.write("%d %.17g %.17g %.17g\n" % (k + 1, p[k, 0], p[k, 1], p[k, 2]))
    frames = P.read_snap(str(snap), 7)
    assert [s for s, _ in frames] == [0, 5] and np.array_equal(frames[1][1], moved)


@pytest.mark.realcodes
def test_real_side_by_side_disordered_small(tmp_path):
    """The packing decks on the committed 3060-particle column, one repetition (about 15 s of CPU): LAMMPS'
    gran/hertz/history runs granwave's radius arm to round-off, LIGGGHTS the contact point to its 6 digits."""
    gw = os.path.join(REPO, "build", "granwave")
    if not os.path.exists(gw) or not shutil.which("lmp") or not shutil.which("liggghts"):
        pytest.skip("needs build/granwave, lmp and liggghts")
    js = tmp_path / "r.json"
    assert S.main(["--granwave", gw, "--cases", "disordered_small,disordered_small_cp", "--reps", "1", "--json",
                   str(js), "--workdir", str(tmp_path / "w")]) == 0
    doc = json.loads(js.read_text())
    for c, code, bound in zip(doc["cases"], ("lammps", "liggghts"), (1e-7, 1e-5)):
        san = c["sanity"]
        assert abs(san[code]["v_half"] - san["granwave"]["v_half"]) < 1e-4 * san["granwave"]["v_half"]
        assert san[code]["vz_dev"] < bound, (code, san[code])
        assert c["runs"][code][0]["neighbor_builds"] == 0 and c["runs"]["granwave"][0]["contact_list_builds"] == 1
        n = c["contacts"]
        assert n[code]["contacts_start"] == n["granwave"]["contacts_start"] > 9000
        assert n[code]["opened"] == n["granwave"]["opened"] and n[code]["closed"] == n["granwave"]["closed"]
