"""The LIGGGHTS deck renderer and dump reader (no LIGGGHTS needed)."""
import os

import numpy as np

import liggghts_case as L
from xclib import sysbuild
from xclib import traces as T


def _render(tmp_path, cases_dir, name):
    case, _ = T.load_case(os.path.join(cases_dir, name))
    sp = str(tmp_path / "sys.h5")
    sysbuild.build(case, sp)
    work = tmp_path / "w"
    work.mkdir()
    facts = L.render(case, T.read_system(sp), str(work))
    return facts, (work / "in.case").read_text(), (work / "data.system").read_text()


def test_chain_deck(tmp_path, cases_dir):
    facts, deck, data = _render(tmp_path, cases_dir, "chain_small.toml")
    assert facts["nsteps"] == 25000 and facts["every"] == 50
    assert "pair_style      gran model hertz tangential no_history" in deck
    assert "hard_particles  yes" in deck
    assert "primitive type 3 xplane" in deck and "store_force yes" in deck   # 2 bead materials + the wall's
    assert deck.count("mass") >= 41 and "set             atom 1 vx 0.443" in deck
    assert "youngsModulus peratomtype 193000000000.0 72400000000.0 115000000000.0" in deck
    assert "%.17g" in deck                                            # full-precision dumps
    assert "41 atoms" in data and "3 atom types" in data


def test_crystal_deck(tmp_path, cases_dir):
    facts, deck, data = _render(tmp_path, cases_dir, "crystal_small_damped.toml")
    # the fixture says normal_tension = "clip" (the convention YADE's damped law shares): limitForce on
    assert "hooke/stiffness tangential history absolute_damping on limitForce on" in deck
    # kt > 0: the pair dump carries the shear history (the converter's step force), full precision
    assert "compute         cpl all pair/gran/local id force history" in deck
    assert "c_cpl[9]" in deck and 'dpl format "' + " ".join(["%.17g"] * 9) + '"' in deck
    assert "gamman_abs peratomtypepair 3 " + " ".join(["0.1"] * 9) in deck
    assert "kn peratomtypepair 3 " + " ".join(["100000.0"] * 9) in deck
    assert "displace_atoms  source move 0.0 0.0 2.0000000000000002e-07 units box" in deck   # 1e-4 * d, exact
    assert deck.index("run             1") < deck.index("displace_atoms") < deck.index("fix             integr free")
    assert "boundary        p p f" in deck and "exclude type 2 2" in deck
    # with a spring: a contact that opens loses it (LIGGGHTS' surfacesClose needs a factor above 1)
    assert "neigh_modify    delay 0 contact_distance_factor 1.01 exclude type 2 2" in deck
    assert "640 atoms" in data
    # frictionless: six columns, no history, and the seed's "allow" (limitForce off)
    (tmp_path / "kt0").mkdir()
    facts, deck, data = _render(tmp_path / "kt0", cases_dir, "crystal_small.toml")
    assert "limitForce off" in deck and "history\n" not in deck and "c_cpl[7]" not in deck
    assert "contact_distance_factor" not in deck       # kt = 0: no spring to lose, the deck as before


def test_dump_reader_and_pair_dedup(tmp_path):
    p = tmp_path / "dump.pairs"
    p.write_text("ITEM: TIMESTEP\n5\nITEM: NUMBER OF ENTRIES\n3\nITEM: BOX BOUNDS pp pp ff\n0 1\n0 1\n0 1\n"
                 "ITEM: ENTRIES c_cpl[1] c_cpl[2] c_cpl[3] c_cpl[4] c_cpl[5] c_cpl[6]\n"
                 "1 2 0 1 0 0\n2 1 1 -1 0 0\n3 1 0 0 0 2\n")
    frames = list(L.read_dump(str(p)))
    assert frames[0][0] == 5 and frames[0][2].shape == (3, 6)
    i, j, f = L._pairs_on_first(frames[0][2])
    # (1,2) listed from both sides counts once; (3,1) is turned into (1,3) with the force on atom 1
    assert list(zip(i, j)) == [(0, 1), (0, 2)]
    assert np.allclose(f, [[1, 0, 0], [0, 0, -2]])
