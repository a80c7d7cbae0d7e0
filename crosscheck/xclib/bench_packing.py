"""The benchmark's decks on a packing file (bench/side_by_side.py, case `disordered`): the numbers LAMMPS'
and LIGGGHTS' per-bin decks need, granwave's contact-list rule, the data file with each atom's z-bin, and
the position snapshots that count the contacts that open and close."""
from __future__ import annotations

import os

import numpy as np

from . import driver as DRV
from . import traces as T
from .codefacts import Unsupported

# granwave's Verlet list (src/crystal/dynamics.cpp, list_skin and the drift test): pairs closer than
# a_i + a_j + skin, skin = 0.1 x the packing's mean radius; rebuilt when a particle has moved more than
# skin/2 since the last build, tested every step. LAMMPS and LIGGGHTS: `neighbor SKIN bin` (granular
# pairs within r_i + r_j + skin) and `neigh_modify delay 0 every 1 check yes` (the same test each step).
SKIN_OVER_MEAN_RADIUS = 0.1


def deck_values(case: dict, system: dict) -> dict:
    """What both codes' per-bin decks need; Unsupported for anything but a packing file's P or S step
    under a law whose bench decks exist (refused, not approximated)."""
    c, ex, law, bad = DRV.bench_refusals(case)
    if case["case"]["model"] != "crystal" or str(system["attrs"].get("generator", "fcc")) != "file":
        bad.append("a packing file's system only (crystal.lattice = \"file\")")
    if bad:
        raise Unsupported("case %s cannot be rendered: %s" % (case["case"]["name"], "; ".join(bad)))
    lay = T.crystal_layout(system)
    f = DRV.run_facts(case, system)
    friction = law.tangential(c)
    a = system["attrs"]
    return dict(case_name=case["case"]["name"], dt=DRV.g(f["dt"]), nsteps=f["nsteps"], every=f["every"], law=law,
                skin=DRV.g(SKIN_OVER_MEAN_RADIUS * float(np.mean(system["radius"]))), l0=DRV.g(lay["l0"]),
                origin=DRV.g(float(a.get("bin_origin", 0.0))), nbins=lay["nlayers"], friction=friction,
                mu=c["mu_static"], excitation_line=DRV.excitation_line(ex, lay["d"]),
                integrator="nve/sphere" if friction else "nve", n=f["n"], contact=c, radius=system["radius"],
                snapshot_lines="# no position snapshots (a timed run)")


def snapshot_lines(code: str, every_steps: int) -> str:
    """A dump of id x y z at full precision every `every_steps` steps (step 0 included) into snap.txt:
    the contact sets the count compares (count_contacts)."""
    fmt = '"%d %.17g %.17g %.17g"'
    mod = ("dump_modify     snap sort id format line %s" % fmt if code == "lammps"
           else "dump_modify     snap sort id format %s" % fmt)
    return "dump            snap all custom %d snap.txt id x y z\n%s" % (every_steps, mod)


def write_deck(deck: str, case: dict, system: dict, workdir: str, title: str, v: dict, molecules: bool) -> dict:
    """in.case and data.system as the per-layer decks write them (DRV.write_layer_deck); with `molecules` a
    Molecules section holding each atom's z-bin + 1 (LAMMPS' `fix property/atom mol`, its chunks)."""
    facts = DRV.write_layer_deck(deck, case, system, workdir, title, v)
    if molecules:
        layer = np.asarray(system["layer"], int)
        with open(os.path.join(workdir, "data.system"), "a") as f:
            f.write("\nMolecules\n\n")
            f.write("".join("%d %d\n" % (k + 1, layer[k] + 1) for k in range(len(layer))))
    return facts
