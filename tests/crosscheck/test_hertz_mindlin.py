"""Hertz-Mindlin in the other codes (issue #14): parameter maps, deck renderers, convention records
(no YADE, LIGGGHTS or LAMMPS needed; the measurements are in test_real_crosscheck.py)."""
import math
import os
import sys

import numpy as np

import liggghts_case as L
from xclib import conventions as CV
from xclib import dumps as D
from xclib import hertz_mindlin as HM
from xclib import sysbuild
from xclib import traces as T

HERE = os.path.dirname(os.path.abspath(__file__))
sys.path.insert(0, os.path.join(os.path.dirname(os.path.dirname(HERE)), "lammps_inputs"))
import lammps_case as LM  # noqa: E402


def _system(tmp_path, cases_dir, name):
    case, _ = T.load_case(os.path.join(cases_dir, name))
    sp = str(tmp_path / (name + ".sys.h5"))
    sysbuild.build(case, sp)
    return case, T.read_system(sp)


def _deck(module, tmp_path, cases_dir, name):
    case, system = _system(tmp_path, cases_dir, name)
    work = tmp_path / (module.__name__ + name)
    work.mkdir()
    facts = module.render(case, system, str(work))
    return facts, (work / "in.case").read_text()


def test_like_sphere_moduli():
    # E* = E/(2(1 - nu^2)), G* = G/(2(2 - nu)), G = E/(2(1 + nu)): the brief's formulas
    assert math.isclose(HM.e_star(63e9, 0.23), 63e9 / (2 * (1 - 0.23 ** 2)), rel_tol=1e-15)
    assert math.isclose(HM.g_star(63e9, 0.23), 63e9 / (2 * 1.23) / (2 * 1.77), rel_tol=1e-15)


def test_restitution_of_the_law_against_the_closed_form():
    """The ODE's e against an independent formula: LIGGGHTS' e(beta) with its sqrt(5/6) (the map
    liggghts_restitution inverts it) gives the restitution of the velocity-independent Hertz dashpot
    2 zeta sqrt(m* k_n(delta)) with a pulling dashpot to 1e-10 at these zeta; clipping raises e."""
    assert HM.restitution(0.0, False) > 1 - 1e-9
    for zeta in (0.02, 0.1, 0.3):
        e = HM.restitution(zeta, False)
        assert abs(e - HM.liggghts_restitution(zeta)) < 1e-9
        assert HM.restitution(zeta, True) > e + 5e-4


def test_lammps_tsuji_map_inverts_the_polynomial():
    for zeta in (0.01, 0.1, 0.4):
        e = HM.lammps_tsuji_restitution(zeta)
        assert 0.0 < e < 1.0
        assert abs(HM.tsuji_alpha(e) - math.sqrt(6) * zeta) < 1e-14
    # alpha(1) = 3e-4, not 0: an undamped law is not a tsuji coefficient (the renderer uses velocity 0)
    assert HM.tsuji_alpha(1.0) > 1e-4
    assert "damping velocity" in HM.lammps_pair_coeff("* *", 63e9, 0.23, 0.5, 0.0, "displacement", False)


def test_liggghts_hertz_deck(tmp_path, cases_dir):
    facts, deck = _deck(L, tmp_path, cases_dir, "crystal_small_hm_s_damped.toml")
    assert "pair_style      gran model hertz tangential history tangential_damping off limitForce on" in deck
    assert "hard_particles  yes" in deck
    assert "youngsModulus peratomtype 63000000000.0 63000000000.0 63000000000.0" in deck
    e = HM.liggghts_restitution(0.1)
    assert "coefficientRestitution peratomtypepair 3 " + " ".join([repr(e)] * 9) in deck
    assert "coefficientFriction peratomtypepair 3 " + " ".join(["0.5"] * 9) in deck
    assert "id force history" in deck and "c_cpl[9]" in deck          # the shear history for the step force
    assert "kn peratomtypepair" not in deck
    facts, deck = _deck(L, tmp_path, cases_dir, "crystal_small_hm.toml")
    assert "tangential no_history tangential_damping off limitForce off" in deck
    assert "coefficientRestitution peratomtypepair 3 " + " ".join(["1.0"] * 9) in deck
    assert "c_cpl[7]" not in deck


def test_lammps_hertz_styles(tmp_path, cases_dir):
    # frictionless, damped: pair granular hertz/material, tsuji with the mapped e, limit_damping ("clip")
    facts, deck = _deck(LM, tmp_path, cases_dir, "crystal_small_hm_damped.toml")
    e = HM.lammps_tsuji_restitution(0.1)
    assert ("pair_coeff      * * hertz/material 63000000000.0 %r 0.23 tangential linear_nohistory 0 0 damping tsuji "
            "limit_damping" % e) in deck
    assert facts["clip"] and not facts["tangential"]
    # friction, undamped, "displacement": gran/hertz/history with Kn = 4/3 E*, Kt = 8 G*, arm a
    facts, deck = _deck(LM, tmp_path, cases_dir, "crystal_small_hm_s.toml")
    kn, kt = 4 / 3 * HM.e_star(63e9, 0.23), 8 * HM.g_star(63e9, 0.23)
    assert "pair_style      gran/hertz/history %r %r 0.0 0.0 0.5 0" % (kn, kt) in deck
    assert facts["conventions"]["lever_arm"] == "radius"
    assert facts["conventions"]["tangential_history"] == "displacement"
    assert "fx fy fz p1 p2 p3" in deck
    # friction with damping: pair granular mindlin, whose arm no granwave option runs
    facts, deck = _deck(LM, tmp_path, cases_dir, "crystal_small_hm_s_damped.toml")
    assert "tangential mindlin NULL 0.0 0.5 damping tsuji limit_damping" in deck
    assert facts["conventions"]["lever_arm"] == LM.MIXED_ARM


def test_dashpot_alignment_with_the_hertz_law():
    """dumps.dashpot_at_half_step with the law's normal_force: the step's normal force is the elastic
    (4/3) E* sqrt(R*) delta^3/2 plus 2 zeta sqrt(m* 2 E* sqrt(R* delta)) times the half-step approach rate."""
    es, zeta, a, m, dt = HM.e_star(63e9, 0.23), 0.1, 1e-3, 8e-6, 1e-8
    p = np.array([[0.0, 0.0, 0.0], [0.0, 0.0, 2 * a - 2e-6]])
    v = np.array([[0.0, 0.0, 0.01], [0.0, 0.0, -0.01]])
    f_atoms = np.array([[0.0, 0.0, -3.0], [0.0, 0.0, 3.0]])
    mobile = np.array([True, True])
    radius = np.array([a, a])
    # the dumped force on atom 1 from atom 0 (i = 1, j = 0), with some dashpot that saw v(t)
    f_pair = np.array([[0.0, 0.0, 5.0]])
    clip = D.dashpot_at_half_step(p, v, f_atoms, np.array([m, m]), mobile, dt, np.array([1]), np.array([0]), f_pair,
                                  radius, zeta, 1.0, 1.0, True,
                                  HM.normal_force({"youngs_modulus": 63e9, "poisson_ratio": 0.23, "damping_ratio": zeta}))
    vh = v - f_atoms / m * dt / 2
    rate = float(vh[0, 2] - vh[1, 2])                       # approach rate d(delta)/dt at the half step
    want = 4 / 3 * es * math.sqrt(a / 2) * 2e-6 ** 1.5 + 2 * zeta * math.sqrt(m / 2 * 2 * es * math.sqrt(a / 2 * 2e-6)) * rate
    assert math.isclose(clip[0, 2], want, rel_tol=1e-12)


def test_hertz_conventions_and_twins():
    case = {"case": {"model": "crystal"},
            "contact": {"law": "hertz_mindlin", "youngs_modulus": 63e9, "poisson_ratio": 0.23, "damping_ratio": 0.1,
                        "tangential": "mindlin", "tangential_history": "displacement", "lever_arm": "contact_point",
                        "normal_tension": "clip"}}
    gw = dict(contact_law="hertz_mindlin", lever_arm="contact_point", normal_tension="clip",
              tangential_history="displacement")
    yade = dict(gw, tangential_history="force")
    lmp = dict(gw, lever_arm=LM.MIXED_ARM)
    assert "tangential-history convention" in CV.difference(case, gw, yade)
    assert CV.difference(case, gw, dict(gw, contact_law="hertz_mindlin")) is None
    # YADE gets a twin with its history; LAMMPS' mixed arm is nothing granwave runs: no twin
    tw = CV.twins(case, {"granwave": gw, "yade": yade, "lammps": lmp})
    assert tw == [("granwave~yade", ["yade"], dict(lever_arm="contact_point", normal_tension="clip",
                                                   tangential_history="force"))]
    assert "lever-arm convention" in CV.difference(case, gw, lmp)
    # a trace of another law is never comparable, and never twinned
    lin = dict(gw, contact_law="linear")
    assert "contact-law convention" in CV.difference(case, gw, lin)
    assert CV.twins(case, {"granwave": gw, "liggghts": lin}) == []
    # frictionless: the history and the arm do not matter
    bare = {"case": {"model": "crystal"}, "contact": dict(case["contact"], tangential="none")}
    assert CV.difference(bare, gw, dict(yade, lever_arm=LM.MIXED_ARM)) is None


def test_damping_ratios_a_code_cannot_express_are_refused(tmp_path, cases_dir):
    """LAMMPS' tsuji reaches sqrt(6) zeta <= alpha(0) = 1.2728 (zeta <= 0.5196); LIGGGHTS' hertz zeta < 0.9129."""
    import pytest
    case, system = _system(tmp_path, cases_dir, "crystal_small_hm_damped.toml")
    case["contact"]["damping_ratio"] = 0.6
    (tmp_path / "l").mkdir()
    with pytest.raises(LM.Unsupported):
        LM.render(case, system, str(tmp_path / "l"))
    (tmp_path / "g").mkdir()
    L.render(case, system, str(tmp_path / "g"))            # 0.6 < 0.9129: LIGGGHTS runs it
    case["contact"]["damping_ratio"] = 0.95
    with pytest.raises(ValueError):
        HM.liggghts_restitution(0.95)
