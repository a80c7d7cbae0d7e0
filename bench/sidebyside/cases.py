"""The benchmark's cases and their decks. The decks are the drivers' (`render(..., output="layers")` of
lammps_inputs/lammps_case.py and liggghts_inputs/liggghts_case.py): per-layer output by each code,
no dumps."""
from __future__ import annotations

import os
import re
import sys

HERE = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
REPO = os.path.dirname(HERE)
for _d in ("crosscheck", "lammps_inputs", "liggghts_inputs"):
    sys.path.insert(0, os.path.join(REPO, _d))
import lammps_case  # noqa: E402
import liggghts_case  # noqa: E402
from xclib.codefacts import Unsupported  # noqa: E402

CODES = ("granwave", "lammps", "liggghts")
CODE_TITLES = {"lammps": "LAMMPS", "liggghts": "LIGGGHTS"}

# name -> (base case file, replacements in its text, analyze layer range or None for the default)
CASES = {
    "frictionless": ("data/cases/crystal_p.toml", {}, None),
    "friction": ("data/cases/crystal_kt10.toml", {}, None),
    "friction_radius": ("data/cases/crystal_kt10.toml", {"lever_arm": '"radius"'}, None),
    "long": ("data/cases/crystal_p.toml", {"cells": "[4, 4, 20000]", "t_end": "4e-5"}, "1:4"),
    # issue #41: the 320 000-particle crystal with the other laws of the table, 200 steps each
    "long_friction_radius": ("data/cases/crystal_kt10.toml",
                             {"lever_arm": '"radius"', "cells": "[4, 4, 20000]", "t_end": "4e-5"}, "1:4"),
    "long_hertz": ("data/cases/crystal_hertz.toml", {"cells": "[4, 4, 20000]", "dt_over_tc": ("dt", "1.7e-7"),
                                                     "t_end": "3.4e-5", "interval": "8.5e-7"}, "1:4"),
    "long_rolling": ("bench/cases/crystal_rolling.toml", {"cells": "[4, 4, 20000]", "t_end": "4e-5"}, "1:4"),
    # issue #14: Hertz normal + Mindlin tangential, the same 4 x 4 x 200 crystal (glass beads at
    # delta_0 = 1e-4 d), 6000 steps of dt = 1.7e-7 s (t_c/52), output every 5 steps as above
    "hertz": ("data/cases/crystal_hertz.toml",
              {"dt_over_tc": ("dt", "1.7e-7"), "t_end": "1.02e-3", "interval": "8.5e-7"}, None),
    # issue #28: friction_radius with Luding's rolling and torsion springs kr = ko = kt/2 (the case file says why)
    "rolling": ("bench/cases/crystal_rolling.toml", {}, None),
    # the same springs as LIGGGHTS' rolling_friction luding runs them: its contact-point arm, the radii's lever,
    # its torque history fixed in space, torsion lumped with rolling (ko = kr) and no limits
    "rolling_luding": ("bench/cases/crystal_rolling.toml", {"lever_arm": '"contact_point"', "mu_r": ("rolling_lever", '"radii"'),
                                                         "mu_o": ("rolling_history", '"fixed"')}, None),
    # the rolling cases with seed 002's S step (t_end of crystal_s.toml): the springs turn and carry the wave
    "rolling_s": ("bench/cases/crystal_rolling.toml", {"mode": '"S"', "t_end": "1.7e-3"}, None),
    "rolling_luding_s": ("bench/cases/crystal_rolling.toml", {"lever_arm": '"contact_point"', "mode": '"S"',
                                                           "t_end": "1.7e-3", "mu_r": ("rolling_lever", '"radii"'),
                                                           "mu_o": ("rolling_history", '"fixed"')}, None),
    # issue #41 item 3: a disordered polydisperse column of 20 000 glass beads LAMMPS made (bench/cases/
    # disordered_packing.lmp, cached: sidebyside/packing.py), Hertz-Mindlin mu = 0.5, a P step; 3032 steps
    # (radius arm: LAMMPS' gran/hertz/history); disordered_cp: the contact point, LIGGGHTS' arm
    "disordered": ("bench/cases/disordered.toml", {}, None),
    "disordered_cp": ("bench/cases/disordered.toml", {"lever_arm": '"contact_point"'}, None),
    # their small twins on the committed 3060-particle column data/packings/lammps_tall/packing_w5.dump (101
    # bins: 1764 steps, the front not yet at the top slab)
    "disordered_small": ("bench/cases/disordered.toml", {"t_end": "6e-5"}, None),
    "disordered_small_cp": ("bench/cases/disordered.toml", {"t_end": "6e-5", "lever_arm": '"contact_point"'}, None),
    # not a benchmark: the smoke case of tests/crosscheck/test_side_by_side.py (640 particles, 1300 steps)
    "small": ("data/cases/crystal40.toml", {}, None),
    # not a benchmark: its S twin with LIGGGHTS' luding springs (640 particles, 1300 steps; z/l0 5..25)
    "small_rolling_luding_s": ("bench/cases/crystal_rolling.toml", {
        "cells": "[4, 4, 40]", "lever_arm": '"contact_point"', "mode": '"S"', "t_end": "2.6e-4",
        "mu_r": ("rolling_lever", '"radii"'), "mu_o": ("rolling_history", '"fixed"')}, "5:25"),
}
DEFAULT_CASES = ("frictionless", "friction", "friction_radius", "hertz", "long")
# The codes that run the same physics as granwave in a case (default: all of CODES).
# rolling: LIGGGHTS' rolling_friction luding has no separate torsion and limits (its driver refuses them);
# rolling_luding: LAMMPS' sds turns its rolling history with the pair and takes a mixed tangential arm.
CASE_CODES = {"friction_radius": ("granwave", "lammps"), "rolling": ("granwave", "lammps"),
              "long_friction_radius": ("granwave", "lammps"), "long_rolling": ("granwave", "lammps"),
              "rolling_luding": ("granwave", "liggghts"), "rolling_s": ("granwave", "lammps"),
              "rolling_luding_s": ("granwave", "liggghts"), "small_rolling_luding_s": ("granwave", "liggghts"),
              "disordered": ("granwave", "lammps"), "disordered_small": ("granwave", "lammps"),
              "disordered_cp": ("granwave", "liggghts"), "disordered_small_cp": ("granwave", "liggghts")}


class BenchError(Exception):
    """Bad input or a missing code: exit 2 with this message."""


# The cases on a packing file (their decks: render_packing_layers of both drivers; sidebyside/packing.py).
PACKING_CASES = ("disordered", "disordered_cp", "disordered_small", "disordered_small_cp")


def case_text(name: str, packing: str | None = None) -> str:
    """The TOML text of a benchmark case: its base case file with the case's replacements (a packing
    case: packing.file = `packing`)."""
    base, repl, _ = CASES[name]
    with open(os.path.join(REPO, base)) as f:
        text = f.read()
    if name in PACKING_CASES:
        if not packing:
            raise BenchError("case %s needs its packing file" % name)
        text = text.replace('file = "PACKING"', 'file = "%s"' % os.path.abspath(packing))
    text = re.sub(r'(?m)^name = ".*"$', 'name = "bench_%s"' % name, text, count=1)
    for key, val in repl.items():
        new_key, val = val if isinstance(val, tuple) else (key, val)  # (key, value): the line takes another key
        text, n = re.subn(r"(?m)^%s = .*$" % re.escape(key), "%s = %s" % (new_key, val), text, count=1)
        if n != 1:
            raise BenchError("%s: no key %s to replace for case %s" % (base, key, name))
    return text


def _render(driver, case: dict, system: dict, workdir: str) -> dict:
    try:
        return driver.render(case, system, workdir, output="layers")
    except Unsupported as e:
        raise BenchError("side_by_side: %s" % e) from None


def _render_packing(driver, case: dict, system: dict, workdir: str, snapshots: int) -> dict:
    try:
        return driver.render_packing_layers(case, system, workdir, snapshots=snapshots)
    except Unsupported as e:
        raise BenchError("side_by_side: %s" % e) from None


def render_lammps(case: dict, system: dict, workdir: str, packing: bool = False, snapshots: int = 0) -> dict:
    """in.case and data.system of the LAMMPS run (lammps_case.render_layers; a packing case:
    render_packing_layers, with position snapshots every `snapshots` steps if > 0); BenchError beyond them."""
    if packing:
        return _render_packing(lammps_case, case, system, workdir, snapshots)
    return _render(lammps_case, case, system, workdir)


def render_liggghts(case: dict, system: dict, workdir: str, packing: bool = False, snapshots: int = 0) -> dict:
    """in.case and data.system of the LIGGGHTS run (liggghts_case.render_layers or render_packing_layers)."""
    if packing:
        return _render_packing(liggghts_case, case, system, workdir, snapshots)
    return _render(liggghts_case, case, system, workdir)
