"""The LAMMPS deck renderer and writer alignments (no LAMMPS needed)."""
import math
import os
import sys

import numpy as np
import pytest

from xclib import dumps as D
from xclib import sysbuild
from xclib import traces as T

HERE = os.path.dirname(os.path.abspath(__file__))
sys.path.insert(0, os.path.join(os.path.dirname(os.path.dirname(HERE)), "lammps_inputs"))
import lammps_case as LM  # noqa: E402


def _render(tmp_path, cases_dir, name, edit=None):
    text = open(os.path.join(cases_dir, name)).read()
    if edit:
        text = edit(text)
    cp = tmp_path / name
    cp.write_text(text)
    case, _ = T.load_case(str(cp))
    sp = str(tmp_path / "sys.h5")
    sysbuild.build(case, sp)
    work = tmp_path / "w"
    work.mkdir()
    facts = LM.render(case, T.read_system(sp), str(work))
    return facts, (work / "in.case").read_text(), (work / "data.system").read_text()


def test_chain_deck_has_eq13_per_material_pair_and_the_walls_own_constant(tmp_path, cases_dir):
    facts, deck, data = _render(tmp_path, cases_dir, "chain_small.toml")
    assert facts["nsteps"] == 25000 and facts["every"] == 50
    estar = LM.e_star(193e9, 0.30, 72.4e9, 0.33)
    # hertz/material mixes unlike types wrongly in this LAMMPS release: each pair gets hertz k = 4/3 E*
    assert "pair_coeff      1 2 hertz %r 0 tangential linear_nohistory 0 0" % (4.0 / 3.0 * estar) in deck
    assert "pair_coeff      1 1 hertz %r " % (4.0 / 3.0 * LM.e_star(193e9, 0.3, 193e9, 0.3)) in deck
    kw = 4.0 / 3.0 * LM.e_star(72.4e9, 0.33, 115e9, 0.31)          # last bead (aluminium) on the brass wall
    assert "wall/gran granular hertz %r 0 tangential linear_nohistory 0 0 xplane NULL" % kw in deck
    assert "contacts" in deck and "f_wall[2]" in deck
    assert "set             atom 1 vx 0.443 vy 0.0 vz 0.0" in deck
    assert "41 atoms" in data and "2 atom types" in data and "Atoms # sphere" in data
    assert "fix             integr beads nve/sphere" in deck and "group           beads id 1:41" in deck


def test_chain_sphere_wall(tmp_path, cases_dir, monkeypatch):
    monkeypatch.setattr(LM, "WALL", "sphere:1000")
    facts, deck, data = _render(tmp_path, cases_dir, "chain_small.toml")
    assert "wall/gran" not in deck and "42 atoms" in data and "3 atom types" in data
    assert facts["wall_atom"] == 42 and facts["wall"] == "sphere R = 1000 m"
    # bead materials on the wall sphere: the true E* of the pair
    kw = 4.0 / 3.0 * LM.e_star(72.4e9, 0.33, 115e9, 0.31)
    assert "pair_coeff      2 3 hertz %r " % kw in deck


def test_crystal_frictionless_uses_pair_granular_with_an_absolute_dashpot(tmp_path, cases_dir):
    facts, deck, data = _render(tmp_path, cases_dir, "crystal_small_damped_kt0.toml")
    assert "pair_coeff      * * hooke 100000.0 0.1 tangential linear_nohistory 0 0 damping velocity limit_damping" in deck
    assert facts["conventions"]["normal_tension"] == "clip" and not facts["tangential"]
    assert "dump            dat all custom 5 dump.atoms id x y z vx vy vz fx fy fz" in deck   # forces: the dashpot alignment
    assert "displace_atoms  source move 0.0 0.0 2.0000000000000002e-07 units box" in deck
    assert deck.index("displace_atoms") < deck.index("fix             integr free") < deck.index("run ")
    assert "exclude type 2 2 exclude type 2 3 exclude type 3 3" in deck and "640 atoms" in data
    assert "set             atom 1*640 mass" in deck        # one line: equal masses
    (tmp_path / "x").mkdir()
    facts, deck, _ = _render(tmp_path / "x", cases_dir, "crystal_small.toml")
    assert "damping velocity\n" in deck and "limit_damping" not in deck


def test_crystal_friction_uses_gran_hooke_history_and_says_its_conventions(tmp_path, cases_dir):
    facts, deck, _ = _render(tmp_path, cases_dir, "crystal_small_damped.toml")
    m = 2000 * 4.0 / 3.0 * math.pi * 1e-9
    line = [ln for ln in deck.splitlines() if ln.startswith("pair_style      gran/hooke/history")][0].split()
    assert float(line[2]) == 1e5 and float(line[3]) == 1e5 and float(line[5]) == 0.0 and line[7] == "0"
    assert float(line[4]) == pytest.approx(0.1 / (m / 2), rel=1e-12)        # gamma_n per unit effective mass
    assert facts["conventions"] == dict(lever_arm="radius", normal_tension="allow", coulomb_normal="magnitude")
    assert "compute         cpl all pair/local fx fy fz p1 p2 p3 cutoff radius" in deck


def test_cases_lammps_cannot_run_exactly_are_refused(tmp_path, cases_dir):
    with pytest.raises(LM.Unsupported, match="gamma_t"):
        _render(tmp_path, cases_dir, "crystal_small_damped.toml", lambda t: t.replace("gamma_t = 0.0", "gamma_t = 0.05"))
    c = dict(kn=1e5, kt=1e5, gamma_n=0.1, gamma_t=0.0, mu_static=0.5, normal_tension="clip")
    with pytest.raises(LM.Unsupported, match="effective mass"):      # polydisperse, damped, friction
        LM.crystal_style(c, np.array([1.0, 1.1]))
    assert LM.crystal_style(dict(c, gamma_n=0.0), np.array([1.0, 1.1]))["style"] == "gran/hooke/history"


def test_mass_lines_are_runs_of_equal_masses():
    assert LM.mass_lines(np.array([1.0, 1.0, 2.0, 1.0])) == ("set             atom 1*2 mass 1.0\n"
                                                             "set             atom 3 mass 2.0\n"
                                                             "set             atom 4 mass 1.0")


def test_tangential_force_of_the_step_from_the_dump():
    """gran/hooke/history's single() cuts -kt xi at mu |f_n(dump)|; the step cut it at mu |f_n(step)|."""
    mu = 0.5
    fs = np.array([[0.3, 0.0, 0.0],     # not cut at dump time: the step's force
                   [0.5, 0.0, 0.0],     # cut at dump (|f_n(dump)| = 1), step |f_n| = 0.8: slid, 0.4
                   [0.0, 0.5, 0.0]])    # cut at dump, step |f_n| = 1.2 > 1: taken as sliding (0.6), flagged
    fn_dump = np.array([1.0, 1.0, 1.0])
    fn_step = np.array([0.9, 0.8, 1.2])
    out, assumed = LM.tangential_at_step(fs, fn_dump, fn_step, mu)
    assert out[0].tolist() == [0.3, 0.0, 0.0]
    assert out[1] == pytest.approx([0.4, 0.0, 0.0], rel=1e-15)
    assert out[2] == pytest.approx([0.0, 0.6, 0.0], rel=1e-15) and assumed.tolist() == [False, False, True]


def test_atom_forces_add_each_contact_to_both_atoms():
    f = LM.atom_forces(3, np.array([0, 1]), np.array([1, 2]), np.array([[1.0, 0, 0], [0, 2.0, 0]]))
    assert f.tolist() == [[1.0, 0, 0], [-1.0, 2.0, 0], [0, -2.0, 0]]


def test_lockstep_reads_both_dumps_a_frame_at_a_time_and_refuses_a_gap(tmp_path):
    def frame(step, n, cols, rows):
        return ("ITEM: TIMESTEP\n%d\nITEM: NUMBER OF ENTRIES\n%d\nITEM: BOX BOUNDS pp pp ff\n0 1\n0 1\n0 1\n"
                "ITEM: ENTRIES %s\n%s" % (step, n, cols, "".join(r + "\n" for r in rows)))
    atoms = tmp_path / "a"
    pairs = tmp_path / "p"
    atoms.write_text(frame(0, 1, "id x", ["1 0.5"]) + frame(5, 1, "id x", ["1 0.6"]))
    pairs.write_text(frame(0, 0, "c1 c2", []) + frame(5, 1, "c1 c2", ["1 2"]))
    got = [(s, c, r.tolist(), p.tolist()) for s, c, r, p in D.lockstep(str(atoms), str(pairs))]
    assert got == [(0, ["id", "x"], [[1.0, 0.5]], []), (5, ["id", "x"], [[1.0, 0.6]], [[1.0, 2.0]])]
    pairs.write_text(frame(0, 0, "c1 c2", []))
    with pytest.raises(ValueError, match="ends before step 5"):
        list(D.lockstep(str(atoms), str(pairs)))
    pairs.write_text(frame(0, 0, "c1 c2", []) + frame(6, 0, "c1 c2", []))
    with pytest.raises(ValueError, match="step 6 where"):
        list(D.lockstep(str(atoms), str(pairs)))


def _atom_types(data):
    """Type of each atom of a LAMMPS data file (atom style sphere: id type diameter density x y z)."""
    atoms = data.split("Atoms")[1].strip().splitlines()[1:]
    return np.array([int(ln.split()[1]) for ln in atoms if ln.strip()])


def test_velocity_drive_frees_the_innermost_bottom_layer_in_front_of_the_wall(tmp_path, cases_dir):
    """SCHEMA.md §1: the velocity drive frees one layer (type 3, integrated with the free type 1); the
    fixed layer below it (type 2, with the top) is the wall, and its pairs with the source are kept."""
    facts, deck, data = _render(tmp_path, cases_dir, "crystal_small_velocity.toml")
    types = _atom_types(data)
    per_layer = 640 // 40
    assert len(types) == 640 and np.count_nonzero(types == 3) == per_layer          # one layer
    assert np.count_nonzero(types == 2) == 3 * per_layer                             # the wall and the 2 top layers
    assert "exclude type 2 2\n" in deck and "exclude type 2 3" not in deck and "exclude type 3 3" not in deck
    assert "velocity        source set 0.0 0.0 0.01 units box" in deck
    assert "fix             integr free" in deck and "group           free type 1 3" in deck
