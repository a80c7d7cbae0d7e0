"""crosscheck/probe_rolling.py on the installed codes: the rolling and torsion conventions that
liggghts_inputs/MAPPING.md ("Rolling and torsion resistance") quotes are measured, not assumed.

    /usr/bin/python3 -m pytest tests/crosscheck/test_probe_rolling.py -m realcodes

Two spheres (a_i = 1e-3 m, a_j = 1.5e-3 m, a' = 6e-4 m) at a held overlap with imposed spins; every
number below is a closed form of the code's own parameters, so the tolerances are round-off (1e-9).
"""
import math
import os
import shutil
import sys

import pytest

HERE = os.path.dirname(os.path.abspath(__file__))
sys.path.insert(0, os.path.join(os.path.dirname(os.path.dirname(HERE)), "crosscheck"))
import probe_rolling as P  # noqa: E402
import probe_rolling_decks as D  # noqa: E402
import probe_rolling_yade as Y  # noqa: E402
from xclib import runners as RN  # noqa: E402

pytestmark = pytest.mark.realcodes
TOL = 1e-9


def close(x, y, tol=TOL):
    return abs(x - y) <= tol * max(abs(y), 1e-30)


@pytest.mark.skipif(shutil.which("yade") is None, reason="yade not installed")
def test_yade_moment_laws():
    r = P.measure(["yade"], ["roll", "frame", "torsion", "mindlin_damped"])["yade"]
    p = Y.yade_params()
    # CohesionMoment: k_r = ks alphaKr a_i a_j per radian, limit etaRoll min(a_i, a_j) |f_n|, no dashpot
    assert close(r["roll"]["K"], p["KS"] * p["ALPHA_KR"] * D.A_I * D.A_J) and close(r["roll"]["K"], D.K_ANG)
    assert close(r["roll"]["plateau"], p["ETA_ROLL"] * min(D.A_I, D.A_J) * D.FN)
    assert abs(r["roll"]["unload_drop"]) < 1e-6 * D.M_LIM and close(r["roll"]["K_unload"], D.K_ANG)
    assert r["roll"]["kept"] == 0.0 and r["roll"]["antisymmetry"] < TOL
    # the moment turns with the pair, to first order in the step's rotation (|M| grows (w dt)^2/2 per step)
    f = r["frame"]
    assert f["frame_miss_rotated"] < 3e-4 and f["frame_miss_fixed"] > 0.4
    assert close(f["frame_norm"] - 1, (D.OMEGA_FRAME * D.DT) ** 2 / 2 * (D.FRAME_STEPS - 1), 1e-2)
    assert close(r["torsion"]["K"], D.K_O * D.A_RED ** 2) and close(r["torsion"]["plateau"], D.MU_O * D.FN * D.A_RED)
    # Mindlin: krot, limit eta (a_i + a_j)/2 |f_n| with the normal dashpot in f_n
    m = r["mindlin_damped"]
    assert close(m["K"], p["KROT"]) and m["fn_viscous"] > 0.5 * m["fn"]       # the dashpot dominates f_n here
    assert close(m["plateau"], p["ETA_MIN"] * (D.A_I + D.A_J) / 2 * m["fn"])


@pytest.mark.skipif(shutil.which("liggghts") is None, reason="liggghts not installed")
def test_liggghts_luding_rolling():
    r = P.measure(["liggghts"], ["roll", "roll_cdf", "damped", "frame", "torsion", "torsion_on", "damped_on",
                                 "combined_on"])["liggghts"]
    q = D.liggghts_params(True)
    c = q["gamma_t"] * q["coefficientRollingViscousDamping"] * 2 * math.sqrt(D.liggghts_inertia() * D.K_ANG)
    # kr = LoadingStiffness coeffRollingStiffness R*^2, limit mu_r |F_n| R* with the normal dashpot in F_n
    assert close(r["roll"]["K"], D.KN * D.liggghts_params(False)["coeffRollingStiffness"] * D.A_RED ** 2)
    assert close(r["roll"]["plateau"], D.M_LIM)
    assert close(r["damped"]["plateau"], D.MU_R * (D.FN + q["gamma_t"] * D.V_N) * D.A_RED)
    assert close(r["damped"]["dashpot"], c, 1e-6) and close(c, D.C_ROT)
    # on slip the history keeps the limited torque and drops the dashpot: unloading starts c w below (granwave 2 c w)
    assert close(r["damped"]["unload_drop"], D.C_ROT * D.W, 1e-6)
    # the history is a fixed vector: after the pair turns by phi it has a component -|M| sin(phi) along n
    assert close(r["frame"]["frame_n_component"], -math.sin(r["frame"]["frame_angle"]), 1e-6)
    # an opened contact keeps its rolling spring unless contact_distance_factor > 1
    assert close(r["roll"]["kept"], 1.0) and r["roll_cdf"]["kept"] == 0.0
    # torsion off: no torque about n; on: the same spring and limit, lumped with rolling, and no rolling dashpot
    assert r["torsion"]["K"] == 0.0
    assert close(r["torsion_on"]["K"], D.K_ANG) and close(r["torsion_on"]["plateau"], D.M_LIM)
    assert abs(r["damped_on"]["dashpot"]) < 1e-12 * D.C_ROT
    assert close(r["combined_on"]["plateau_norm"], D.M_LIM)


@pytest.mark.skipif(RN.find_lammps() is None, reason="LAMMPS (lmp) not installed")
def test_lammps_sds_rolling_and_twisting():
    r = P.measure(["lammps"], ["roll", "damped", "frame", "torsion", "torsion_stop", "torsion_set",
                                "marshall"])["lammps"]
    # rolling sds: k_roll R*^2 per radian, limit mu_roll Fn_tot R*, dashpot gamma_roll R*^2: granwave's law
    assert close(r["roll"]["K"], D.K_R * D.A_RED ** 2) and close(r["roll"]["plateau"], D.M_LIM)
    assert r["roll"]["kept"] == 0.0 and r["roll"]["antisymmetry"] < TOL
    d = r["damped"]
    assert close(d["plateau"], D.MU_R * (D.FN + D.GAMMA_N * D.V_N) * D.A_RED)
    assert close(d["dashpot"], D.C_ROT, 1e-6) and close(d["unload_drop"], 2 * D.C_ROT * D.W, 1e-6)
    assert r["frame"]["frame_miss_rotated"] < 1e-12
    # twisting sds: k_twist per radian, limit mu_twist (a length) Fn
    assert close(r["torsion"]["K"], D.K_O * D.A_RED ** 2) and close(r["torsion"]["plateau"], D.MU_O * D.FN * D.A_RED)
    # a twist spring at its limit loses everything when the twist rate is exactly 0 (sign(0) = 0)
    assert r["torsion_stop"]["after_stop"] == 0.0
    # in one run a reversed twist unloads with k; reversed by `set omega` between runs it jumps to the opposite limit
    # (the slip branch runs in the setup with the new rate's sign)
    assert close(r["torsion"]["first_B"], 1 - D.K_ANG * D.W * D.DT / D.M_LIM) and r["torsion_set"]["first_B"] == -1.0
    a = math.sqrt(D.A_RED * D.DELTA)
    assert close(r["marshall"]["K"], 0.5 * D.KN * a * a) and close(r["marshall"]["plateau"], 2 / 3 * a * 0.5 * D.FN)
