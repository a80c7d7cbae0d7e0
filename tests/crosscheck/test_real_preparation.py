"""Real runs (issue 40 item 4, the CI size): one gas drawn by granwave (`[random] stop_at = "gas"`), prepared at
1 MPa by granwave (`granwave packing`), YADE (PeriTriaxController) and LAMMPS (the servo scripted on fix deform,
crosscheck/xclib/preparation.py), 200 frictionless glass beads, Hertz; every packing measured by the one reader
(`granwave packing` of a file case). The full comparison (10 kPa, Agnolin & Roux's conditions, 3 seeds) is
bench/preparation_codes.py, its numbers in docs/validation.md. Measured 2026-11-29: both tests 31 s of CPU
(YADE's most of it), 124 s of wall time on the loaded 2-core machine (load 7-10).

    /usr/bin/python3 -m pytest tests/crosscheck/test_real_preparation.py
"""
import os
import shutil

import numpy as np
import pytest

from xclib import harness
from xclib import preparation as X

pytestmark = pytest.mark.realcodes

MAT = dict(X.GLASS, pressure=1e6)  # 1 MPa: kappa ~ 1800, ~5x fewer steps than A&R's 10 kPa (CI's time)
COUNT, SEED = 200, 3


def _granwave():
    gw = harness.find_granwave(None)
    if gw is None:
        pytest.skip("granwave not built")
    return gw


def test_the_reader_reads_granwave_gas_and_packing_as_granwave_wrote_them(tmp_path):
    """The gas round trip (dump written, imported as a file case): the same spheres; granwave's prepared packing
    read back meets granwave's own criteria (docs/random-packing.md step 6: pressure 1e-3, unbalanced 1e-3)."""
    gw = _granwave()
    work = str(tmp_path)
    X.make_gas(gw, work, MAT, COUNT, SEED, 0.0)
    lo, hi, c = X.read_dump(os.path.join(work, "gas.dump"))
    gas = X.measure(gw, os.path.join(work, "gas.dump"), MAT, 0.0, gas=True)
    phi = np.sum(4.0 / 3.0 * np.pi * c["radius"] ** 3) / np.prod(hi - lo)
    assert gas["particles"] == COUNT and gas["contacts"] == 0
    assert gas["solid_fraction"] == pytest.approx(0.3, rel=1e-12) and phi == pytest.approx(0.3, rel=1e-12)
    X.prepare_granwave(gw, work, MAT, COUNT, SEED, 0.0, 300)
    m = X.measure(gw, os.path.join(work, "granwave.dump"), MAT, 0.0)
    assert abs(m["pressure"] / MAT["pressure"] - 1.0) <= 1e-3 and m["unbalanced"] <= 1e-3, m


@pytest.mark.skipif(not (shutil.which("yade") and harness.RN.find_lammps()), reason="yade and lmp not both installed")
def test_three_controllers_prepare_the_same_gas(tmp_path):
    """Each code's controller stops by its own criterion; the one reader then requires of every packing:
    at the pressure (|p/P - 1| <= 5e-3 from the elastic normal forces: each controller aims at 1e-3); jammed
    as a frictionless packing at kappa ~ 1800 is (Phi in [0.62, 0.66] about random close packing 0.64 with
    200 spheres; z* in [6 (1 - 1/N_backbone), 7]: at least isostatic, 3 (N - 1) + 1 contacts, and below the
    z of a much more compressed packing); near rest (the largest net force <= 5e-2 of a mean contact force,
    E_kin/E_pot <= 1e-3: YADE's controller checks no kinetic energy, docs/validation.md); and each at the
    rest its own controller claims: granwave its recorded E_kin/E_pot <= 1e-8 and unbalanced <= 1e-3 (its
    packing carries no velocities), LAMMPS E_kin/E_pot <= 1e-7 read from its velocities (its servo stops at
    1e-8 of a closed-form E_pot), YADE the mean net force <= 2e-3 of the mean contact force (its
    unbalancedForce <= 1e-3 counts the dashpots' forces too)."""
    gw = _granwave()
    work = str(tmp_path)
    dt = X.time_step(MAT)
    X.make_gas(gw, work, MAT, COUNT, SEED, 0.0)
    runs = {"granwave": X.prepare_granwave(gw, work, MAT, COUNT, SEED, 0.0, 300),
            "yade": X.prepare_yade(work, MAT, 0.0, dt, 300, max_steps=400000),
            "lammps": X.prepare_lammps(harness.RN.find_lammps(), work, MAT, 0.0, dt, 300, max_steps=400000)}
    for code, r in runs.items():
        assert r["done"], (code, r)
        m = X.measure(gw, os.path.join(work, code + ".dump"), MAT, 0.0)
        assert m["particles"] == COUNT, code
        nb = COUNT - m["rattlers"]
        assert abs(m["pressure"] / MAT["pressure"] - 1.0) <= 5e-3, (code, m)
        assert 0.62 <= m["solid_fraction"] <= 0.66, (code, m)
        assert 6.0 * (1.0 - 1.0 / nb) <= m["coordination_backbone"] <= 7.0, (code, m)
        assert m["kinetic_ratio"] <= 1e-3 and m["unbalanced"] <= 5e-2, (code, m)
    g = X.measure(gw, os.path.join(work, "granwave.dump"), MAT, 0.0)
    assert runs["granwave"]["own"]["kinetic_ratio"] <= 1e-8 and g["unbalanced"] <= 1e-3, g
    assert X.measure(gw, os.path.join(work, "lammps.dump"), MAT, 0.0)["kinetic_ratio"] <= 1e-7
    assert X.measure(gw, os.path.join(work, "yade.dump"), MAT, 0.0)["unbalanced_mean"] <= 2e-3
